// How far one design gradient is from another, functional by functional: row 0 is the cost's
// gradient, row r the gradient of constraint r − 1 (the same rows and measure as `mbsopt gradcheck`).
#pragma once

#include <Eigen/Core>

#include "mbsopt/sensitivity/design_evaluation.hpp"

namespace mbsopt {

/// Row r of a gradient: the cost's (r = 0) or constraint r − 1's.
inline Eigen::VectorXd functionalGradient(const DesignGradient& g, Eigen::Index r) {
  return r == 0 ? g.cost : Eigen::VectorXd(g.constraints.row(r - 1).transpose());
}

/// max |g − reference| / max |reference| (absolute when the reference is zero).
inline double relativeDifference(const Eigen::VectorXd& g, const Eigen::VectorXd& reference) {
  const double scale = reference.size() ? reference.cwiseAbs().maxCoeff() : 0.0;
  return (g - reference).cwiseAbs().maxCoeff() / (scale > 0.0 ? scale : 1.0);
}

}  // namespace mbsopt
