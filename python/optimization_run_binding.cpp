#include "python/optimization_run_binding.hpp"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <cmath>
#include <limits>
#include <map>
#include <vector>

#include "mbsopt/design/run_record.hpp"
#include "python/conversions.hpp"

namespace py = pybind11;

namespace mbsopt {
namespace {

/// The run's history, one entry per record, as numpy arrays: NaN where the optimizer did not say
/// which point a record was (its cost functional, its design).
struct PythonHistory {
  std::vector<int> iteration;
  std::vector<long> simulations, gradient_evaluations;
  Eigen::VectorXd cost, max_violation, step, simulation_equivalents, cost_functional;
  Eigen::MatrixXd design;  ///< records × variables, SI
};

PythonHistory historyOf(const OptimizationRun& run) {
  const std::vector<IterationRecord>& records = run.result.history;
  const auto n = static_cast<Eigen::Index>(records.size());
  PythonHistory h;
  h.cost.resize(n), h.max_violation.resize(n), h.step.resize(n), h.simulation_equivalents.resize(n);
  h.cost_functional.resize(n);
  h.design.setConstant(n, static_cast<Eigen::Index>(run.variables.size()), std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index k = 0; k < n; ++k) {
    const IterationRecord& r = records[static_cast<std::size_t>(k)];
    h.iteration.push_back(r.iteration);
    h.simulations.push_back(r.value_evaluations);
    h.gradient_evaluations.push_back(r.gradient_evaluations);
    h.cost[k] = r.cost;
    h.max_violation[k] = r.max_violation;
    h.step[k] = r.step;
    h.simulation_equivalents[k] = r.simulation_equivalents;
    h.cost_functional[k] = run.iterate_costs[static_cast<std::size_t>(k)];
    const std::vector<double>& design = run.iterate_designs[static_cast<std::size_t>(k)];
    for (std::size_t i = 0; i < design.size(); ++i) h.design(k, static_cast<Eigen::Index>(i)) = design[i];
  }
  return h;
}

std::map<std::string, double> responsesOf(const OptimizationRun& run) {
  std::map<std::string, double> out;
  for (const auto& [key, value] : run.responses.items()) out[key] = value.get<double>();
  return out;
}

}  // namespace

void bindOptimizationRun(py::module_& m) {
  py::enum_<OptimizerStatus>(m, "Status", "How an optimizer ended (the record's `status`).")
      .value("converged", OptimizerStatus::Converged, "its own stopping test passed at a feasible point")
      .value("max_iterations", OptimizerStatus::MaxIterations, "stopped by the iteration or evaluation budget")
      .value("failed", OptimizerStatus::Failed, "stopped elsewhere, or converged at an infeasible point")
      .value("unsupported", OptimizerStatus::Unsupported, "the optimizer cannot take this problem");
  py::enum_<ReportedPoint>(m, "ReportedPoint", "Which point a run reports (the record's `reported_iterate.point`).")
      .value("final", ReportedPoint::Final, "the optimizer's final point, converged, feasible and first-order optimal")
      .value("cheapest_feasible", ReportedPoint::CheapestFeasible, "the cheapest feasible iterate")
      .value("least_infeasible", ReportedPoint::LeastInfeasible, "no iterate is feasible: the closest one");

  py::class_<ConstraintVerdict>(m, "Verdict", "A constraint judged at the final design in its own units.")
      .def_readonly("name", &ConstraintVerdict::name)
      .def_readonly("unit", &ConstraintVerdict::unit, "of value, bound, excess and tolerance")
      .def_readonly("value", &ConstraintVerdict::value)
      .def_readonly("bound", &ConstraintVerdict::bound, "the bound, or the value an equality asks for")
      .def_readonly("equality", &ConstraintVerdict::equality)
      .def_readonly("excess", &ConstraintVerdict::excess, "how far the value lies beyond the bound (<= 0 inside)")
      .def_readonly("tolerance", &ConstraintVerdict::tolerance)
      .def_property_readonly("met", &ConstraintVerdict::met, "excess <= tolerance")
      .def("__repr__", [](const ConstraintVerdict& v) {
        return "<Verdict " + v.name + (v.equality ? " = " : " ≤ ") + py::str(py::float_(v.bound)).cast<std::string>() + " " +
               v.unit + ": " + py::str(py::float_(v.value)).cast<std::string>() + (v.met() ? ", met>" : ", not met>");
      });

  py::class_<PythonHistory>(m, "History", "One entry per record of the run, as numpy arrays (NaN where unknown).")
      .def_readonly("iteration", &PythonHistory::iteration)
      .def_property_readonly("cost", [](const PythonHistory& h) { return array(h.cost); }, "b_{k+1}")
      .def_property_readonly("max_violation", [](const PythonHistory& h) { return array(h.max_violation); })
      .def_property_readonly("step", [](const PythonHistory& h) { return array(h.step); }, "‖x_k − x_{k−1}‖∞")
      .def_readonly("simulations", &PythonHistory::simulations, "value evaluations so far")
      .def_readonly("gradient_evaluations", &PythonHistory::gradient_evaluations, "gradients so far")
      .def_property_readonly("simulation_equivalents", [](const PythonHistory& h) { return array(h.simulation_equivalents); },
                             "the budget spent so far")
      .def_property_readonly("cost_functional", [](const PythonHistory& h) { return array(h.cost_functional); },
                             "the cost's own functional at each record (its unit: OptimizationRun.cost_unit)")
      .def_property_readonly("design", [](const PythonHistory& h) { return array(h.design); },
                             "records × design variables, SI");

  py::class_<PythonRun>(m, "OptimizationRun",
                        "One optimizer run on a design problem: what ran, how it ended, the final design and its "
                        "verdicts, the history; record() is the JSON record `mbsopt optimize --json` writes.")
      .def_property_readonly("optimizer", [](const PythonRun& r) { return r.run.choice.optimizer; })
      .def_property_readonly("gradient", [](const PythonRun& r) { return r.run.choice.gradient; })
      .def_property_readonly("formulation", [](const PythonRun& r) { return r.run.choice.formulation; })
      .def_property_readonly("epsilon", [](const PythonRun& r) { return r.run.choice.epsilon.value_or(0.0); })
      .def_property_readonly("status", [](const PythonRun& r) { return r.run.result.status; })
      .def_property_readonly("message", [](const PythonRun& r) { return r.run.result.message; })
      .def_property_readonly("reported", [](const PythonRun& r) { return r.run.result.reported; },
                             "which point the run reports (ReportedPoint)")
      .def_property_readonly("variables", [](const PythonRun& r) {
        std::vector<std::string> names;
        for (const DesignVariable& v : r.run.variables) names.push_back(v.parameter);
        return names;
      }, "the design variables' parameters")
      .def_property_readonly("variable_units", [](const PythonRun& r) { return r.run.variable_units; })
      .def_property_readonly("start", [](const PythonRun& r) { return array(r.run.start); }, "the start, SI")
      .def_property_readonly("design", [](const PythonRun& r) { return array(r.run.design); }, "the reported design, SI")
      .def_property_readonly("cost", [](const PythonRun& r) { return r.run.result.cost; }, "b_{k+1} at the reported point")
      .def_property_readonly("cost_name", [](const PythonRun& r) { return r.run.cost_response; },
                             "the key in responses of the cost's own functional")
      .def_property_readonly("cost_unit", [](const PythonRun& r) { return r.run.cost_unit; })
      .def_property_readonly("cost_functional", [](const PythonRun& r) { return r.run.responses[r.run.cost_response].get<double>(); },
                             "the cost's own functional at the reported design")
      .def_property_readonly("initial_cost", [](const PythonRun& r) { return r.run.initial_cost; },
                             "the cost's own functional at the start")
      .def_property_readonly("feasible", [](const PythonRun& r) { return feasible(r.run); },
                             "every constraint met in its own units")
      .def_property_readonly("constraints", [](const PythonRun& r) { return r.run.verdicts; }, "a Verdict per constraint")
      .def_property_readonly("responses", [](const PythonRun& r) { return responsesOf(r.run); },
                             "max |y| of each sensor of the cost and constraints, and each exact functional they take")
      .def_property_readonly("response_units", [](const PythonRun& r) { return pythonOf(r.run.response_units); })
      .def_property_readonly("max_violation", [](const PythonRun& r) { return r.run.result.max_violation; })
      .def_property_readonly("iterations", [](const PythonRun& r) { return r.run.result.iterations; })
      .def_property_readonly("simulations", [](const PythonRun& r) { return r.run.result.value_evaluations; })
      .def_property_readonly("gradient_evaluations", [](const PythonRun& r) { return r.run.result.gradient_evaluations; })
      .def_property_readonly("simulation_equivalents", [](const PythonRun& r) { return r.run.result.simulation_equivalents; },
                             "the budget spent")
      .def_property_readonly("wall_time_s", [](const PythonRun& r) { return r.run.result.wall_time_s; })
      .def_property_readonly("history", [](const PythonRun& r) { return historyOf(r.run); })
      .def_property_readonly("time", [](const PythonRun& r) { return array(r.run.time); }, "[s], of the histories below")
      .def_property_readonly("initial_history", [](const PythonRun& r) { return array(r.run.initial_history); },
                             "the cost's sensor over time at the start (SI)")
      .def_property_readonly("final_history", [](const PythonRun& r) { return array(r.run.final_history); },
                             "the cost's sensor over time at the reported design (SI)")
      .def("record", [](const PythonRun& r) { return pythonOf(toJson(r.run, r.problem)); },
           "The documented JSON record of the run, as `mbsopt optimize --json` writes it, as Python objects.")
      .def("__repr__", [](const PythonRun& r) {
        return "<mbsopt.OptimizationRun " + runLabel(r.run.choice) + ": " + toString(r.run.result.status) + ", " +
               r.run.cost_response + " " + py::str(py::float_(r.run.responses[r.run.cost_response].get<double>())).cast<std::string>() +
               " " + r.run.cost_unit + (feasible(r.run) ? ", feasible>" : ", infeasible>");
      });
}

}  // namespace mbsopt
