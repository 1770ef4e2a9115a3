#include "mbsopt/algorithms/closure.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mbsopt/model/overloaded.hpp"

namespace mbsopt {

namespace {

/// Unit vector u fixed in frame a paired with unit vector w fixed in frame b: equation u·w = 0.
struct Orthogonality {
  FrameIndex frame_a;
  Eigen::Vector3d u_local;
  FrameIndex frame_b;
  Eigen::Vector3d w_local;
};

/// Visits the equations of one cut: a point coincidence (3 rows) then its orthogonalities (1 row each).
template <class OnCoincidence, class OnOrthogonality>
void forEachEquation(const CutKind& cut, OnCoincidence&& coincidence, OnOrthogonality&& orthogonality) {
  std::visit(Overloaded{[&](const SphericalCut& c) { coincidence(c.frame_a, c.frame_b); },
                        [&](const RevoluteCut& c) {
                          coincidence(c.frame_a, c.frame_b);
                          for (const Eigen::Vector3d& w : perpendicularPair(c.axis_in_b))
                            orthogonality(Orthogonality{c.frame_a, c.axis_in_a, c.frame_b, w});
                        },
                        [&](const WeldCut& c) {
                          coincidence(c.frame_a, c.frame_b);
                          const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
                          orthogonality(Orthogonality{c.frame_a, I.col(0), c.frame_b, I.col(1)});
                          orthogonality(Orthogonality{c.frame_a, I.col(1), c.frame_b, I.col(2)});
                          orthogonality(Orthogonality{c.frame_a, I.col(2), c.frame_b, I.col(0)});
                        }},
             cut);
}

}  // namespace

template <class Scalar>
void closureEquations(const Model& model, const Workspace<Scalar>& ws, Derivative level, VectorX<Scalar>& out) {
  out.resize(model.constraintCount());
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {
    forEachEquation(
        cut.kind,
        [&](FrameIndex a, FrameIndex b) {
          const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
          switch (level) {
            case Derivative::Position: out.template segment<3>(row) = ws.position[ia] - ws.position[ib]; break;
            case Derivative::Velocity: out.template segment<3>(row) = ws.velocity[ia] - ws.velocity[ib]; break;
            case Derivative::Acceleration:
              out.template segment<3>(row) = ws.acceleration[ia] - ws.acceleration[ib];
              break;
          }
          row += 3;
        },
        [&](const Orthogonality& o) {
          const auto ia = static_cast<std::size_t>(o.frame_a), ib = static_cast<std::size_t>(o.frame_b);
          const Vector3<Scalar> u = ws.rotation[ia] * o.u_local;
          const Vector3<Scalar> w = ws.rotation[ib] * o.w_local;
          if (level == Derivative::Position) {
            out[row++] = u.dot(w);
            return;
          }
          const Vector3<Scalar>& wa = ws.angular_velocity[ia];
          const Vector3<Scalar>& wb = ws.angular_velocity[ib];
          const Vector3<Scalar> du = wa.cross(u), dw = wb.cross(w);
          if (level == Derivative::Velocity) {
            out[row++] = du.dot(w) + u.dot(dw);
            return;
          }
          const Vector3<Scalar> ddu = ws.angular_acceleration[ia].cross(u) + wa.cross(du);
          const Vector3<Scalar> ddw = ws.angular_acceleration[ib].cross(w) + wb.cross(dw);
          out[row++] = ddu.dot(w) + Scalar(2) * du.dot(dw) + u.dot(ddw);
        });
  }
}

template <class Scalar>
void addConstraintWrenches(const Model& model, Workspace<Scalar>& ws, const VectorX<Scalar>& lambda) {
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {
    forEachEquation(
        cut.kind,
        [&](FrameIndex a, FrameIndex b) {
          const Vector3<Scalar> f = lambda.template segment<3>(row);
          addForce(model, ws, static_cast<std::size_t>(a), f);  // δ(p_a − p_b) = δp_a − δp_b
          addForce(model, ws, static_cast<std::size_t>(b), Vector3<Scalar>(-f));
          row += 3;
        },
        [&](const Orthogonality& o) {
          const auto ia = static_cast<std::size_t>(o.frame_a), ib = static_cast<std::size_t>(o.frame_b);
          const Vector3<Scalar> u = ws.rotation[ia] * o.u_local;
          const Vector3<Scalar> w = ws.rotation[ib] * o.w_local;
          const Vector3<Scalar> torque = lambda[row++] * u.cross(w);  // δ(u·w) = δθ_a·(u×w) − δθ_b·(u×w)
          addMoment(model, ws, ia, torque);
          addMoment(model, ws, ib, Vector3<Scalar>(-torque));
        });
  }
}

template <class Scalar>
void reactionCoefficients(const Model& model, const Workspace<Scalar>& ws, const CutReactionSensor& sensor,
                          VectorX<Scalar>& c) {
  c.setZero(model.constraintCount());
  Eigen::Index row = 0;
  for (int k = 0; k < sensor.cut; ++k) row += equationCount(model.cuts()[static_cast<std::size_t>(k)].kind);
  const CutKind& cut = model.cuts()[static_cast<std::size_t>(sensor.cut)].kind;
  const Vector3<Scalar> axis = ws.rotation[static_cast<std::size_t>(cutFrameA(cut))].col(sensor.component);
  const bool force = sensor.quantity == ReactionQuantity::Force;
  // addConstraintWrenches adds λ to the wrench frame b must transmit when the rows say −λ: the cut
  // applies +λ_p and +λ_r u_r × w_r to frame b.
  forEachEquation(
      cut,
      [&](FrameIndex, FrameIndex) {
        if (force) c.template segment<3>(row) = axis;
        row += 3;
      },
      [&](const Orthogonality& o) {
        const Vector3<Scalar> u = ws.rotation[static_cast<std::size_t>(o.frame_a)] * o.u_local;
        const Vector3<Scalar> w = ws.rotation[static_cast<std::size_t>(o.frame_b)] * o.w_local;
        if (!force) c[row] = axis.dot(u.cross(w));
        ++row;
      });
}

void checkWeldOrientations(const Model& model, const Workspace<double>& ws) {
  for (const CutJoint& cut : model.cuts()) {
    const auto* weld = std::get_if<WeldCut>(&cut.kind);
    if (!weld) continue;
    const double trace = (ws.rotation[static_cast<std::size_t>(weld->frame_a)].transpose() *
                          ws.rotation[static_cast<std::size_t>(weld->frame_b)])
                             .trace();
    if (trace <= 1.0) {
      const double angle = std::acos(std::clamp(0.5 * (trace - 1.0), -1.0, 1.0)) * 180.0 / 3.14159265358979323846;
      throw std::invalid_argument("the frames of the weld cut '" + cut.name + "' are turned by " +
                                  std::to_string(angle) +
                                  "° from each other: its equations hold there too, but the frames do not coincide; "
                                  "start from a configuration closer to the intended one");
    }
  }
}

template void closureEquations<double>(const Model&, const Workspace<double>&, Derivative, VectorX<double>&);
template void closureEquations<AdScalar>(const Model&, const Workspace<AdScalar>&, Derivative, VectorX<AdScalar>&);
template void reactionCoefficients<double>(const Model&, const Workspace<double>&, const CutReactionSensor&,
                                           VectorX<double>&);
template void reactionCoefficients<AdScalar>(const Model&, const Workspace<AdScalar>&, const CutReactionSensor&,
                                             VectorX<AdScalar>&);
template void addConstraintWrenches<double>(const Model&, Workspace<double>&, const VectorX<double>&);
template void addConstraintWrenches<AdScalar>(const Model&, Workspace<AdScalar>&, const VectorX<AdScalar>&);

}  // namespace mbsopt
