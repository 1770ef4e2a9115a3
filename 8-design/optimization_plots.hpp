// The plots of optimisation runs: the design variables against iterations, and the convergence of
// cost and violation (the paper's figures 7 and 8 and their log-scale companions).
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/io/gnuplot.hpp"
#include "mbsopt/design/optimization_run.hpp"

namespace mbsopt {

/// The design variables (SI) against iterations on a logarithmic axis, one curve per variable
/// (the paper's figure 7).
PlotPanel designPanel(const OptimizationRun& run);

/// How close a convergence plot draws a cost that equals the best, relative to the best.
inline constexpr double kDistanceFloor = 1e-10;
/// |cost − best|, at least kDistanceFloor |best|: a cost's distance on a logarithmic axis, where the
/// end of a convergence shows (the paper's figures draw the cost itself, on which it does not).
double distanceToBest(double cost, double best);

/// Two panels on logarithmic axes, the distance of the cost's own functional (OptimizationRun::
/// iterate_costs) to the best (distanceToBest: `reference` where given, else the least reported cost
/// of the feasible runs) and the max violation (zero drawn at 1e-12), against iterations or against
/// the budget's simulation-equivalents, one curve per (title, run), its reported point ringed in its
/// colour (the point the summary, the tables and the JSON give); distances above twice the farthest
/// start's are cut off.
std::vector<PlotPanel> convergencePanels(const std::vector<std::pair<std::string, const OptimizationRun*>>& runs,
                                         bool against_simulation_equivalents,
                                         double reference = std::numeric_limits<double>::quiet_NaN());

}  // namespace mbsopt
