// `point`: one component of a point's position, velocity or acceleration.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType pointSensor() {
  return {"point",
          "the x, y or z `component` in the axes of `axes` (the ground by default) of the position, velocity or "
          "acceleration (`quantity`) of `point` of `frame` (its origin by default)",
          {"frame", "point", "quantity", "axes", "component"}, [](SectionEntry& s) {
            const FrameIndex f = s.frame("frame");
            const Eigen::Vector3d point = s.map().vector("point", Eigen::Vector3d::Zero());
            const Derivative d = readDerivative(s.map());
            const FrameIndex axes = s.map().has("axes") ? s.frame("axes") : Model::ground;
            const std::string c = s.map().choice("component", {"x", "y", "z"});
            s.guarded([&] { s.model().addSensor(s.name(), PointSensor{f, point, d, axes, c[0] - 'x'}); });
          }};
}

}  // namespace mbsopt
