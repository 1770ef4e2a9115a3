// Library values as Python ones: Eigen matrices and vectors as numpy arrays of their own, JSON
// records as Python objects.
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <algorithm>
#include <nlohmann/json.hpp>
#include <vector>

namespace mbsopt {

/// A matrix as a numpy array of its own (rows × columns, C order).
inline pybind11::array_t<double> array(const Eigen::MatrixXd& m) {
  pybind11::array_t<double> out({m.rows(), m.cols()});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return out;
}

inline pybind11::array_t<double> array(const Eigen::VectorXd& v) {
  pybind11::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

inline pybind11::array_t<double> array(const std::vector<double>& v) {
  pybind11::array_t<double> out(static_cast<pybind11::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), out.mutable_data());
  return out;
}

/// JSON as Python objects, through the json module (the records the command line writes).
inline pybind11::object pythonOf(const nlohmann::json& json) {
  return pybind11::module_::import("json").attr("loads")(json.dump());
}

}  // namespace mbsopt
