#include "python/evaluation_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <optional>

#include "python/conversions.hpp"

namespace py = pybind11;

namespace mbsopt {

void bindEvaluation(py::module_& m) {
  py::class_<PythonEvaluation>(m, "Evaluation",
                               "A design problem at one point: b_{k+1}, the cost's own functional, the transcribed "
                               "constraints (each <= 0, equalities = 0) and, when asked for, their gradients with "
                               "respect to x = value / scale.")
      .def_readonly("variables", &PythonEvaluation::variables,
                    "the columns of the gradients: the design variables' parameters, then b_{k+1}")
      .def_readonly("scales", &PythonEvaluation::scales, "value = x * scale, per variable")
      .def_property_readonly("cost", [](const PythonEvaluation& e) { return e.values.cost; }, "b_{k+1}")
      .def_property_readonly("cost_functional", [](const PythonEvaluation& e) { return e.values.reported_cost; },
                             "the cost sensor's own functional (SI)")
      .def_readonly("constraint_names", &PythonEvaluation::constraint_names, "the rows of constraints")
      .def_property_readonly("constraints", [](const PythonEvaluation& e) { return array(e.values.constraints); })
      .def_readonly("outside_bounds", &PythonEvaluation::outside_bounds,
                    "the design values outside their bounds that outside_bounds=True let through")
      .def_property_readonly("cost_gradient", [](const PythonEvaluation& e) -> std::optional<py::array_t<double>> {
        if (!e.gradients) return std::nullopt;
        return array(e.values.cost_gradient);
      }, "d cost / dx, None unless gradients were asked for")
      .def_property_readonly("constraint_jacobian", [](const PythonEvaluation& e) -> std::optional<py::array_t<double>> {
        if (!e.gradients) return std::nullopt;
        return array(e.values.constraint_jacobian);
      }, "constraints × variables, d g / dx; None unless gradients were asked for")
      .def("__repr__", [](const PythonEvaluation& e) {
        return "<mbsopt.Evaluation cost " + py::str(py::float_(e.values.cost)).cast<std::string>() + ", cost_functional " +
               py::str(py::float_(e.values.reported_cost)).cast<std::string>() + ", " +
               std::to_string(e.values.constraints.size()) + " constraints" + (e.gradients ? ", with gradients>" : ">");
      });
}

}  // namespace mbsopt
