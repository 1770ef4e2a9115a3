// `spherical`: a cut that makes the origins of two frames coincide (3 closure equations).
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType sphericalCut() {
  return {"spherical", "the origins of frame_a and frame_b coincide (3 equations)", {"frame_a", "frame_b"},
          [](SectionEntry& c) {
            const FrameIndex a = c.frame("frame_a"), b = c.frame("frame_b");
            c.guarded([&] { c.model().addSphericalCut(c.name(), a, b); });
          }};
}

}  // namespace mbsopt
