// `track_guidance`: a torsional spring and damper between a frame's heading and the track's.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType trackGuidance() {
  return {"track_guidance",
          "a torsional spring and damper between the heading (x axis) of `frame` and the track's heading at the arc "
          "length of the curve slider `slider`",
          {"frame", "slider", "k", "c"}, [](SectionEntry& f) {
            const FrameIndex frame = f.frame("frame");
            const std::string slider = f.joint("slider");
            const double k = f.map().nonNegative("k", 0.0), c = f.map().nonNegative("c", 0.0);
            f.guarded([&] { f.model().addTrackGuidance(f.name(), frame, slider, k, c); });
          }};
}

}  // namespace mbsopt
