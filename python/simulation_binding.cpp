#include "python/simulation_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "python/conversions.hpp"

namespace py = pybind11;

namespace mbsopt {
namespace {

const Trajectory& trajectoryOf(const PythonSimulation& s) { return s.integration.run.trajectory; }

/// The estimated errors of a run, without its trajectory: a row per time point.
struct PythonErrorEstimate {
  Eigen::MatrixXd q, v, sensors;
  std::optional<double> round_off_floor;
};

/// Column `name` of the sensors; ValueError naming the sensors there are otherwise.
py::array_t<double> sensorColumn(const PythonSimulation& s, const std::string& name) {
  const auto found = std::find(s.sensor_names.begin(), s.sensor_names.end(), name);
  if (found == s.sensor_names.end()) {
    std::string known;
    for (const std::string& n : s.sensor_names) known += (known.empty() ? "" : ", ") + n;
    throw std::invalid_argument("no sensor '" + name + "' in this scene (its sensors: " + (known.empty() ? "none" : known) + ")");
  }
  return array(Eigen::VectorXd(trajectoryOf(s).sensors.col(found - s.sensor_names.begin())));
}

}  // namespace

void bindSimulation(py::module_& m) {
  py::class_<PythonErrorEstimate>(m, "ErrorEstimate",
                                  "The estimated global error of a run (the result minus the exact value), in the "
                                  "shapes of Simulation.q, .v and .sensors.")
      .def_property_readonly("q", [](const PythonErrorEstimate& e) { return array(e.q); }, "in q's units")
      .def_property_readonly("v", [](const PythonErrorEstimate& e) { return array(e.v); }, "in v's units")
      .def_property_readonly("sensors", [](const PythonErrorEstimate& e) { return array(e.sensors); },
                             "in the sensors' units")
      .def_readonly("round_off_floor", &PythonErrorEstimate::round_off_floor,
                    "the largest round-off floor included in q where it was measured, else None");

  py::class_<PythonSimulation>(m, "Simulation",
                               "One simulation of a scene, as `mbsopt simulate` runs it: the time points and, a row "
                               "per time point, q, v, a and the sensors (SI).")
      .def_property_readonly("time", [](const PythonSimulation& s) { return array(trajectoryOf(s).time); }, "[s]")
      .def_readonly("coordinates", &PythonSimulation::coordinates, "the columns of q, v and a")
      .def_readonly("coordinate_units", &PythonSimulation::coordinate_units, "of q (v and a per s and per s²)")
      .def_property_readonly("q", [](const PythonSimulation& s) { return array(Eigen::MatrixXd(trajectoryOf(s).q.transpose())); })
      .def_property_readonly("v", [](const PythonSimulation& s) { return array(Eigen::MatrixXd(trajectoryOf(s).v.transpose())); })
      .def_property_readonly("a", [](const PythonSimulation& s) { return array(Eigen::MatrixXd(trajectoryOf(s).a.transpose())); })
      .def_readonly("sensor_names", &PythonSimulation::sensor_names, "the columns of sensors")
      .def_readonly("sensor_units", &PythonSimulation::sensor_units, "SI")
      .def_property_readonly("sensors", [](const PythonSimulation& s) { return array(trajectoryOf(s).sensors); })
      .def("sensor", &sensorColumn, py::arg("name"), "One sensor's column of sensors, by its name.")
      .def_property_readonly("newton_iterations", [](const PythonSimulation& s) {
        return array(Eigen::VectorXd(trajectoryOf(s).newton_iterations.cast<double>()));
      }, "Newton's iterations of the step ending at each time point")
      .def_readonly("integrator", &PythonSimulation::integrator)
      .def_property_readonly("steps", [](const PythonSimulation& s) { return s.integration.run.steps; },
                             "the step of every Newmark run made [s]")
      .def_property_readonly("order", [](const PythonSimulation& s) { return s.integration.run.order; },
                             "the order of convergence of the result")
      .def_property_readonly("estimated_error", [](const PythonSimulation& s) -> std::optional<PythonErrorEstimate> {
        if (!s.integration.estimated) return std::nullopt;
        const EstimatedRun& r = s.integration.run;
        return PythonErrorEstimate{r.q_error.transpose(), r.v_error.transpose(), r.sensor_error, r.round_off_floor};
      }, "an ErrorEstimate where the run has one (accuracy, the extrapolation, or estimate_error=True), else None")
      .def("__repr__", [](const PythonSimulation& s) {
        const Trajectory& t = trajectoryOf(s);
        return "<mbsopt.Simulation " + s.integrator + ": " + std::to_string(t.time.size()) + " time points to " +
               py::str(py::float_(t.time.size() ? t.time[t.time.size() - 1] : 0.0)).cast<std::string>() + " s>";
      });
}

}  // namespace mbsopt
