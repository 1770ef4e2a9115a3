#include "app/csv_output.hpp"

#include "app/atomic_file.hpp"

namespace mbsopt {

void writeTrajectoryCsv(const std::string& path, const Model& model, const Trajectory& trajectory,
                        const Eigen::MatrixXd& sensors, long every) {
  writeAtomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << 't';
    for (const Coordinate& c : model.coordinates()) out << ',' << c.name;
    for (const Sensor& s : model.sensors()) out << ',' << s.name;
    out << '\n';
    const Eigen::Index last = trajectory.time.size() - 1;
    for (Eigen::Index k = 0; k <= last; ++k) {
      if (k % every != 0 && k != last) continue;
      out << trajectory.time[k];
      for (Eigen::Index i = 0; i < trajectory.q.rows(); ++i) out << ',' << trajectory.q(i, k);
      for (Eigen::Index s = 0; s < sensors.cols(); ++s) out << ',' << sensors(k, s);
      out << '\n';
    }
  });
}

}  // namespace mbsopt
