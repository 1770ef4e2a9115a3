// `revolute`: a cut that joins two frames at their origins with two axes kept aligned (5 equations).
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType revoluteCut() {
  return {"revolute", "the origins of frame_a and frame_b coincide and axis_in_a stays along axis_in_b (5 equations)",
          {"frame_a", "frame_b", "axis_in_a", "axis_in_b"}, [](SectionEntry& c) {
            const FrameIndex a = c.frame("frame_a"), b = c.frame("frame_b");
            const Eigen::Vector3d axis_a = readAxis(c.map(), "axis_in_a"), axis_b = readAxis(c.map(), "axis_in_b");
            c.guarded([&] { c.model().addRevoluteCut(c.name(), a, b, axis_a, axis_b); });
          }};
}

}  // namespace mbsopt
