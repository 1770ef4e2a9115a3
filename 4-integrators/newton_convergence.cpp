#include "mbsopt/integrators/newton_convergence.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mbsopt {

namespace {

double ratio(double value, double scale) {
  if (value == 0.0) return 0.0;
  return scale > 0.0 ? std::abs(value) / (std::numeric_limits<double>::epsilon() * scale)
                     : std::numeric_limits<double>::infinity();
}

}  // namespace

void frameReach(const Model& model, const Workspace<double>& ws, std::vector<double>& reach) {
  reach.assign(static_cast<std::size_t>(model.frameCount()), 0.0);
  // Elements are stored parents first: each is added after its entry frame exists.
  for (const KinematicElement& element : model.elements()) {
    const auto entry = static_cast<std::size_t>(element.entry), exit = static_cast<std::size_t>(element.exit);
    reach[exit] = reach[entry] + (ws.position[exit] - ws.position[entry]).lpNorm<1>();
  }
}

double closureRowScale(const Model& model, const CutJoint& cut, int row, const std::vector<double>& reach) {
  const auto [a, b] = cutFrames(cut.kind);
  const auto ia = static_cast<std::size_t>(a), ib = static_cast<std::size_t>(b);
  if (row < 3) return reach[ia] + reach[ib];
  return static_cast<double>(model.frames()[ia].depth) + static_cast<double>(model.frames()[ib].depth) + 1.0;
}

NewtonRoundoff::NewtonRoundoff(const Model& model)
    : reach_(static_cast<std::size_t>(model.frameCount()), 0.0),
      force_(reach_.size(), 0.0),
      moment_(reach_.size(), 0.0),
      factor_(std::max(kFactor, static_cast<double>(model.frameCount()))) {
  for (const Body& body : model.bodies())
    bodies_.push_back({model.value(body.mass), model.centreOfMass(body).norm(), model.inertia(body).cwiseAbs().sum()});
}

void NewtonRoundoff::setWrenchMagnitudes(const Model& model, const Workspace<double>& ws,
                                         const Eigen::VectorXd& lambda) {
  std::fill(force_.begin(), force_.end(), 0.0);
  std::fill(moment_.begin(), moment_.end(), 0.0);
  const double g = model.gravity().norm();
  for (std::size_t i = 0; i < bodies_.size(); ++i) {  // as addBodyWrenches, on magnitudes
    const auto k = static_cast<std::size_t>(model.bodies()[i].frame);
    const BodyMagnitudes& body = bodies_[i];
    const double c = body.centre_of_mass, w = ws.angular_velocity[k].norm();
    const double alpha = ws.angular_acceleration[k].norm();
    const double force = body.mass * (ws.acceleration[k].norm() + alpha * c + w * w * c + g);
    force_[k] += force;
    moment_[k] += body.inertia * (alpha + w * w) + (c + reach_[k]) * force;
  }
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {  // as addConstraintWrenches: λ on both frames
    const auto [a, b] = cutFrames(cut.kind);
    const int rows = equationCount(cut.kind);
    const double force = lambda.size() ? lambda.segment<3>(row).lpNorm<1>() : 0.0;
    const double torque = lambda.size() && rows > 3 ? lambda.segment(row + 3, rows - 3).lpNorm<1>() : 0.0;
    for (const FrameIndex f : {a, b}) {
      const auto k = static_cast<std::size_t>(f);
      force_[k] += force;
      moment_[k] += torque + reach_[k] * force;
    }
    row += rows;
  }
  const auto& elements = model.elements();
  for (std::size_t k = elements.size(); k-- > 0;) {  // as addElementResiduals
    const auto e = static_cast<std::size_t>(elements[k].entry), s = static_cast<std::size_t>(elements[k].exit);
    force_[e] += force_[s];
    moment_[e] += moment_[s] + (reach_[s] + reach_[e]) * force_[s];
  }
}

void NewtonRoundoff::measureScales(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& lambda) {
  frameReach(model, ws, reach_);
  setWrenchMagnitudes(model, ws, lambda);
}

double NewtonRoundoff::relativeResidual(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& r,
                                        const std::vector<int>& free, const Eigen::VectorXd& closure) const {
  double largest = 0.0;
  for (std::size_t j = 0; j < free.size(); ++j) {
    const auto element = static_cast<std::size_t>(model.coordinates()[static_cast<std::size_t>(free[j])].element);
    const auto exit = static_cast<std::size_t>(model.elements()[element].exit);
    const double scale =
        ws.motion_linear[element].norm() * force_[exit] + ws.motion_angular[element].norm() * moment_[exit];
    largest = std::max(largest, ratio(r[static_cast<Eigen::Index>(j)], scale));
  }
  if (closure.size() == 0) return largest;
  Eigen::Index row = 0;
  for (const CutJoint& cut : model.cuts()) {
    const int rows = equationCount(cut.kind);
    for (int k = 0; k < rows; ++k)
      largest = std::max(largest, ratio(closure[row + k], closureRowScale(model, cut, k, reach_)));
    row += rows;
  }
  return largest;
}

double NewtonRoundoff::closureRoundoff(const Model& model) const {
  double sum = 0.0;
  for (const CutJoint& cut : model.cuts())
    for (int k = 0; k < equationCount(cut.kind); ++k) {
      const double scale = closureRowScale(model, cut, k, reach_);
      sum += scale * scale;
    }
  return std::numeric_limits<double>::epsilon() * std::sqrt(sum);
}

}  // namespace mbsopt
