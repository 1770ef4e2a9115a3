// `offset`: a fixed frame of its parent, translated and optionally turned by an angle about an axis
// (the angle a model parameter, NAME.rotation.angle).
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType offsetElement() {
  return {"offset", "a fixed frame of its parent: translation [m], optionally rotation {axis, angle [rad]}",
          {"translation", "rotation"}, [](ElementEntry& e) {
            const MapReader& map = e.map();
            const Eigen::Vector3d translation = map.vector("translation", Eigen::Vector3d::Zero());
            if (!map.has("rotation")) {
              e.guarded([&] { e.model().addOffset(e.name(), e.parent(), translation); });
              return;
            }
            const MapReader rotation(map.context(), map.node()["rotation"], map.what() + " rotation");
            rotation.allowKeys({"axis", "angle"});
            const Eigen::Vector3d axis = readAxis(rotation, "axis");
            const double angle = rotation.number("angle");
            e.guarded([&] { e.model().addOffset(e.name(), e.parent(), translation, axis, angle); });
          }};
}

}  // namespace mbsopt
