#include "app/csv_output.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>


namespace mbsopt {

void writeTrajectoryCsv(const std::string& path, const Model& model, const Trajectory& trajectory,
                        const Eigen::MatrixXd& sensors) {
  const std::string partial = path + ".partial";
  {
    std::ofstream out(partial);
    if (!out) throw std::runtime_error("cannot write '" + partial + "': " + std::strerror(errno));
    out.precision(17);
    out << 't';
    for (const Coordinate& c : model.coordinates()) out << ',' << c.name;
    for (const Sensor& s : model.sensors()) out << ',' << s.name;
    out << '\n';
    for (Eigen::Index k = 0; k < trajectory.time.size(); ++k) {
      out << trajectory.time[k];
      for (Eigen::Index i = 0; i < trajectory.q.rows(); ++i) out << ',' << trajectory.q(i, k);
      for (Eigen::Index s = 0; s < sensors.cols(); ++s) out << ',' << sensors(k, s);
      out << '\n';
    }
    if (!out.flush()) {
      std::remove(partial.c_str());
      throw std::runtime_error("writing '" + path + "' failed");
    }
  }
  std::error_code error;
  std::filesystem::rename(partial, path, error);
  if (error) {
    std::remove(partial.c_str());
    throw std::runtime_error("cannot replace '" + path + "': " + error.message());
  }
}

}  // namespace mbsopt
