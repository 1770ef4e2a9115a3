// `curve_slider`: a cut that keeps a frame on a track, its arc length a coordinate named like the cut.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType curveSliderCut() {
  return {"curve_slider",
          "`frame` rides `track` of `base` (the ground by default), its arc length a coordinate named like the cut "
          "(q0 [m], v0 [m/s]); orientation follow_track or translate (3 or 6 equations)",
          {"frame", "base", "track", "orientation", "q0", "v0"}, [](SectionEntry& c) {
            const FrameIndex a = c.frame("frame");
            const FrameIndex base = c.map().has("base") ? c.frame("base") : Model::ground;
            const TrackIndex t = c.track("track");
            const SliderOrientation o = readSliderOrientation(c.map());
            c.guarded([&] { c.model().addCurveSliderCut(c.name(), a, base, t, o); });
            c.initialValues(c.name(), false);
          }};
}

}  // namespace mbsopt
