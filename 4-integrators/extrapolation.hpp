// Global extrapolation of the trapezoidal Newmark scheme, and the global error estimates it gives
// (docs/integrators.md §2-3).
//
// The global error of a run at step h expands in powers of h at every point of its grid:
//     y_h(t) = y(t) + e_{p₁}(t) h^{p₁} + e_{p₂}(t) h^{p₂} + …
// with p = 2, 4, 6, … for the trapezoidal rule (β = 1/4, γ = 1/2), a symmetric one-step method
// (Hairer, Nørsett and Wanner, Solving ODEs I, §II.8-9), and p = 2, 3, 4, … once cut joints are closed
// at position level: the projections of q̇ and q̈ after each step break the symmetry (measured on the
// four-bar: an h³ term; errorExponents). Runs at H/1, H/2, H/3, … (the harmonic sequence, the
// cheapest) meet at the multiples of H. The combination of runs first + 1 … j with Σ c_i = 1 and
// Σ c_i (1/i)^{p_m} = 0 for the first j − first − 1 powers (extrapolationWeights) cancels those terms:
// the result T_{j,j−1} (runs 2 … j) is of order p_{j−1}, and T_{j,j} − T_{j,j−1} (T_{j,j}: all j runs,
// of order p_j) is its error to within a factor 1 + O(H), the estimate it is reported with.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <limits>
#include <optional>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/integrators/newmark.hpp"

namespace mbsopt {

/// A Newmark run kept at every `stride`-th step only: its state at t = m·stride·h, m = 0 … outputs.
struct SampledRun {
  Eigen::VectorXd time;
  Eigen::MatrixXd q, v, a, lambda;  ///< one column per kept time point
  IntegratorStatistics statistics;
};

/// `run`'s counts added to `sum`, its largest closure error and residual kept where larger.
void addStatistics(IntegratorStatistics& sum, const IntegratorStatistics& run);

/// Runs `settings` (its step h, from t = 0) from (q0, v0), keeping every `stride`-th point, `outputs`
/// of them after t = 0. `progress(t)` is called after each step. SimulationError as simulate().
SampledRun sampledNewmarkRun(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                             const Eigen::VectorXd& v0, long stride, long outputs,
                             const std::function<void(double)>& progress = {});

/// What an error may be, per entry y of a coordinate (or rate), as IDA weights it:
/// |e| ≤ absolute + relative·|y|.
struct ErrorTolerance {
  double absolute = 1e-6;
  double relative = 0.0;
};

/// max over the entries of |error| / (absolute + relative·|value|): at most 1 where `error` meets it.
double weightedErrorNorm(const Eigen::MatrixXd& error, const Eigen::MatrixXd& value, const ErrorTolerance& tolerance);

/// A result with its estimated global error.
struct EstimatedRun {
  /// At the kept time points: q, q̇, q̈, λ and the sensors; `statistics` summed over every run made.
  Trajectory trajectory;
  /// Estimated global error of each entry of trajectory.q, trajectory.v and trajectory.sensors (same
  /// shapes), signed as every estimate of mbsopt: the result minus the exact value.
  Eigen::MatrixXd q_error, v_error, sensor_error;
  std::vector<double> steps;  ///< the step of every Newmark run made, in order
  int order = 2;              ///< of the result in h (2: plain Newmark)
  /// The largest round-off floor of a coordinate included in q_error, when it was measured (an
  /// extrapolation of kProbedRuns runs or more; ExtrapolationTableau): q_error, v_error and
  /// sensor_error are then the truncation estimate with the floor added to its magnitude.
  std::optional<double> round_off_floor;

  double positionError() const;  ///< largest estimated |error| of a coordinate (its unit: m or rad)
  double velocityError() const;  ///< largest estimated |error| of a rate
};

/// Keeps only the time points `kept` (increasing) of a result and of its estimates (the step
/// matrices are dropped).
void keepPoints(EstimatedRun& run, const std::vector<Eigen::Index>& kept);
/// The global error of `trajectory`, a run of `settings` from (q0, v0) (β = 1/4, γ = 1/2: the
/// trapezoidal rule), estimated from a second run at h/2: e_h = 4/3 (y_h − y_{h/2}) at each of its
/// points (with settings.time_grid: each of its steps split in two). Returns the trajectory (moved)
/// with the estimate; `steps` = {h, h/2}.
EstimatedRun estimateGlobalError(const Model& model, const NewmarkSettings& settings, Trajectory trajectory,
                                 const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                 const std::function<void(double)>& progress = {});

/// The powers of h in a scheme's error expansion, from the first: 2, 4, 6, … for the trapezoidal rule
/// itself (a model without cut joints); 2, 3, 4, … with cut joints closed at position level, whose
/// projections of q̇ and q̈ after each step break the symmetry: on the four-bar the error of a first
/// elimination of h² falls as h³ (docs/integrators.md).
std::vector<int> errorExponents(const Model& model, const NewmarkSettings& settings);

/// The most runs an extrapolation combines: the weights grow with them (with cut joints Σ|c_i| is 57 for
/// the result of 6 runs, 518 for 8, 5e4 for 12) and multiply the runs' round-off (measured and added to
/// the estimate: ExtrapolationTableau; docs/integrators.md §5).
inline constexpr int kMaxExtrapolationRuns = 8;

/// The weights of runs first + 1 … runs (1-based; run i at H/i) in the combination that keeps a
/// constant and cancels the first runs − first − 1 terms h^{p_m} of the expansion:
/// Σ c_i = 1, Σ c_i (1/i)^{p_m} = 0. What the tableau, and the design functionals' extrapolation, combine.
Eigen::VectorXd extrapolationWeights(const std::vector<int>& exponents, int first, int runs);

/// How much longer the round-off probe's steps are than the runs it repeats (relative): a few ulps,
/// enough for every step to round differently, far too little to move the truncation error (by 2·16ε
/// of it) or the time points (by 16ε·t).
inline constexpr double kRoundOffProbeStretch = 16.0 * std::numeric_limits<double>::epsilon();
/// Combinations of this many runs or more measure their round-off (ExtrapolationTableau::addRoundOffProbe).
/// With fewer, the estimate sees enough of it: T_{3,2}'s weights amplify the runs' round-off 2.0 times
/// (root sum of squares), the estimate T_{3,3} − T_{3,2} weighs it with 0.70; a result of two runs is the
/// run at H/2 itself (docs/integrators.md §5).
inline constexpr int kProbedRuns = 4;

/// The runs at H/1, H/2, H/3, … of one macro step H, and their combinations: the j runs so far give
/// T_{j,j−1}, the combination of runs 2 … j that cancels the first j − 2 terms of the expansion
/// (of order p_{j−1}), and T_{j,j}, that of all j runs (of order p_j), whose difference from it is its
/// error estimate.
///
/// That estimate sees the truncation error, not the round-off the weights amplify: each run carries
/// its own round-off, independent between runs (their steps differ), and the result's is about
/// ‖(c_i r_i)‖₂, c = weights(1) (‖c‖₂ = 33 for six runs with cut joints, where the estimate's weights,
/// T_{j,j} − T_{j,j−1}, have 6.5). The probe repeats the runs the result combines (2 … P) at steps
/// kRoundOffProbeStretch longer, which round differently at every step: the same combination of the
/// repeats differs from the result by √2 times its round-off, and roundOffFloor() is that difference's
/// largest magnitude up to each time point over √2. One run repeated does not do: on a mechanism
/// passing singular configurations a run's round-off is set by a few passages and varies tenfold
/// between roundings (docs/integrators.md §5).
class ExtrapolationTableau {
 public:
  explicit ExtrapolationTableau(std::vector<int> exponents) : exponents_(std::move(exponents)) {}
  /// Adds the run at H/(rows() + 1) (its step `step`), kept at the multiples of H.
  void add(SampledRun run, double step);
  int rows() const { return static_cast<int>(runs_.size()); }
  /// The order of result(): p_{j−1} for j = rows() ≥ 2.
  int order() const { return exponents_.at(static_cast<std::size_t>(rows() - 2)); }
  /// T_{j,j−1} (q, q̇, q̈, λ combined; time and statistics of the last run), j = rows() ≥ 2.
  SampledRun result() const { return combination(1); }
  /// T_{j,j}, of order p_j: T_{j,j} − T_{j,j−1} is the result's estimated error.
  SampledRun check() const { return combination(0); }
  /// Every run's statistics summed.
  const IntegratorStatistics& statistics() const { return statistics_; }
  /// Every run's step, in order.
  const std::vector<double>& steps() const { return steps_; }
  /// extrapolationWeights(exponents, first, rows()).
  Eigen::VectorXd weights(int first) const { return extrapolationWeights(exponents_, first, rows()); }

  /// Adds the round-off probe: runs 2 … rows() repeated (roundOffProbe; their statistics count).
  /// std::logic_error unless there are rows() − 1 of them.
  void addRoundOffProbe(std::vector<SampledRun> repeats);
  bool probed() const { return !repeats_.empty(); }
  /// The runs the probe repeated (its P); 0 without a probe.
  int probedRuns() const { return probed() ? static_cast<int>(repeats_.size()) + 1 : 0; }
  /// T_{runs,runs−1} of the repeats (2 ≤ runs ≤ probedRuns(); std::logic_error otherwise).
  SampledRun repeatedResult(int runs) const;
  /// The round-off floor of the result of `runs` runs (default rows(); at most probedRuns()) in `part`
  /// (&SampledRun::q or &SampledRun::v): the largest |T_{runs,runs−1} − the same of the repeats| of each
  /// entry up to each time point, over √2. Zero without a probe.
  Eigen::MatrixXd roundOffFloor(Eigen::MatrixXd SampledRun::*part, int runs = 0) const;

 private:
  /// The runs from `first` (0-based) on, combined by weights(first).
  SampledRun combination(int first) const;
  std::vector<int> exponents_;
  std::vector<SampledRun> runs_;
  std::vector<SampledRun> repeats_;  ///< runs 2 … P repeated by the round-off probe
  std::vector<double> steps_;
  IntegratorStatistics statistics_;
};


/// The trajectory of a sampled (and perhaps combined) state: q and q̇ moved back onto b(q) = 0 and
/// ḃ = 0 (assemble(); for a combination of runs the correction is far below their error), the
/// sensors evaluated there, `statistics` as given.
Trajectory sampledTrajectory(const Model& model, const NewmarkSettings& settings, SampledRun run);

/// The tableau's result T_{j,j−1} with its estimated errors T_{j,j} − T_{j,j−1} (q, q̇ and sensors, each
/// combination's q and q̇ moved back onto the closure first), and with a probe the round-off floor added
/// to their magnitudes (the sensors' from those of the result and of its repeat).
EstimatedRun estimatedRun(const Model& model, const NewmarkSettings& settings, const ExtrapolationTableau& tableau);

/// `runs` (2 … kMaxExtrapolationRuns) Newmark runs at H/1, H/2, …, H/runs (H = uniformStep(settings),
/// the macro step that ends at settings.end_time) from (q0, v0), combined at the multiples of H into
/// T_{runs,runs−1}, of order p_{runs−1} (2(runs − 1) without cut joints, runs with them), with its
/// error estimate T_{runs,runs−1} − T_{runs,runs}, and from kProbedRuns runs on its round-off floor
/// (runs 2 … runs once more: roundOffProbe) added to the estimate's magnitude. The combined q and q̇ are moved
/// back onto the closure and its derivative (assemble(); the error that removes is the estimate's
/// order squared), then the sensors are evaluated there. std::invalid_argument unless β = 1/4,
/// γ = 1/2 and the loops are closed at position level; SimulationError from a run.
EstimatedRun extrapolatedNewmark(const Model& model, const NewmarkSettings& settings, int runs,
                                 const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                 const std::function<void(double)>& progress = {});

/// The round-off probe of the first `runs` runs of the macro step H = uniformStep(macro) (ExtrapolationTableau):
/// runs 2 … `runs` again, run i at (H/i)(1 + kRoundOffProbeStretch) to an end time stretched alike (the
/// same number of steps, a few ulps longer each), kept at every i-th step, `outputs` of them.
std::vector<SampledRun> roundOffProbe(const Model& model, const NewmarkSettings& macro, int runs,
                                      const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, long outputs,
                                      const std::function<void(double)>& progress = {});

/// Why runs at h and h/2 cannot estimate a run's error (empty when they can): the symmetric scheme,
/// whose error is even in h, every step's Newton iterate accepted on a test of its own error (not
/// --fast-newton). Newton stopped at a fraction κ of the truncation error
/// (newton_truncation_fraction) leaves the estimate off by about κ: allowed. `who` names what needs
/// it in the message (the adaptive integrator's error estimates need the same).
std::string halvingDefect(const NewmarkSettings& settings, const std::string& who);
/// Why a setting cannot be extrapolated (empty when it can): halvingDefect's conditions, and every step
/// solved to newton_tolerance: Newton's errors at a fraction of the h² truncation error would cap the
/// extrapolation's higher orders.
std::string extrapolationDefect(const NewmarkSettings& settings, const std::string& who = "extrapolation");

}  // namespace mbsopt
