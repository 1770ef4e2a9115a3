// Writes a simulation to CSV: one row per time point (or every N-th), `t`, every coordinate, then
// every sensor, each number in SI units to 17 significant digits (it reads back to the bit). Each
// column's header is "name [unit]" (units.hpp): one file that says what it holds to any CSV reader,
// with no sidecar to lose (a relative angle is in rad here, as the trajectories hold it; the reports
// give it in degrees). The file appears only when complete (written to a temporary name, then renamed).
#pragma once

#include <string>

#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {

/// `sensors`: rows = time points, columns = model sensors (Trajectory::sensors). `every` ≥ 1: writes
/// time points 0, every, 2·every, … and always the last one.
void writeTrajectoryCsv(const std::string& path, const Model& model, const Trajectory& trajectory,
                        const Eigen::MatrixXd& sensors, long every = 1);

}  // namespace mbsopt
