// Seeded starting points for multi-start runs: a Latin hypercube in a box (McKay, Beckman and
// Conover 1979). Each variable's range is cut into `count` equal strata; every stratum of every
// variable holds exactly one point, at a uniformly random place in it, and the strata are paired
// across variables by independent random permutations. The same seed gives the same points on every
// machine and compiler (its own generator arithmetic, not std::uniform_*_distribution, whose
// algorithms the standard leaves to the library), so every optimizer is started from the same points.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace mbsopt {

/// `count` points in [lower, upper] (finite, lower ≤ upper, same sizes); throws
/// std::invalid_argument otherwise.
std::vector<Eigen::VectorXd> latinHypercube(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper, int count,
                                            std::uint64_t seed);

}  // namespace mbsopt
