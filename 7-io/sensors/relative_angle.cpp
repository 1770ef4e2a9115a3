// `relative_angle`: the angle of frame_b relative to frame_a about an axis.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType relativeAngleSensor() {
  return {"relative_angle", "the angle [rad] of frame_b relative to frame_a about `axis` of frame_a",
          {"frame_a", "frame_b", "axis"}, [](SectionEntry& s) {
            const FrameIndex a = s.frame("frame_a"), b = s.frame("frame_b");
            const Eigen::Vector3d axis = readAxis(s.map(), "axis").normalized();
            s.guarded([&] { s.model().addSensor(s.name(), RelativeAngleSensor{a, b, axis}); });
          }};
}

}  // namespace mbsopt
