// `weld`: a cut that fixes two frames to each other (6 closure equations).
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType weldCut() {
  return {"weld", "frame_a and frame_b coincide, origins and axes (6 equations)", {"frame_a", "frame_b"},
          [](SectionEntry& c) {
            const FrameIndex a = c.frame("frame_a"), b = c.frame("frame_b");
            c.guarded([&] { c.model().addWeldCut(c.name(), a, b); });
          }};
}

}  // namespace mbsopt
