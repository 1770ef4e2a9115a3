// `revolute`: a rotation q [rad] about a unit axis of the parent frame.
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType revoluteElement() {
  return {"revolute", "a rotation q [rad] about `axis` of the parent frame; q0, v0 (deg allowed) or a driven `motion`; "
          "`armature`: a rotor inertia [kg·m²] on q̈",
          {"axis", "q0", "v0", "motion", "armature"}, [](ElementEntry& e) {
            const Eigen::Vector3d axis = readAxis(e.map(), "axis");
            e.guarded([&] { e.model().addRevolute(e.name(), e.parent(), axis); });
            if (e.map().has("armature"))  // a rotor inertia [kg·m²] on the coordinate, NAME.armature
              e.guarded([&] { e.model().addArmature(e.name(), e.map().nonNegative("armature", 0.0)); });
            e.motionOrInitialValues(e.name(), true);
          }};
}

}  // namespace mbsopt
