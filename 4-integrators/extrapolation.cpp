#include "mbsopt/integrators/extrapolation.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/trajectory.hpp"

namespace mbsopt {

std::vector<int> errorExponents(const Model& model, const NewmarkSettings& settings) {
  const bool projected = model.constraintCount() > 0 && settings.closure == ClosureLevel::Position;
  std::vector<int> exponents;
  for (int p = 2; exponents.size() < 12; p += projected ? 1 : 2) exponents.push_back(p);
  return exponents;
}

Eigen::VectorXd extrapolationWeights(const std::vector<int>& exponents, int first, int runs) {
  const int count = runs - first;
  if (first < 0 || count < 1 || count > static_cast<int>(exponents.size()) + 1)
    throw std::invalid_argument("extrapolation: no combination of " + std::to_string(count) + " runs");
  // Row 0: Σ c_i = 1; row m: Σ c_i h_i^{p_m} = 0 with h_i = 1/n_i (H factors out), n_i = i.
  Eigen::MatrixXd system(count, count);
  for (int i = 0; i < count; ++i) {
    const double h = 1.0 / (first + i + 1);
    system(0, i) = 1.0;
    for (int m = 1; m < count; ++m) system(m, i) = std::pow(h, exponents[static_cast<std::size_t>(m - 1)]);
  }
  return system.fullPivLu().solve(Eigen::VectorXd::Unit(count, 0));
}

namespace {

/// Σ c_i runs[i] (q, q̇, q̈, λ); time of the last run, `statistics` as given.
SampledRun combined(const std::vector<SampledRun>& runs, std::size_t first, const Eigen::VectorXd& c,
                    const IntegratorStatistics& statistics) {
  const SampledRun& last = runs[first + static_cast<std::size_t>(c.size()) - 1];
  SampledRun sum;
  sum.time = last.time;
  sum.statistics = statistics;
  for (Eigen::MatrixXd SampledRun::*part : {&SampledRun::q, &SampledRun::v, &SampledRun::a, &SampledRun::lambda}) {
    sum.*part = Eigen::MatrixXd::Zero((last.*part).rows(), (last.*part).cols());
    for (Eigen::Index i = 0; i < c.size(); ++i) sum.*part += c[i] * (runs[first + static_cast<std::size_t>(i)].*part);
  }
  return sum;
}

/// The round-off floor from the difference of two roundings: max_{s ≤ t} |difference(s)| / √2 entry by
/// entry (√2: the difference holds both roundings), time along columns (`time_along_rows` false: q, v)
/// or along rows (true: sensors).
Eigen::MatrixXd floorOfTwoRoundings(const Eigen::MatrixXd& difference, bool time_along_rows) {
  Eigen::MatrixXd out = difference.cwiseAbs();
  if (time_along_rows) {
    for (Eigen::Index k = 1; k < out.rows(); ++k) out.row(k) = out.row(k).cwiseMax(out.row(k - 1));
  } else {
    for (Eigen::Index k = 1; k < out.cols(); ++k) out.col(k) = out.col(k).cwiseMax(out.col(k - 1));
  }
  return out / std::numbers::sqrt2;
}

}  // namespace

SampledRun ExtrapolationTableau::combination(int first) const {
  if (rows() < 2) throw std::logic_error("ExtrapolationTableau: a combination needs two runs");
  return combined(runs_, static_cast<std::size_t>(first), weights(first), statistics_);
}

void addStatistics(IntegratorStatistics& sum, const IntegratorStatistics& run) {
  sum.steps += run.steps;
  sum.rejected_steps += run.rejected_steps;
  sum.newton_iterations += run.newton_iterations;
  sum.jacobian_updates += run.jacobian_updates;
  sum.mass_updates += run.mass_updates;
  sum.factorizations += run.factorizations;
  sum.max_closure_error = std::max(sum.max_closure_error, run.max_closure_error);
  sum.max_relative_residual = std::max(sum.max_relative_residual, run.max_relative_residual);
}

void ExtrapolationTableau::add(SampledRun run, double step) {
  steps_.push_back(step);
  addStatistics(statistics_, run.statistics);
  runs_.push_back(std::move(run));
}

void ExtrapolationTableau::addRoundOffProbe(std::vector<SampledRun> repeats) {
  if (rows() < 2 || static_cast<int>(repeats.size()) != rows() - 1)
    throw std::logic_error("ExtrapolationTableau: the round-off probe repeats runs 2 … rows(), made after them");
  for (const SampledRun& run : repeats) addStatistics(statistics_, run.statistics);
  repeats_ = std::move(repeats);
}

SampledRun ExtrapolationTableau::repeatedResult(int runs) const {
  if (!probed() || runs < 2 || runs > probedRuns())
    throw std::logic_error("ExtrapolationTableau: no round-off probe of " + std::to_string(runs) + " runs");
  return combined(repeats_, 0, extrapolationWeights(exponents_, 1, runs), statistics_);
}

Eigen::MatrixXd ExtrapolationTableau::roundOffFloor(Eigen::MatrixXd SampledRun::*part, int runs) const {
  if (runs == 0) runs = rows();
  if (!probed()) {
    const Eigen::MatrixXd& any = runs_.front().*part;
    return Eigen::MatrixXd::Zero(any.rows(), any.cols());
  }
  // The same combination of the runs and of their repeats: independent roundings of equal size.
  const Eigen::VectorXd c = extrapolationWeights(exponents_, 1, runs);
  return floorOfTwoRoundings(combined(runs_, 1, c, statistics_).*part - repeatedResult(runs).*part, false);
}

Trajectory sampledTrajectory(const Model& model, const NewmarkSettings& settings, SampledRun run) {
  Trajectory trajectory;
  trajectory.time = std::move(run.time);
  trajectory.q = std::move(run.q);
  trajectory.v = std::move(run.v);
  trajectory.a = std::move(run.a);
  trajectory.lambda = std::move(run.lambda);
  trajectory.closure_error = Eigen::VectorXd::Zero(trajectory.time.size());
  if (model.constraintCount() > 0) {
    Eigen::VectorXd q, v;
    for (Eigen::Index k = 0; k < trajectory.time.size(); ++k) {
      q = trajectory.q.col(k);
      v = trajectory.v.col(k);
      const AssemblyReport report = assemble(model, q, v, trajectory.time[k], 1e-12, settings.svd_threshold);
      trajectory.q.col(k) = q;
      trajectory.v.col(k) = v;
      trajectory.closure_error[k] = report.closure_error;
    }
  }
  trajectory.sensors = sensorHistory(model, trajectory);
  trajectory.newton_iterations = Eigen::VectorXi::Zero(trajectory.time.size());
  trajectory.statistics = run.statistics;
  return trajectory;
}

std::string extrapolationDefect(const NewmarkSettings& settings, const std::string& who) {
  if (std::string defect = halvingDefect(settings, who); !defect.empty()) return defect;
  if (settings.newton_truncation_fraction > 0.0)
    return who + " needs every step solved to the Newton tolerance (not --fast-steps): Newton's "
           "errors, a fraction of the h^2 truncation error, would cap its higher orders";
  return {};
}

std::string halvingDefect(const NewmarkSettings& settings, const std::string& who) {
  if (settings.beta != 0.25 || settings.gamma != 0.5)
    return who + " needs the trapezoidal rule (beta = 0.25, gamma = 0.5), whose error is even in h; this "
           "scene has beta = " + std::to_string(settings.beta) + ", gamma = " + std::to_string(settings.gamma);
  if (settings.closure != ClosureLevel::Position)
    return who + " needs the loops closed at position level: the acceleration-level closure drifts";
  if (settings.accept_by_contraction_rate)
    return who + " needs every Newton iteration converged to its tolerance (not --fast-newton): the runs' "
           "differences must be the discretisation's, not the iteration's";
  return {};
}

SampledRun sampledNewmarkRun(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& v0, long stride, long outputs,
                             const std::function<void(double)>& progress) {
  if (stride < 1 || outputs < 1) throw std::invalid_argument("sampledNewmarkRun: stride and outputs must be positive");
  NewmarkIntegrator integrator(model, settings);
  integrator.initialize(q0, v0, 0.0);
  const Eigen::Index n = model.coordinateCount();
  SampledRun run;
  run.time.resize(outputs + 1);
  run.q.resize(n, outputs + 1);
  run.v.resize(n, outputs + 1);
  run.a.resize(n, outputs + 1);
  run.lambda.resize(model.constraintCount(), outputs + 1);
  const auto keep = [&](Eigen::Index m) {
    run.time[m] = integrator.time();
    run.q.col(m) = integrator.q();
    run.v.col(m) = integrator.v();
    run.a.col(m) = integrator.a();
    run.lambda.col(m) = integrator.lambda();
  };
  keep(0);
  for (Eigen::Index m = 1; m <= outputs; ++m) {
    for (long s = 0; s < stride; ++s) {
      integrator.step();
      if (progress) progress(integrator.time());
    }
    keep(m);
  }
  run.statistics = integrator.statistics();
  return run;
}

double weightedErrorNorm(const Eigen::MatrixXd& error, const Eigen::MatrixXd& value, const ErrorTolerance& tolerance) {
  return (error.array().abs() / (tolerance.absolute + tolerance.relative * value.array().abs())).maxCoeff();
}

void keepPoints(EstimatedRun& run, const std::vector<Eigen::Index>& kept) {
  Trajectory& t = run.trajectory;
  t.time = Eigen::VectorXd(t.time(kept));
  for (Eigen::MatrixXd* columns : {&t.q, &t.v, &t.a, &t.lambda, &t.v_unprojected, &t.a_unprojected, &run.q_error,
                                   &run.v_error})
    if (columns->cols() > 0) *columns = Eigen::MatrixXd((*columns)(Eigen::all, kept));
  for (Eigen::MatrixXd* by_row : {&t.sensors, &run.sensor_error})
    if (by_row->rows() > 0) *by_row = Eigen::MatrixXd((*by_row)(kept, Eigen::all));
  if (t.closure_error.size() > 0) t.closure_error = Eigen::VectorXd(t.closure_error(kept));
  if (t.newton_iterations.size() > 0) t.newton_iterations = Eigen::VectorXi(t.newton_iterations(kept));
  t.step_matrices.resize(0, 0);
}

double EstimatedRun::positionError() const { return q_error.size() ? q_error.cwiseAbs().maxCoeff() : 0.0; }
double EstimatedRun::velocityError() const { return v_error.size() ? v_error.cwiseAbs().maxCoeff() : 0.0; }

EstimatedRun estimateGlobalError(const Model& model, const NewmarkSettings& settings, Trajectory trajectory,
                                 const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                 const std::function<void(double)>& progress) {
  if (const std::string defect = halvingDefect(settings, "the global error estimate"); !defect.empty())
    throw std::invalid_argument(defect);
  const NewmarkSettings half = halvedSteps(settings);
  const long points = trajectory.time.size();
  SampledRun fine = sampledNewmarkRun(model, half, q0, v0, 2, points - 1, progress);
  addStatistics(trajectory.statistics, fine.statistics);
  EstimatedRun run;
  // y_h − y = e₂h² + O(h⁴), y_{h/2} − y = e₂h²/4 + O(h⁴): e_h = 4/3 (y_h − y_{h/2}) + O(h⁴).
  run.q_error = (4.0 / 3.0) * (trajectory.q - fine.q);
  run.v_error = (4.0 / 3.0) * (trajectory.v - fine.v);
  run.sensor_error = (4.0 / 3.0) * (trajectory.sensors - sampledTrajectory(model, settings, std::move(fine)).sensors);
  run.trajectory = std::move(trajectory);
  run.steps = {uniformStep(settings), half.step};
  run.order = 2;
  return run;
}

EstimatedRun extrapolatedNewmark(const Model& model, const NewmarkSettings& settings, int runs,
                                 const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                 const std::function<void(double)>& progress) {
  if (runs < 2 || runs > kMaxExtrapolationRuns)
    throw std::invalid_argument("extrapolation takes 2 to " + std::to_string(kMaxExtrapolationRuns) + " runs, not " +
                                std::to_string(runs));
  if (const std::string defect = extrapolationDefect(settings); !defect.empty()) throw std::invalid_argument(defect);
  const double H = uniformStep(settings);
  const long outputs = stepsToCover(settings.end_time, H);
  ExtrapolationTableau tableau(errorExponents(model, settings));
  for (int j = 1; j <= runs; ++j) {
    NewmarkSettings run_settings = settings;
    run_settings.step = H / j;
    tableau.add(sampledNewmarkRun(model, run_settings, q0, v0, j, outputs, progress), run_settings.step);
  }
  if (runs >= kProbedRuns) tableau.addRoundOffProbe(roundOffProbe(model, settings, runs, q0, v0, outputs, progress));
  return estimatedRun(model, settings, tableau);
}

std::vector<SampledRun> roundOffProbe(const Model& model, const NewmarkSettings& macro, int runs,
                                      const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, long outputs,
                                      const std::function<void(double)>& progress) {
  std::vector<SampledRun> repeats;
  for (int i = 2; i <= runs; ++i) {
    NewmarkSettings repeat = macro;
    repeat.step = uniformStep(macro) / i * (1.0 + kRoundOffProbeStretch);
    repeat.end_time = macro.end_time * (1.0 + kRoundOffProbeStretch);
    repeats.push_back(sampledNewmarkRun(model, repeat, q0, v0, i, outputs, progress));
  }
  return repeats;
}

EstimatedRun estimatedRun(const Model& model, const NewmarkSettings& settings, const ExtrapolationTableau& tableau) {
  EstimatedRun result;
  result.steps = tableau.steps();
  result.order = tableau.order();
  result.trajectory = sampledTrajectory(model, settings, tableau.result());
  const Trajectory check = sampledTrajectory(model, settings, tableau.check());
  result.q_error = result.trajectory.q - check.q;  // result − exact ≈ T_{j,j−1} − T_{j,j}
  result.v_error = result.trajectory.v - check.v;
  result.sensor_error = result.trajectory.sensors - check.sensors;
  if (tableau.probed()) {
    // The floor added to each estimate's magnitude (its sign stays the truncation part's).
    const auto add = [](Eigen::MatrixXd& estimate, const Eigen::MatrixXd& floor) {
      const Eigen::ArrayXXd magnitude = estimate.array().abs() + floor.array();
      estimate = (estimate.array() < 0.0).select(-magnitude, magnitude).matrix();
    };
    const Eigen::MatrixXd q_floor = tableau.roundOffFloor(&SampledRun::q);
    add(result.q_error, q_floor);
    add(result.v_error, tableau.roundOffFloor(&SampledRun::v));
    const Eigen::MatrixXd repeated = sampledTrajectory(model, settings, tableau.repeatedResult(tableau.rows())).sensors;
    add(result.sensor_error, floorOfTwoRoundings(result.trajectory.sensors - repeated, true));
    result.round_off_floor = q_floor.size() ? q_floor.maxCoeff() : 0.0;
  }
  return result;
}

}  // namespace mbsopt
