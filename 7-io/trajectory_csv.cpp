#include "mbsopt/io/trajectory_csv.hpp"

#include "mbsopt/model/units.hpp"
#include "mbsopt/io/atomic_file.hpp"

namespace mbsopt {

void writeTrajectoryCsv(const std::string& path, const Model& model, const Trajectory& trajectory,
                        const Eigen::MatrixXd& sensors, long every) {
  writeAtomically(path, [&](std::ostream& out) {
    out.precision(17);
    out << withUnit("t", "s");  // each column "name [unit]", SI (trajectory_csv.hpp)
    for (std::size_t i = 0; i < model.coordinates().size(); ++i)
      out << ',' << withUnit(model.coordinates()[i].name, coordinateUnit(model, static_cast<int>(i)));
    for (const Sensor& s : model.sensors()) out << ',' << withUnit(s.name, sensorSiUnit(model, s));
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
