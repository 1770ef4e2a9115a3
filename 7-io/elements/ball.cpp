// `ball`: a ball joint in a rotation vector, its exit frame NAME turned from the parent by
// exp([φ]×) about the parent's origin (Model::addBallJoint), with coordinates NAME_x, NAME_y, NAME_z,
// the components of φ in the parent's axes [rad]. No quarter turn locks it, as one locks the Cardan
// angles of `spherical`; its chart ends where |φ| reaches 1.8π, which a motion that spins the
// joint about one axis reaches after nine tenths of a turn, and `spherical` about its x axis never.
#include <array>
#include <string>

#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType ballElement() {
  return {"ball",
          "a ball joint in a rotation vector φ (coordinates NAME_x, NAME_y, NAME_z, in the parent's axes), exit "
          "frame NAME turned by exp([φ]×): no gimbal lock, |φ| < 1.8π; q0, v0 [rad, rad/s] as [x, y, z]",
          {"q0", "v0"}, [](ElementEntry& e) {
            const Eigen::Vector3d q0 = e.map().vector("q0", Eigen::Vector3d::Zero());
            const Eigen::Vector3d v0 = e.map().vector("v0", Eigen::Vector3d::Zero());
            const std::array<std::string, 3> names{e.name() + "_x", e.name() + "_y", e.name() + "_z"};
            for (const std::string& name : names) e.claimName(name);
            FrameIndex frame = e.parent();
            e.guarded([&] { frame = e.model().addBallJoint(names, frame); });
            for (std::size_t i = 0; i < 3; ++i) e.initialValues(names[i], q0[static_cast<Eigen::Index>(i)], v0[static_cast<Eigen::Index>(i)]);
            e.guarded([&] { e.model().addOffset(e.name(), frame, Eigen::Vector3d::Zero()); });
          }};
}

}  // namespace mbsopt
