// `prismatic`: a translation q [m] along a unit axis of the parent frame.
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType prismaticElement() {
  return {"prismatic", "a translation q [m] along `axis` of the parent frame; q0, v0 or a driven `motion`",
          {"axis", "q0", "v0", "motion"}, [](ElementEntry& e) {
            const Eigen::Vector3d axis = readAxis(e.map(), "axis");
            e.guarded([&] { e.model().addPrismatic(e.name(), e.parent(), axis); });
            e.motionOrInitialValues(e.name(), false);
          }};
}

}  // namespace mbsopt
