#include "mbsopt/sensitivity/design_problem.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include "mbsopt/integrators/extrapolation.hpp"

#include <Eigen/SVD>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/algorithms/tangent.hpp"

namespace mbsopt {

std::optional<TimeMeasure> exactMeasure(ResponseMeasure of) {
  if (of == ResponseMeasure::Integral) return TimeMeasure::Integral;
  if (of == ResponseMeasure::Rms) return TimeMeasure::RootMeanSquare;
  if (of == ResponseMeasure::FinalValue) return TimeMeasure::FinalValue;
  return std::nullopt;
}

int sensorIndex(const Model& model, const std::string& name) {
  for (std::size_t s = 0; s < model.sensors().size(); ++s)
    if (model.sensors()[s].name == name) return static_cast<int>(s);
  throw std::invalid_argument("design: no sensor named '" + name + "'");
}

std::string designSensorDefect(const Sensor& sensor) {
  if (isStateSensor(sensor) || readsMultipliers(sensor)) return {};
  return "sensor '" + sensor.name +
         "' is an energy sensor, which depends on the model parameters (masses, stiffnesses) directly: the design "
         "gradients differentiate point, joint, relative_angle and cut_reaction sensors, so it cannot be a cost or "
         "a constraint";
}

std::string reactionDeterminacyDefect(const Scene& scene, const Sensor& sensor) {
  const auto* reaction = std::get_if<CutReactionSensor>(&sensor.kind);
  if (!reaction) return {};
  const Model& model = scene.model;
  Workspace<double> ws(model);
  Eigen::VectorXd b, c;
  Eigen::MatrixXd B;
  constraintJacobian(model, ws, scene.q0, model.freeCoordinates(), b, B);  // leaves q₀'s geometry in ws
  reactionCoefficients(model, ws, *reaction, c);
  // The range of B at the integrator's threshold: the multipliers there are determinate.
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeThinU);
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < sigma.size() && sigma[rank] > scene.settings.svd_threshold * sigma[0]) ++rank;
  const Eigen::MatrixXd U1 = svd.matrixU().leftCols(rank);
  const double indeterminate = (c - U1 * (U1.transpose() * c)).norm();
  if (indeterminate <= kDeterminateReaction * c.norm()) return {};
  return "sensor '" + sensor.name + "' reads a component of the reaction of cut '" +
         model.cuts()[static_cast<std::size_t>(reaction->cut)].name +
         "' that its redundant closure equations leave statically indeterminate (at the initial state " +
         std::to_string(static_cast<int>(std::lround(100.0 * indeterminate / c.norm()))) +
         " % of it reads multipliers that no motion fixes): it is not a function of the design, so it cannot be a "
         "cost or a constraint; a planar loop determines only the in-plane forces of its cut";
}

namespace {

void checkRange(const std::string& what, double lower, double upper, double scale) {
  if (!std::isfinite(lower) || !std::isfinite(upper) || !(lower <= upper))
    throw std::invalid_argument(what + ": the bounds must be finite with lower <= upper");
  if (!(scale > 0.0) || !std::isfinite(scale)) throw std::invalid_argument(what + ": the scale must be positive");
}

}  // namespace

DesignProblem loadCaseProblem(const DesignProblem& problem, std::size_t c) {
  return {problem.load_cases.at(c).scene, problem.design, {}};
}

int extrapolationRuns(const DesignProblem& problem) {
  return problem.scene.integrator.extrapolated() ? problem.scene.integrator.extrapolation_runs : 1;
}

DesignProblem extrapolationRunProblem(const DesignProblem& problem, int j) {
  DesignProblem run{problem.scene, problem.design, {}};
  NewmarkSettings& s = run.scene.settings;
  s.step = uniformStep(s) / j;  // j steps in each macro step, the last ending at the end time
  run.scene.integrator = {};
  return run;
}

std::vector<ConstraintFunctional> loadCaseFunctionals(const std::vector<ConstraintFunctional>& functionals, int c,
                                                      std::vector<Eigen::Index>* rows) {
  std::vector<ConstraintFunctional> out;
  if (rows) rows->clear();
  for (std::size_t j = 0; j < functionals.size(); ++j) {
    if (functionals[j].load_case != c) continue;
    out.push_back(functionals[j]);
    out.back().load_case = 0;  // in the case's own problem
    if (rows) rows->push_back(static_cast<Eigen::Index>(j));
  }
  return out;
}

DesignVariable designVariable(const Model& model, std::string parameter, double lower, double upper, double scale) {
  const std::vector<std::string>& names = model.parameterNames();
  if (std::find(names.begin(), names.end(), parameter) == names.end())
    throw std::invalid_argument("design variable '" + parameter + "' is not a model parameter");
  const ParameterIndex index = model.parameterIndex(parameter);
  return {std::move(parameter), index, lower, upper, scale};
}

namespace {

/// Every variable's index names its parameter in `model` (a load case's scene has the scene's parameters).
void checkResolved(const std::vector<DesignVariable>& variables, const Model& model) {
  const std::vector<std::string>& names = model.parameterNames();
  for (const DesignVariable& v : variables) {
    const auto i = static_cast<std::size_t>(v.index);
    if (i >= names.size() || names[i] != v.parameter)
      throw std::invalid_argument("design variable '" + v.parameter + "' is not resolved in the model (designVariable)");
  }
}

}  // namespace

std::vector<ConstraintFunctional> transcribe(const DesignProblem& problem) {
  checkResolved(problem.design.variables, problem.scene.model);
  if (!problem.load_cases.empty()) {
    // Each case's constraints, named after it; NlpProblem's order: every inequality, then every equality.
    std::vector<ConstraintFunctional> inequalities, equalities;
    for (std::size_t c = 0; c < problem.load_cases.size(); ++c)
      for (ConstraintFunctional f : transcribe(loadCaseProblem(problem, c))) {
        f.name += "_" + problem.load_cases[c].name;
        f.load_case = static_cast<int>(c);
        (f.equality ? equalities : inequalities).push_back(std::move(f));
      }
    inequalities.insert(inequalities.end(), equalities.begin(), equalities.end());
    return inequalities;
  }
  const Model& model = problem.scene.model;
  std::vector<ConstraintFunctional> functionals;
  const Transcription& t = problem.design.transcription;
  if (t.windows < 1) throw std::invalid_argument("design: the windows must be at least one");
  const double duration = problem.scene.settings.end_time;
  const auto add = [&](const std::string& sensor, ResponseMeasure of, double bound, bool artificial, bool equality,
                       int constraint) {
    const std::size_t first = functionals.size();
    const int index = sensorIndex(model, sensor);
    const Sensor& read = model.sensors()[static_cast<std::size_t>(index)];
    for (const std::string& defect : {designSensorDefect(read), reactionDeterminacyDefect(problem.scene, read)})
      if (!defect.empty()) throw std::invalid_argument("design: " + defect);
    if (equality && of != ResponseMeasure::Integral && of != ResponseMeasure::FinalValue)
      throw std::invalid_argument("design: an equality on '" + sensor + "' needs an exact functional (integral or final)");
    // The cost's epigraph: b_{k+1} in the samples of a transcribed extreme, after an exact functional.
    const ArtificialUse in_samples = artificial ? ArtificialUse::InSamples : ArtificialUse::None;
    const ArtificialUse after = artificial ? ArtificialUse::AfterMeasure : ArtificialUse::None;
    if (of == ResponseMeasure::Integral) {
      functionals.push_back({sensor + "_integral", index, 1.0, bound / duration, after, TimeMeasure::Integral, 0.0, equality});
    } else if (of == ResponseMeasure::Rms) {  // √((1/τ)∫y²dt) − bound (− b) ≤ 0
      functionals.push_back({sensor + "_rms", index, 1.0, 0.0, after, TimeMeasure::RootMeanSquare, 0.0, false, bound});
    } else if (of == ResponseMeasure::FinalValue) {
      functionals.push_back({sensor + "_final", index, 1.0, bound, after, TimeMeasure::FinalValue, 0.0, equality});
    } else {  // the extremes, transcribed on each window of the run
      for (int w = 0; w < t.windows; ++w) {
        const std::string window = t.windows > 1 ? "_w" + std::to_string(w + 1) : "";
        const auto extreme = [&](const std::string& side, double sign, double offset) {
          ConstraintFunctional f{sensor + side + window, index, sign, offset, in_samples, t.measure, t.tolerance};
          f.window = w;
          f.windows = t.windows;
          functionals.push_back(f);
        };
        if (of == ResponseMeasure::Min) {  // min y ≥ bound: −y + bound ≤ 0
          extreme("_min", -1.0, -bound);
        } else {  // y − bound (− b) ≤ 0, and −y − bound (− b) ≤ 0 for MaxAbs
          extreme("_above", 1.0, bound);
          if (of == ResponseMeasure::MaxAbs) extreme("_below", -1.0, bound);
        }
      }
    }
    for (std::size_t j = first; j < functionals.size(); ++j) {  // how each moves with the bound
      ConstraintFunctional& f = functionals[j];
      f.constraint = constraint;
      if (constraint < 0) continue;
      if (of == ResponseMeasure::Rms) f.level_per_bound = 1.0;
      else if (of == ResponseMeasure::Integral) f.offset_per_bound = 1.0 / duration;
      else f.offset_per_bound = of == ResponseMeasure::Min ? -1.0 : 1.0;
    }
  };
  add(problem.design.cost.sensor, problem.design.cost.of, 0.0, true, false, -1);  // (17)-(19): ±y − b_{k+1} ≤ 0
  for (const bool equalities : {false, true})  // NlpProblem's order: the inequalities first
    for (std::size_t i = 0; i < problem.design.constraints.size(); ++i) {
      const ResponseConstraint& c = problem.design.constraints[i];
      if (c.equality == equalities) add(c.sensor, c.of, c.bound, false, c.equality, static_cast<int>(i));
    }
  // Several constraints may read one sensor the same way (two bounds on its maximum, or a maximum
  // beside the cost's): a repeated name gets its rank, "travel_above_2".
  std::map<std::string, int> seen;
  for (ConstraintFunctional& f : functionals)
    if (const int rank = ++seen[f.name]; rank > 1) {
      f.name += '_';
      f.name += std::to_string(rank);
    }
  return functionals;
}

std::pair<Eigen::Index, Eigen::Index> windowPoints(int window, int windows, Eigen::Index points) {
  const Eigen::Index N = points - 1;
  const auto start = [&](int i) { return (static_cast<Eigen::Index>(i) * N + windows - 1) / windows; };  // ⌈i N / W⌉
  const Eigen::Index first = start(window), end = window + 1 == windows ? points : start(window + 1);
  if (end - first < 2)
    throw std::invalid_argument("design: " + std::to_string(windows) + " windows leave window " +
                                std::to_string(window + 1) + " fewer than two of the run's " + std::to_string(points) +
                                " time points");
  return {first, end - first};
}

Eigen::VectorXd initialPoint(const DesignProblem& problem) {
  Eigen::VectorXd x(optimisationSize(problem));
  for (std::size_t i = 0; i < problem.design.variables.size(); ++i) {
    const DesignVariable& v = problem.design.variables[i];
    x[static_cast<Eigen::Index>(i)] = problem.scene.model.value(v.index) / v.scale;
  }
  x[x.size() - 1] = problem.design.artificial.initial / problem.design.artificial.scale;
  return x;
}

double applyDesign(const DesignProblem& problem, const Eigen::VectorXd& x, Model& model) {
  if (x.size() != optimisationSize(problem))
    throw std::invalid_argument("design: " + std::to_string(x.size()) + " values for " +
                                std::to_string(optimisationSize(problem)) + " variables");
  for (std::size_t i = 0; i < problem.design.variables.size(); ++i) {
    const DesignVariable& v = problem.design.variables[i];
    model.setParameter(v.index, x[static_cast<Eigen::Index>(i)] * v.scale);
  }
  return x[x.size() - 1] * problem.design.artificial.scale;
}

void validate(const DesignProblem& problem) {
  if (const ResponseMeasure of = problem.design.cost.of; of == ResponseMeasure::Min || of == ResponseMeasure::FinalValue)
    throw std::invalid_argument("the cost is a sensor's extreme over time (max_abs or max), its integral or its rms");
  checkResolved(problem.design.variables, problem.scene.model);
  for (const DesignVariable& v : problem.design.variables) {
    checkRange("design variable '" + v.parameter + "'", v.lower, v.upper, v.scale);
    const double value = problem.scene.model.value(v.index);
    if (value < v.lower || value > v.upper)
      throw std::invalid_argument("design variable '" + v.parameter + "' starts outside its bounds");
  }
  const ArtificialVariable& a = problem.design.artificial;
  checkRange("the artificial variable", a.lower, a.upper, a.scale);
  if (a.initial < a.lower || a.initial > a.upper)
    throw std::invalid_argument("the artificial variable starts outside its bounds");
  if (!(problem.design.transcription.tolerance >= 0.0)) throw std::invalid_argument("the tolerance must not be negative");
  if (!(problem.design.transcription.rho > 0.0)) throw std::invalid_argument("rho must be positive");
  if (problem.design.transcription.windows < 1) throw std::invalid_argument("the windows must be at least one");
  transcribe(problem);  // every sensor exists
}

}  // namespace mbsopt
