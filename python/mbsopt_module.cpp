// The Python module `mbsopt` (pybind11, numpy): scenes and design problems by name or file, as the
// command line takes them, simulated, evaluated with gradients by any method, and optimised by any
// optimizer, with the records the command line writes. C++ exceptions become Python's with the
// same messages (std::invalid_argument → ValueError, others → RuntimeError).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/optimization_run.hpp"
#include "app/scene_argument.hpp"
#include "dynamics/newmark.hpp"
#include "problems/design_nlp.hpp"
#include "problems/scene_file.hpp"
#include "sensitivity/gradient_method.hpp"

namespace py = pybind11;

namespace mbsopt {
namespace {

/// A scene's overrides from {name: value}: numbers as numbers, words (a setting such as
/// settings.closure) as text, checked as `--set NAME=VALUE` checks them.
std::vector<ParameterOverride> overridesOf(const SceneSource& source, const py::dict& values) {
  std::vector<ParameterOverride> out;
  for (const auto& [name, value] : values)
    out.push_back(parseOverride(source, py::str(name), py::str(value)));
  return out;
}

/// A matrix as a numpy array of its own (rows × columns, C order).
py::array_t<double> array(const Eigen::MatrixXd& m) {
  py::array_t<double> out({m.rows(), m.cols()});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index i = 0; i < m.rows(); ++i)
    for (Eigen::Index j = 0; j < m.cols(); ++j) view(i, j) = m(i, j);
  return out;
}

py::array_t<double> array(const Eigen::VectorXd& v) {
  py::array_t<double> out(v.size());
  std::copy(v.data(), v.data() + v.size(), out.mutable_data());
  return out;
}

/// JSON as Python objects, through the json module (the records the command line writes).
py::object pythonOf(const nlohmann::json& json) { return py::module_::import("json").attr("loads")(json.dump()); }

py::dict simulate(const std::string& scene, const py::dict& set) {
  const SceneSource source = resolveScene(scene);
  const LoadedScene loaded = loadScene(source, overridesOf(source, set));
  const Scene& s = loaded.scene;
  const Trajectory t = NewmarkIntegrator(s.model, s.settings).simulate(s.q0, s.v0);
  std::vector<std::string> coordinates, sensors;
  for (const Coordinate& c : s.model.coordinates()) coordinates.push_back(c.name);
  for (const Sensor& sensor : s.model.sensors()) sensors.push_back(sensor.name);
  py::dict out;
  out["time"] = array(t.time);
  out["coordinates"] = coordinates;  // the columns of q, v and a
  out["q"] = array(Eigen::MatrixXd(t.q.transpose()));
  out["v"] = array(Eigen::MatrixXd(t.v.transpose()));
  out["a"] = array(Eigen::MatrixXd(t.a.transpose()));
  out["sensor_names"] = sensors;  // the columns of sensors
  out["sensors"] = array(t.sensors);
  out["newton_iterations"] = array(Eigen::VectorXd(t.newton_iterations.cast<double>()));
  return out;
}

py::dict parameters(const std::string& scene, const py::dict& set) {
  const SceneSource source = resolveScene(scene);
  const Model& model = loadScene(source, overridesOf(source, set)).scene.model;
  py::dict out;
  for (const std::string& name : model.parameterNames()) out[py::str(name)] = model.parameter(name);
  return out;
}

py::dict evaluate(const std::string& problem_name, const std::optional<std::vector<double>>& design,
                  std::optional<double> artificial, const std::string& gradient, const py::dict& set) {
  const SceneSource source = resolveScene(problem_name);
  DesignNlp nlp(loadDesignProblem(source, overridesOf(source, set)), gradient == "fd" ? "fd_central" : gradient);
  const DesignProblem& problem = nlp.problem();
  Eigen::VectorXd x = nlp.start();
  if (design) {
    if (design->size() != problem.design.variables.size())
      throw std::invalid_argument("evaluate: " + std::to_string(design->size()) + " design values for " +
                                  std::to_string(problem.design.variables.size()) + " variables");
    for (std::size_t i = 0; i < design->size(); ++i)
      x[static_cast<Eigen::Index>(i)] = (*design)[i] / problem.design.variables[i].scale;
  }
  if (artificial) x[x.size() - 1] = *artificial / problem.design.artificial.scale;
  NlpEvaluation e;
  nlp.evaluate(x, !gradient.empty(), e);
  std::vector<std::string> variables, constraints;
  for (const DesignVariable& v : problem.design.variables) variables.push_back(v.parameter);
  variables.push_back("b_{k+1}");
  for (Eigen::Index i = 0; i < e.constraints.size(); ++i) constraints.push_back(nlp.constraintName(i));
  py::dict out;
  out["variables"] = variables;  // the columns of the gradients: d/dx, x = value / scale
  out["scales"] = [&] {
    std::vector<double> s;
    for (const DesignVariable& v : problem.design.variables) s.push_back(v.scale);
    s.push_back(problem.design.artificial.scale);
    return s;
  }();
  out["cost"] = e.cost;  // b_{k+1}
  out["cost_functional"] = e.reported_cost;  // the cost sensor's own, SI
  out["constraint_names"] = constraints;
  out["constraints"] = array(e.constraints);
  if (!gradient.empty()) {
    out["cost_gradient"] = array(e.cost_gradient);
    out["constraint_jacobian"] = array(e.constraint_jacobian);
  }
  return out;
}

py::object optimize(const std::string& problem_name, const std::string& optimizer, const std::string& gradient,
                    const std::string& formulation, std::optional<double> epsilon, std::optional<double> budget,
                    int max_iter, const py::dict& settings, const py::dict& set, int jobs) {
  const SceneSource source = resolveScene(problem_name);
  const DesignProblem problem = loadDesignProblem(source, overridesOf(source, set));
  RunChoice choice;
  choice.optimizer = optimizer;
  choice.gradient = gradient;
  choice.formulation = formulation;
  choice.epsilon = epsilon;
  if (budget) choice.budget.simulation_equivalents = *budget;
  choice.max_iterations = max_iter;
  choice.gradient_jobs = jobs;
  for (const auto& [name, value] : settings)
    choice.settings.push_back(std::string(py::str(name)) + "=" + std::string(py::str(value)));
  OptimizationRun run;
  {
    const py::gil_scoped_release unlocked;  // a run takes seconds; other Python threads may go on
    run = runOptimization(problem, choice, {});
  }
  return pythonOf(toJson(run, source.path));
}

}  // namespace
}  // namespace mbsopt

PYBIND11_MODULE(mbsopt, m) {
  using namespace mbsopt;
  m.doc() = "mbsopt: simulation, exact design gradients and optimisation of multibody systems";
  m.attr("__version__") = MBSOPT_VERSION;
  m.def("simulate", &simulate, py::arg("scene"), py::arg("set") = py::dict(),
        "Simulates a scene (a built-in name or a YAML file) with its `set` overrides {name: value}: a dict "
        "with time, coordinates, q, v, a (rows = time points), sensor_names, sensors, newton_iterations.");
  m.def("parameters", &parameters, py::arg("scene"), py::arg("set") = py::dict(),
        "Every model parameter of a scene by its dotted name, {name: value} (SI).");
  m.def("gradient_methods", [] { return gradientMethodNames(); }, "The gradient methods' names.");
  m.def("optimizers", [] { return optimizerNames(); }, "The optimizers' names.");
  m.def("formulations", [] { return formulationNames(); }, "The formulations' names.");
  m.def("evaluate", &evaluate, py::arg("problem"), py::arg("design") = py::none(), py::arg("artificial") = py::none(),
        py::arg("gradient") = "adjoint", py::arg("set") = py::dict(),
        "A design problem at a design (SI values of its variables; default its start) and b_{k+1} (default its "
        "start): cost (b_{k+1}), cost_functional, the transcribed constraints (each ≤ 0, equalities = 0) and, "
        "unless gradient is '', their gradients by that method with respect to x = value / scale.");
  m.def("optimize", &optimize, py::arg("problem"), py::arg("optimizer") = "sdcc", py::arg("gradient") = "adjoint",
        py::arg("formulation") = "", py::arg("epsilon") = py::none(), py::arg("budget") = py::none(),
        py::arg("max_iter") = 100, py::arg("settings") = py::dict(), py::arg("set") = py::dict(), py::arg("jobs") = 1,
        "Runs an optimizer on a design problem: the record `mbsopt optimize --json` writes, as a dict (status, "
        "message, design, responses, constraints, cost_functional, history, …). formulation '' is the "
        "problem's own; budget in simulation-equivalents; settings {name: value} are the optimizer's own.");
}
