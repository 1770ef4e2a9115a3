// `prismatic`: a translation q [m] along a unit axis of the parent frame.
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType prismaticElement() {
  return {"prismatic", "a translation q [m] along `axis` of the parent frame; q0, v0 or a driven `motion`; `armature`: a "
          "rotor inertia [kg] on q̈",
          {"axis", "q0", "v0", "motion", "armature"}, [](ElementEntry& e) {
            const Eigen::Vector3d axis = readAxis(e.map(), "axis");
            e.guarded([&] { e.model().addPrismatic(e.name(), e.parent(), axis); });
            if (e.map().has("armature"))  // a rotor inertia [kg] on the coordinate, NAME.armature
              e.guarded([&] { e.model().addArmature(e.name(), e.map().nonNegative("armature", 0.0)); });
            e.motionOrInitialValues(e.name(), false);
          }};
}

}  // namespace mbsopt
