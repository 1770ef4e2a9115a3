#include "mbsopt/sensitivity/design_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <utility>

#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/sensitivity/initial_state.hpp"
#include "mbsopt/sensitivity/parallel_runs.hpp"

namespace mbsopt {

namespace {

/// φ(t_k) = sign · y(t_k) − offset − b_{k+1} (when the functional takes it in its samples), DesignProblem docs.
Eigen::VectorXd violation(const ConstraintFunctional& f, const Eigen::MatrixXd& sensors, double artificial) {
  const double b = f.artificial == ArtificialUse::InSamples ? artificial : 0.0;
  return (f.sign * sensors.col(f.sensor).array() - f.offset - b).matrix();
}

}  // namespace

DesignResponse evaluateDesign(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x) {
  DesignResponse out;
  evaluateDesign(problem, functionals, x, out, {});
  return out;
}

const DesignResponse& loadCaseResponse(const DesignResponse& response, std::size_t c) {
  if (response.made_of != ResponseParts::LoadCases) throw std::logic_error("loadCaseResponse: a response without load cases");
  return response.parts.at(c);
}

const DesignResponse& extrapolationRunResponse(const DesignResponse& response, int j) {
  if (response.made_of != ResponseParts::ExtrapolationRuns)
    throw std::logic_error("extrapolationRunResponse: a response of one Newmark run");
  return response.parts.at(static_cast<std::size_t>(j - 1));
}

const Trajectory& caseTrajectory(const DesignResponse& response, std::size_t c) {
  switch (response.made_of) {
    case ResponseParts::ExtrapolationRuns: return caseTrajectory(response.parts.back(), c);
    case ResponseParts::LoadCases: return response.parts.at(c).trajectory;
    case ResponseParts::Simulation: break;
  }
  return response.trajectory;
}

Eigen::VectorXd runWeights(const DesignProblem& problem, int first) {
  return extrapolationWeights(errorExponents(problem.scene.model, problem.scene.settings), first,
                              extrapolationRuns(problem));
}

namespace {

/// Σ w_i value(run first + i) over the runs of an extrapolated response.
template <class Value>
auto combineRuns(const DesignProblem& problem, const DesignResponse& response, int first, Value&& value) {
  const Eigen::VectorXd w = runWeights(problem, first);
  auto sum = value(extrapolationRunProblem(problem, first + 1), extrapolationRunResponse(response, first + 1));
  sum *= w[0];
  for (Eigen::Index i = 1; i < w.size(); ++i) {
    const int j = first + static_cast<int>(i);
    sum += w[i] * value(extrapolationRunProblem(problem, j + 1), extrapolationRunResponse(response, j + 1));
  }
  return sum;
}

}  // namespace

double costFunctional(const DesignProblem& problem, const DesignResponse& response) {
  if (response.made_of == ResponseParts::ExtrapolationRuns)
    return combineRuns(problem, response, 1, [](const DesignProblem& run, const DesignResponse& r) {
      return costFunctional(run, r);
    });
  const ResponseCost& cost = problem.design.cost;
  const int sensor = sensorIndex(problem.scene.model, cost.sensor);
  const std::optional<TimeMeasure> exact = exactMeasure(cost.of);
  double worst = -std::numeric_limits<double>::infinity();
  for (std::size_t c = 0; c < std::max<std::size_t>(problem.load_cases.size(), 1); ++c) {
    const Trajectory& trajectory = caseTrajectory(response, c);
    const auto y = trajectory.sensors.col(sensor);
    const double value = exact ? evaluateTimeFunctional(*exact, trajectory.time, y).value
                         : cost.of == ResponseMeasure::Max ? y.maxCoeff() : y.cwiseAbs().maxCoeff();
    worst = std::max(worst, value);
  }
  return worst;
}

double costFunctionalError(const DesignProblem& problem, const DesignResponse& response) {
  if (response.made_of != ResponseParts::ExtrapolationRuns) return 0.0;
  const auto value = [](const DesignProblem& run, const DesignResponse& r) { return costFunctional(run, r); };
  return combineRuns(problem, response, 1, value) - combineRuns(problem, response, 0, value);  // result − exact
}

void evaluateDesign(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                    const Eigen::VectorXd& x, DesignResponse& out, const std::function<void(long)>& stored,
                    bool keep_step_matrices) {
  if (const int runs = extrapolationRuns(problem); runs > 1) {
    if (stored) throw std::logic_error("evaluateDesign: an extrapolated problem reports no stored points");
    if (!problem.load_cases.empty())
      throw std::invalid_argument("the extrapolation does not combine load cases: take settings.integrator newmark");
    out.made_of = ResponseParts::ExtrapolationRuns;
    out.parts.resize(static_cast<std::size_t>(runs));
    for (int j = 0; j < runs; ++j)
      evaluateDesign(extrapolationRunProblem(problem, j + 1), functionals, x, out.parts[static_cast<std::size_t>(j)], {},
                     keep_step_matrices);
    out.cost = out.parts.front().cost;
    const auto constraints = [](const DesignProblem&, const DesignResponse& r) -> Eigen::VectorXd { return r.constraints; };
    out.constraints = combineRuns(problem, out, 1, constraints);
    out.constraint_errors = out.constraints - combineRuns(problem, out, 0, constraints);  // result − exact
    out.trajectory = {};
    out.functionals.clear();
    return;
  }
  out.constraint_errors.resize(0);
  if (!problem.load_cases.empty()) {
    if (stored) throw std::logic_error("evaluateDesign: a problem with load cases reports no stored points");
    out.made_of = ResponseParts::LoadCases;
    out.parts.resize(problem.load_cases.size());
    out.constraints.resize(static_cast<Eigen::Index>(functionals.size()));
    out.functionals.assign(functionals.size(), {});
    out.trajectory = {};
    std::vector<Eigen::Index> rows;
    for (std::size_t c = 0; c < problem.load_cases.size(); ++c) {
      const std::vector<ConstraintFunctional> own = loadCaseFunctionals(functionals, static_cast<int>(c), &rows);
      DesignResponse& response = out.parts[c];
      evaluateDesign(loadCaseProblem(problem, c), own, x, response, {}, keep_step_matrices);
      out.cost = response.cost;
      for (std::size_t i = 0; i < rows.size(); ++i) {
        out.constraints[rows[i]] = response.constraints[static_cast<Eigen::Index>(i)];
        out.functionals[static_cast<std::size_t>(rows[i])] = response.functionals[i];
      }
    }
    return;
  }
  out.made_of = ResponseParts::Simulation;
  out.parts.clear();
  const Scene& scene = problem.scene;
  Model model = scene.model;
  out.cost = applyDesign(problem, x, model);
  NewmarkIntegrator integrator(model, scene.settings);
  integrator.keepStepMatrices(keep_step_matrices);
  if (designMovesLoopClosure(problem)) {  // a geometric variable opens the loops
    Eigen::VectorXd q0, v0;
    designInitialState(scene, model, q0, v0);
    integrator.simulate(q0, v0, out.trajectory, stored);
  } else {
    integrator.simulate(scene.q0, scene.v0, out.trajectory, stored);
  }
  out.constraints.resize(static_cast<Eigen::Index>(functionals.size()));
  out.functionals.clear();
  for (std::size_t j = 0; j < functionals.size(); ++j) {
    const ConstraintFunctional& f = functionals[j];
    const Eigen::VectorXd phi = violation(f, out.trajectory.sensors, out.cost);
    const auto [first, count] = windowPoints(f.window, f.windows, phi.size());
    TimeFunctionalValue value = evaluateTimeFunctional(f.measure, out.trajectory.time.segment(first, count),
                                                       phi.segment(first, count), problem.design.transcription.rho);
    if (count < phi.size()) {  // its gradient on the whole grid, zero outside the window
      Eigen::VectorXd gradient = Eigen::VectorXd::Zero(phi.size());
      gradient.segment(first, count) = value.gradient;
      value.gradient.swap(gradient);
    }
    out.functionals.push_back(std::move(value));
    const double b = f.artificial == ArtificialUse::AfterMeasure ? out.cost : 0.0;
    out.constraints[static_cast<Eigen::Index>(j)] = out.functionals.back().value - f.level - b - f.tolerance;
  }
}

Eigen::VectorXd artificialColumn(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                 const DesignResponse& response) {
  if (response.made_of == ResponseParts::ExtrapolationRuns)
    return combineRuns(problem, response, 1, [&](const DesignProblem& run, const DesignResponse& r) {
      return artificialColumn(run, functionals, r);
    });
  Eigen::VectorXd column = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(functionals.size()));
  for (std::size_t j = 0; j < functionals.size(); ++j)
    if (functionals[j].artificial == ArtificialUse::InSamples)  // ∂φ_k/∂b = −1 at every k
      column[static_cast<Eigen::Index>(j)] = -response.functionals[j].gradient.sum() * problem.design.artificial.scale;
    else if (functionals[j].artificial == ArtificialUse::AfterMeasure)  // measure(φ) − b
      column[static_cast<Eigen::Index>(j)] = -problem.design.artificial.scale;
  return column;
}

Eigen::MatrixXd boundJacobian(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const DesignResponse& response) {
  if (response.made_of == ResponseParts::ExtrapolationRuns)
    return combineRuns(problem, response, 1, [&](const DesignProblem& run, const DesignResponse& r) {
      return boundJacobian(run, functionals, r);
    });
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(functionals.size()),
                                                   static_cast<Eigen::Index>(problem.design.constraints.size()));
  for (std::size_t j = 0; j < functionals.size(); ++j) {  // φ_k = sign·y_k − offset: ∂φ_k/∂B = −∂offset/∂B
    const ConstraintFunctional& f = functionals[j];
    if (f.constraint < 0) continue;
    jacobian(static_cast<Eigen::Index>(j), f.constraint) =
        -f.offset_per_bound * response.functionals[j].gradient.sum() - f.level_per_bound;
  }
  return jacobian;
}

DesignGradient finiteDifferenceGradient(const DesignProblem& problem,
                                        const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                                        double relative_step, bool central, const DesignResponse* simulated, int jobs) {
  if (!(relative_step > 0.0)) throw std::invalid_argument("finite differences: the relative step must be positive");
  const Eigen::Index n = x.size(), m = static_cast<Eigen::Index>(functionals.size());
  DesignGradient out;
  out.cost = Eigen::VectorXd::Zero(n);
  out.cost[n - 1] = problem.design.artificial.scale;  // the cost is b_{k+1} = x_{k+1} · scale
  out.constraints.resize(m, n);
  // The points to simulate: x itself unless known, then x + step eᵢ (and x − step eᵢ) per design variable.
  std::vector<Eigen::VectorXd> points;
  std::vector<double> steps;
  if (!simulated) points.push_back(x);
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    steps.push_back(relative_step * std::max(std::abs(x[i]), 1.0));
    points.push_back(x);
    points.back()[i] += steps.back();
    if (central) {
      points.push_back(x);
      points.back()[i] -= steps.back();
    }
  }
  // Of the shifted points only the constraints are kept (a trajectory per point would not be small).
  std::optional<DesignResponse> own;
  std::vector<Eigen::VectorXd> values(points.size());
  runInParallel(points.size(), jobs, [&](std::size_t k) {
    if (k == 0 && !simulated) {
      own = evaluateDesign(problem, functionals, points[k]);
      values[k] = own->constraints;
    } else {
      values[k] = evaluateDesign(problem, functionals, points[k]).constraints;
    }
  });
  const DesignResponse& base = simulated ? *simulated : *own;
  std::size_t next = simulated ? 0 : 1;
  for (Eigen::Index i = 0; i + 1 < n; ++i) {
    const double step = steps[static_cast<std::size_t>(i)];
    const Eigen::VectorXd& above = values[next++];
    if (central) out.constraints.col(i) = (above - values[next++]) / (2.0 * step);
    else out.constraints.col(i) = (above - base.constraints) / step;
  }
  out.constraints.col(n - 1) = artificialColumn(problem, functionals, base);
  return out;
}

}  // namespace mbsopt
