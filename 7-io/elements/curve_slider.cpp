// `curve_slider`: the exit frame rides a track of the parent frame at arc length q [m], turning with
// the track's tangent or translating.
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType curveSliderElement() {
  return {"curve_slider",
          "rides `track` of the parent frame at arc length q [m], its frame following the track's tangent or "
          "translating (`orientation`); q0, v0 or a driven `motion`",
          {"track", "orientation", "q0", "v0", "motion"}, [](ElementEntry& e) {
            const TrackIndex track = e.track("track");
            const SliderOrientation orientation = readSliderOrientation(e.map());
            e.guarded([&] { e.model().addCurveSlider(e.name(), e.parent(), track, orientation); });
            e.motionOrInitialValues(e.name(), false);
          }};
}

}  // namespace mbsopt
