// Writes a simulation to CSV: one row per time point, `t`, every coordinate, then every sensor.
// The file appears only when complete (written to a temporary name, then renamed).
#pragma once

#include <string>

#include "dynamics/newmark.hpp"

namespace mbsopt {

/// `sensors`: sensorHistory(model, trajectory).
void writeTrajectoryCsv(const std::string& path, const Model& model, const Trajectory& trajectory,
                        const Eigen::MatrixXd& sensors);

}  // namespace mbsopt
