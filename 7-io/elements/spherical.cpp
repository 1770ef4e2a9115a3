// `spherical`: a ball joint, its exit frame NAME turned from the parent by three Cardan angles, the
// revolute joints NAME_x, NAME_y, NAME_z about the parent's x, then the turned y, then the turned z
// axis (R = Rx(q_x) Ry(q_y) Rz(q_z)), all through the parent's origin. Its coordinates are those
// three angles [rad]; at q_y = ±90° the x and z axes line up (gimbal lock) and the mass matrix of
// the chain is singular, so a motion must stay away from it (`ball` has no such lock; this one
// spins about its x axis without end).
#include "mbsopt/io/element_type.hpp"

namespace mbsopt {

ElementType sphericalElement() {
  return {"spherical",
          "a ball joint: three revolutes NAME_x, NAME_y, NAME_z about the parent's x, then the turned y and z axes "
          "(Cardan angles, singular at q_y = ±90°; see `ball`), exit frame NAME; q0, v0 [rad, rad/s] as [x, y, z]",
          {"q0", "v0"}, [](ElementEntry& e) {
            const Eigen::Vector3d q0 = e.map().vector("q0", Eigen::Vector3d::Zero());
            const Eigen::Vector3d v0 = e.map().vector("v0", Eigen::Vector3d::Zero());
            FrameIndex frame = e.parent();
            const char* const names[] = {"_x", "_y", "_z"};
            for (int i = 0; i < 3; ++i) {
              const std::string joint = e.name() + names[i];
              e.claimName(joint);
              e.guarded([&] { frame = e.model().addRevolute(joint, frame, Eigen::Vector3d::Unit(i)); });
              e.initialValues(joint, q0[i], v0[i]);
            }
            e.guarded([&] { e.model().addOffset(e.name(), frame, Eigen::Vector3d::Zero()); });
          }};
}

}  // namespace mbsopt
