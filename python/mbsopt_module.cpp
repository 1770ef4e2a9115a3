// The Python module `mbsopt` (pybind11, numpy): scenes and design problems (Scene, Problem), loaded
// once by name or file as the command line takes them, simulated, evaluated with gradients by any
// method, and optimised by any optimizer, with the records the command line writes. C++ exceptions become Python's with the
// same messages (std::invalid_argument → ValueError, others → RuntimeError).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/model/units.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/io/design_point.hpp"
#include "mbsopt/io/element_type.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/io/scene_lookup.hpp"
#include "mbsopt/design/design_nlp.hpp"
#include "mbsopt/design/optimization_run.hpp"
#include "mbsopt/design/provenance.hpp"
#include "mbsopt/design/run_record.hpp"
#include "python/conversions.hpp"
#include "python/evaluation_binding.hpp"
#include "python/optimization_run_binding.hpp"
#include "python/simulation_binding.hpp"

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

/// A scene loaded once, with its overrides: `mbsopt.Scene`. set() adds overrides and reloads it, so
/// a value is checked, and settings (words) take effect, exactly as `--set` does on the command line;
/// a name set again takes its new value, and overrides the scene refuses leave it as it was. Threads: simulate() runs without the GIL, under the
/// object's mutex, which set() takes too (the other members run under the GIL and only read).
class PythonScene {
 public:
  PythonScene(const std::string& scene, const py::dict& set) : source_(resolveScene(scene)) { this->set(set); }

  void set(const py::dict& values) {
    std::vector<ParameterOverride> overrides = overrides_;
    for (ParameterOverride& o : overridesOf(source_, values)) {  // a name set again takes its new value
      std::erase_if(overrides, [&](const ParameterOverride& old) { return old.name == o.name; });
      overrides.push_back(std::move(o));
    }
    LoadedScene loaded = loadScene(source_, overrides);  // throws before anything changes
    const std::lock_guard<std::mutex> lock(mutex_);
    overrides_ = std::move(overrides);
    loaded_ = std::move(loaded);
  }

  py::dict parameters() const {
    const Model& model = loaded_.scene.model;
    py::dict out;
    for (const std::string& name : model.parameterNames()) out[py::str(name)] = model.parameter(name);
    return out;
  }

  std::vector<std::string> coordinates() const {
    std::vector<std::string> out;
    for (const Coordinate& c : loaded_.scene.model.coordinates()) out.push_back(c.name);
    return out;
  }

  std::vector<std::string> sensorNames() const {
    std::vector<std::string> out;
    for (const Sensor& sensor : loaded_.scene.model.sensors()) out.push_back(sensor.name);
    return out;
  }

  /// The SI units of q's columns and of the sensors' (units.hpp), as the CSV's headers give them.
  std::vector<std::string> coordinateUnits() const {
    std::vector<std::string> out;
    for (std::size_t i = 0; i < loaded_.scene.model.coordinates().size(); ++i)
      out.push_back(coordinateUnit(loaded_.scene.model, static_cast<int>(i)));
    return out;
  }
  std::vector<std::string> sensorUnits() const {
    std::vector<std::string> out;
    for (const Sensor& sensor : loaded_.scene.model.sensors()) out.push_back(sensorSiUnit(loaded_.scene.model, sensor));
    return out;
  }

  /// As `mbsopt simulate` runs the scene: its own integrator at its step, or to `accuracy` (absolute,
  /// the extrapolation unless `integrator` says), rows at the multiples of `output_step` when given.
  PythonSimulation simulate(const std::optional<std::string>& integrator, const std::optional<double>& accuracy,
                            double output_step, bool estimate_error, bool fast_steps) const {
    const Scene& s = loaded_.scene;
    IntegrationRequest request =
        sceneIntegration(s, integrator, accuracy ? std::optional<ErrorTolerance>(ErrorTolerance{*accuracy, 0.0}) : std::nullopt);
    request.output_step = output_step;
    request.estimate_error = estimate_error;
    Integration integration;
    {
      const py::gil_scoped_release unlocked;  // released first, so the mutex is never awaited with it
      const std::lock_guard<std::mutex> lock(mutex_);
      integration = integrate(s.model, fast_steps ? withFastSteps(s.settings) : s.settings, s.q0, s.v0, request);
    }
    return {std::move(integration), request.integrator.name, coordinates(), coordinateUnits(), sensorNames(),
            sensorUnits()};
  }

  const std::string& path() const { return source_.path; }
  const std::vector<std::string>& warnings() const { return loaded_.warnings; }

 private:
  SceneSource source_;
  std::vector<ParameterOverride> overrides_;
  LoadedScene loaded_;
  mutable std::mutex mutex_;  ///< loaded_ while simulate() reads it without the GIL
};

/// A design problem loaded once, with its gradient method: `mbsopt.Problem`. Its variables are
/// given and returned in SI units; the gradients are with respect to x = value / scale, the
/// variables the optimizers see. Threads: evaluate() runs without the GIL, under the object's mutex
/// (the problem's kept simulations change); optimize() reads the problem only, each run on its own.
class PythonProblem {
 public:
  PythonProblem(const std::string& problem, const std::string& gradient, const py::dict& set, int jobs)
      : source_(resolveScene(problem)),
        overrides_(overridesOf(source_, set)),
        nlp_(loadDesignProblem(source_, overrides_), gradient, 1e-6, checkedJobs(jobs)),
        gradient_(gradient),
        jobs_(jobs) {}

  std::vector<std::string> variables() const {
    std::vector<std::string> out;
    for (const DesignVariable& v : problem().design.variables) out.push_back(v.parameter);
    out.push_back("b_{k+1}");
    return out;
  }

  std::vector<double> scales() const {
    std::vector<double> out;
    for (const DesignVariable& v : problem().design.variables) out.push_back(v.scale);
    out.push_back(problem().design.artificial.scale);
    return out;
  }

  py::array_t<double> lower() const { return inSi(nlp_.lowerBounds()); }
  py::array_t<double> upper() const { return inSi(nlp_.upperBounds()); }
  py::array_t<double> start() const { return inSi(nlp_.start()); }

  std::vector<std::string> constraintNames() const {
    std::vector<std::string> out;
    for (Eigen::Index i = 0; i < nlp_.inequalityCount() + nlp_.equalityCount(); ++i)
      out.push_back(nlp_.constraintName(i));
    return out;
  }

  PythonEvaluation evaluate(const std::optional<std::vector<double>>& design, std::optional<double> artificial,
                            bool gradients, bool outside_bounds) {
    const Eigen::VectorXd x =
        checkedDesignPoint(source_, overrides_, problem(), {design.value_or(std::vector<double>{}), artificial, outside_bounds});
    NlpEvaluation e;
    {
      const py::gil_scoped_release unlocked;  // released first, so the mutex is never awaited with it
      const std::lock_guard<std::mutex> lock(mutex_);
      nlp_.evaluate(x, gradients, e);
    }
    return {std::move(e), gradients, variables(), scales(), constraintNames(), outsideBounds(problem(), x)};
  }

  PythonRun optimize(const std::string& optimizer, const std::string& formulation, std::optional<double> epsilon,
                      std::optional<double> budget, int max_iter, const py::dict& settings) const {
    RunChoice choice;
    choice.optimizer = optimizer;
    choice.gradient = gradient_;
    choice.formulation = formulation;
    choice.epsilon = epsilon;
    if (budget) choice.budget.simulation_equivalents = *budget;
    choice.max_iterations = max_iter;
    choice.gradient_jobs = jobs_;
    for (const auto& [name, value] : settings)
      choice.settings.push_back(std::string(py::str(name)) + "=" + std::string(py::str(value)));
    PythonRun run{{}, source_.path};
    {
      const py::gil_scoped_release unlocked;  // a run takes seconds; other Python threads may go on
      run.run = runOptimization(problem(), choice, {});
    }
    return run;
  }

  const DesignProblem& problem() const { return nlp_.problem(); }
  const std::string& path() const { return source_.path; }
  const std::string& gradient() const { return gradient_; }

 private:
  static int checkedJobs(int jobs) {
    if (jobs < 1) throw std::invalid_argument("jobs must be at least 1, not " + std::to_string(jobs));
    return jobs;
  }

  /// Scaled values (x) as SI ones, variable by variable.
  py::array_t<double> inSi(const Eigen::VectorXd& x) const {
    const std::vector<double> s = scales();
    return array(Eigen::VectorXd(x.cwiseProduct(Eigen::Map<const Eigen::VectorXd>(s.data(), x.size()))));
  }

  SceneSource source_;
  std::vector<ParameterOverride> overrides_;
  DesignNlp nlp_;
  std::string gradient_;
  int jobs_;
  std::mutex mutex_;  ///< nlp_ while evaluate() runs without the GIL
};

}  // namespace
}  // namespace mbsopt

PYBIND11_MODULE(mbsopt, m) {
  using namespace mbsopt;
  m.doc() = "mbsopt: simulation, exact design gradients and optimisation of multibody systems";
  m.attr("__version__") = version();
  m.def("gradient_methods", [] { return gradientMethodNames(); }, "The gradient methods' names.");
  m.def("optimizers", [] { return optimizerNames(); }, "The optimizers' names.");
  m.def("formulations", [] { return formulationNames(); }, "The formulations' names.");
  m.def("integrators", [] { return integratorNames(); }, "The integrators' names.");
  m.def(
      "entry_types",
      [] {
        py::dict sections;
        const auto add = [&](const char* section, const auto& registry) {
          py::list types;
          for (const auto& type : registry)
            types.append(py::dict(py::arg("name") = type.name, py::arg("description") = type.description,
                                  py::arg("keys") = type.keys));
          sections[section] = types;
        };
        add("elements", elementTypes());
        add("cuts", cutTypes());
        add("forces", forceTypes());
        add("sensors", sensorTypes());
        return sections;
      },
      "The types a scene file's sections take, by section (elements, cuts, forces, sensors): each type's name, "
      "description and keys besides name and type (and an element's parent).");
  bindSimulation(m);
  bindEvaluation(m);
  bindOptimizationRun(m);

  py::class_<PythonScene>(m, "Scene",
                          "A scene (a built-in name or a YAML file), loaded once, with overrides {name: value} as "
                          "`mbsopt simulate --set` takes them.")
      .def(py::init<const std::string&, const py::dict&>(), py::arg("scene"), py::arg("set") = py::dict())
      .def("set", &PythonScene::set, py::arg("values"),
           "Adds overrides {name: value} (model parameters, settings.*) and reloads the scene with all of them.")
      .def("simulate", &PythonScene::simulate, py::arg("integrator") = py::none(), py::arg("accuracy") = py::none(),
           py::arg("output_step") = 0.0, py::arg("estimate_error") = false, py::arg("fast_steps") = false,
           "Simulates as `mbsopt simulate` does: the scene's integrator at its step, or to `accuracy` (absolute, "
           "in the coordinates' units; the extrapolation unless `integrator` names one), rows at the multiples "
           "of `output_step` when given; fast_steps=True as `--fast-steps` (each step solved to a thousandth of "
           "its truncation error; not with the extrapolation). A Simulation.")
      .def_property_readonly("parameters", &PythonScene::parameters, "Every model parameter by its dotted name (SI).")
      .def_property_readonly("coordinates", &PythonScene::coordinates, "The columns of q, v and a.")
      .def_property_readonly("sensor_names", &PythonScene::sensorNames, "The columns of the sensors.")
      .def_property_readonly("path", &PythonScene::path,
                             "The scene file read (problems/scenes/NAME.yaml for a built-in, compiled in).")
      .def_property_readonly("warnings", &PythonScene::warnings, "What loading changed (e.g. the initial state).")
      .def("__repr__", [](const PythonScene& s) { return "mbsopt.Scene('" + s.path() + "')"; });

  py::class_<PythonProblem>(
      m, "Problem",
      "A design problem (a built-in name or a YAML file with a design: section), loaded once, with the gradient "
      "method of its evaluations and optimisations and its overrides {name: value}; jobs: the most threads a "
      "gradient takes. Variables are in SI units; gradients are with respect to x = value / scale.")
      .def(py::init<const std::string&, const std::string&, const py::dict&, int>(), py::arg("problem"),
           py::arg("gradient") = "adjoint", py::arg("set") = py::dict(), py::arg("jobs") = 1)
      .def("evaluate", &PythonProblem::evaluate, py::arg("design") = py::none(), py::arg("artificial") = py::none(),
           py::arg("gradients") = true, py::arg("outside_bounds") = false,
           "The problem at a design (SI values of its variables; default its start) and b_{k+1} (default its "
           "start), with gradients unless gradients=False: an Evaluation. Each design value must lie within "
           "its bounds unless outside_bounds=True (Evaluation.outside_bounds then lists those that do not) "
           "and pass the scene file's checks of the same number (a RuntimeError with its message otherwise).")
      .def("optimize", &PythonProblem::optimize, py::arg("optimizer") = "sdcc", py::arg("formulation") = "",
           py::arg("epsilon") = py::none(), py::arg("budget") = py::none(), py::arg("max_iter") = 100,
           py::arg("settings") = py::dict(),
           "Runs an optimizer from the problem's start: an OptimizationRun (status, design, constraints, history, "
           "...; record() is what `mbsopt optimize --json` writes). formulation '' is the problem's own; budget "
           "in simulation-equivalents; settings {name: value} are the optimizer's.")
      .def_property_readonly("variables", &PythonProblem::variables, "The design variables' parameters, then b_{k+1}.")
      .def_property_readonly("scales", &PythonProblem::scales, "value = x * scale, per variable.")
      .def_property_readonly("lower", &PythonProblem::lower,
                             "The lower bounds (SI).")
      .def_property_readonly("upper", &PythonProblem::upper,
                             "The upper bounds (SI).")
      .def_property_readonly("start", &PythonProblem::start,
                             "The start (SI), b_{k+1} last.")
      .def_property_readonly("constraint_names", &PythonProblem::constraintNames, "The transcribed constraints.")
      .def_property_readonly("gradient", &PythonProblem::gradient, "The gradient method.")
      .def_property_readonly("path", &PythonProblem::path,
                             "The scene file read (problems/scenes/NAME.yaml for a built-in, compiled in).")
      .def("__repr__", [](const PythonProblem& p) {
        return "mbsopt.Problem('" + p.path() + "', gradient='" + p.gradient() + "')";
      });

  // One call each, for scripts that need one result: the classes' methods on a fresh object.
  m.def(
      "simulate",
      [](const std::string& scene, const py::dict& set, const std::optional<std::string>& integrator,
         const std::optional<double>& accuracy, double output_step, bool estimate_error, bool fast_steps) {
        return PythonScene(scene, set).simulate(integrator, accuracy, output_step, estimate_error, fast_steps);
      },
      py::arg("scene"), py::arg("set") = py::dict(), py::arg("integrator") = py::none(), py::arg("accuracy") = py::none(),
      py::arg("output_step") = 0.0, py::arg("estimate_error") = false, py::arg("fast_steps") = false,
      "Scene(scene, set).simulate(integrator, accuracy, output_step, estimate_error, fast_steps).");
  m.def("parameters", [](const std::string& scene, const py::dict& set) { return PythonScene(scene, set).parameters(); },
        py::arg("scene"), py::arg("set") = py::dict(), "Scene(scene, set).parameters.");
  m.def(
      "evaluate",
      [](const std::string& problem, const std::optional<std::vector<double>>& design, std::optional<double> artificial,
         const std::string& gradient, const py::dict& set, bool outside_bounds) {
        return PythonProblem(problem, gradient.empty() ? "adjoint" : gradient, set, 1)
            .evaluate(design, artificial, !gradient.empty(), outside_bounds);
      },
      py::arg("problem"), py::arg("design") = py::none(), py::arg("artificial") = py::none(),
      py::arg("gradient") = "adjoint", py::arg("set") = py::dict(), py::arg("outside_bounds") = false,
      "Problem(problem, gradient, set).evaluate(design, artificial, outside_bounds=...); gradient '' evaluates "
      "without gradients.");
  m.def(
      "optimize",
      [](const std::string& problem, const std::string& optimizer, const std::string& gradient,
         const std::string& formulation, std::optional<double> epsilon, std::optional<double> budget, int max_iter,
         const py::dict& settings, const py::dict& set, int jobs) {
        return PythonProblem(problem, gradient, set, jobs).optimize(optimizer, formulation, epsilon, budget, max_iter,
                                                                    settings);
      },
      py::arg("problem"), py::arg("optimizer") = "sdcc", py::arg("gradient") = "adjoint", py::arg("formulation") = "",
      py::arg("epsilon") = py::none(), py::arg("budget") = py::none(), py::arg("max_iter") = 100,
      py::arg("settings") = py::dict(), py::arg("set") = py::dict(), py::arg("jobs") = 1,
      "Problem(problem, gradient, set, jobs).optimize(optimizer, formulation, epsilon, budget, max_iter, settings).");
}
