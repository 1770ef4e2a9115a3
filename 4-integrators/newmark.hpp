// Implicit Newmark integration in residual form (paper §4.3, (26)-(33)) with Newton iterations on
// the accelerations at t + h, and closed loops through the SVD partition (41)-(48).
//
// Per step (docs/design.md §3): unknowns q̈ₙ₊₁ (free coordinates) and λₙ₊₁, with
//     qₙ₊₁ = q̃ + βh² q̈ₙ₊₁,   q̃ = qₙ + h q̇ₙ + (½ − β) h² q̈ₙ                         (32)
//     q̇ₙ₊₁ = ṽ + γh q̈ₙ₊₁,    ṽ = q̇ₙ + (1 − γ) h q̈ₙ
//     f(q̈ₙ₊₁, q̇ₙ₊₁, qₙ₊₁, tₙ₊₁) + Bᵀλₙ₊₁ = 0                                         (37)
//     b(qₙ₊₁, tₙ₊₁) / (βh²) = 0        (position-level closure; the paper's (38) is an option)
// Newton matrix [J Bᵀ; B 0] with J = M + γh C_T + βh² K_T (33), kept while Newton contracts
// (modified Newton). With position-level closure every step factors M(qₙ₊₁) for its projections,
// and J = M lets that factorization serve the next step's iterations: the tangent part (AD) joins
// J only when the contraction asks for it. After convergence the velocities
// and accelerations are projected onto the velocity- and acceleration-level constraints
// (minimum-norm correction through the same SVD), which removes the weak instability of the
// trapezoidal rule on index-3 equations (the ALI3-P idea).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/scalar.hpp"
#include "mbsopt/model/workspace.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/integrators/newton_convergence.hpp"
#include "mbsopt/integrators/newton_predictor.hpp"
#include "mbsopt/integrators/run_checks.hpp"
#include "mbsopt/integrators/step_outcome.hpp"
#include "mbsopt/integrators/trajectory.hpp"

namespace mbsopt {

enum class ClosureLevel {
  Position,     ///< b(qₙ₊₁) = 0 each step, with velocity/acceleration projection (default)
  Acceleration  ///< the paper's (38): B q̈ + Ḃ q̇ = 0 only; positions drift (for comparison)
};

/// Longest run the integrator accepts: the trajectory keeps q, q̇, q̈ and λ of every step in
/// memory (10⁷ steps of a 10-coordinate model are ~5 GB).
inline constexpr double kMaxNewmarkSteps = 1e7;
/// Most memory a stored trajectory may take (trajectoryBytes), 4 GiB.
inline constexpr double kMaxTrajectoryBytes = 4.0 * 1024 * 1024 * 1024;

/// The fraction κ of NewmarkSettings::newton_truncation_fraction that `simulate --fast-steps` and
/// the Simbody benchmark take. Newton's errors are alike from step to step (its start is biased
/// the same way), so they add up where the truncation errors partly cancel: on the four-bar at
/// h = 5 ms κ = 1e-2 made the global error 17 % larger, 1e-3 0.4 % (at h = 1 ms: 1 %, 0.2 %), with
/// 2.3 times fewer Newton iterations than at newton_tolerance (Andrews' squeezer: 2.1 times, 0.0 %).
inline constexpr double kNewtonTruncationFraction = 1e-3;

struct NewmarkSettings {
  /// h [s], fixed (unless time_grid is set): the longest step a run takes. A run of T = end_time
  /// takes N = ⌈T/h⌉ equal steps of T/N (uniformStep), so that its last time point is T and every
  /// functional over the run is one over [0, T]; T/N = h where T/h is whole.
  double step = 1e-3;
  double end_time = 1.0;   ///< T [s]
  /// When set, the run's time points instead of the multiples of the step: t₀ = 0, then strictly
  /// increasing, the last at end_time (where the run ends). A variable step sequence, as an
  /// adaptive run chose it (adaptive_newmark.hpp), replayed exactly: its exact gradients are those of
  /// this sequence. Shared, so that copies of the settings do not copy it.
  std::shared_ptr<const std::vector<double>> time_grid;
  double beta = 0.25;      ///< Newmark β
  double gamma = 0.5;      ///< Newmark γ
  /// On ‖Δq̈‖∞ relative to 1 + ‖q̈‖∞ (‖q̈‖∞ capped at 2‖q̈ₙ‖∞ + 1, the last accepted step's), or
  /// below the increments' round-off floor (the closure rows' round-off through B⁺ over βh²). An
  /// iterate whose every residual row is at its round-off level is accepted too (newton_convergence.hpp).
  /// The iterate after a step's first solve, whose contraction rate that step has not measured, is
  /// accepted on this tolerance (above the floor) only when a recent step measured a rate ≤ 0.05:
  /// its error, about the rate times its increment, is then a twentieth of the tolerance.
  double newton_tolerance = 1e-10;
  int max_newton_iterations = 30;
  /// Singular values of B below this fraction of the largest are dropped. About √ε: in a direction
  /// below it, round-off in the closure (ε times the model's reach, over βh²) moves the solution by
  /// more than √ε, so near a singular configuration the dynamics, not the noise, decides the motion
  /// there (IFToMM A02 released flat at h = 2e-3 diverged at a flat passage with 1e-10).
  double svd_threshold = 1e-8;
  /// Accept the first Newton iterate also when its increment is above tolerance, whenever the
  /// contraction rate measured on a recent step (×10) says the next increment would be below it
  /// (DASSL/IDA's test). About 1.3 instead of 1.7 iterations per step on the tramway, but the
  /// trajectory then depends on those decisions at the round-off floor (1e-8..1e-9 relative): off by
  /// default, since design gradients need smoothness.
  bool accept_by_contraction_rate = false;
  /// κ ≥ 0. When positive, Newton also stops once its iterate's error, moved into q by βh², is below κ
  /// times the step's local truncation error |β − 1/6| h² ‖q̈ₙ₊₁ − q̈ₙ‖∞ (the estimate of
  /// Zienkiewicz and Xie): solving the step's equations more precisely than they approximate the
  /// motion buys nothing, as IDA stops Newton at a fraction of its local error test (κ: see
  /// kNewtonTruncationFraction); Newton's iterations at coarse steps fall 2-3×. 0 (the default)
  /// solves every step to newton_tolerance: design gradients, finite differences and the
  /// extrapolation need the discrete equations solved, not approximated (extrapolationDefect).
  double newton_truncation_fraction = 0.0;
  /// Start each step's SVD of B from the last step's rotations and stop it at an orthogonality of
  /// 1e-8 (SvdPartition::updateConstraintJacobian): about 3 Jacobi sweeps a step instead of 6 on
  /// Andrews' squeezer. The partition then depends on the steps before it, and the exact gradients, which factor
  /// B again when the run kept no step matrices, would not match those of a run that kept them to the
  /// bit: off by default, as design problems need.
  bool reuse_svd_rotations = false;
  ClosureLevel closure = ClosureLevel::Position;
  /// After every step, a run stops with an error when a closure row exceeds this: a coincidence row
  /// (metres) relative to the reach of its two frames, an orthogonality row (a cosine) absolutely.
  /// 0 means the level's default (closureTolerance()): 1e-6 with the position closure, where the rows
  /// are at round-off after every step; 1e-2 with the acceleration closure, whose positions drift by
  /// design and are only kept from coming apart.
  double closure_tolerance = 0.0;
  /// In a run where no force does work (no damping, actuation, driven joint or moving spring rest),
  /// a run stops with an error when the mechanical energy grows by more than this fraction of its
  /// scale (kinetic energy at the start, spring energy at the start and the work of gravity over the
  /// model's reach); the Newmark family may only dissipate it.
  double energy_tolerance = 0.1;
  /// From this many free coordinates on, M(q) for the projections and for Newton with J = M is
  /// factored by the articulated-body recursion and the augmented system solved through the range
  /// of Bᵀ (O(n) per factorization and solve for a few constraint rows; svd_partition.hpp), not
  /// formed by the CRBA and LU-factored on the free directions (O(n³)). The solutions are the same
  /// to round-off; below this size the dense path is the faster (bench_dynamics:
  /// BM_ClosedChainMassFactorization). The dense path is kept when the constraints' rank exceeds half
  /// the free coordinates, when J has its tangent part, and when M is nearly singular (a coordinate
  /// that moves almost no inertia of its own, articulated_body.hpp).
  int articulated_mass_from = 24;
};

/// The number of equal steps of at most `step` that cover [0, end_time]: ⌈end_time/step⌉, at least
/// one (a ratio within 1e-12 of a whole number counts as that number: the times' round-off).
long stepsToCover(double end_time, double step);
/// The largest step of at most `step` that divides [0, end_time] into whole steps:
/// end_time / stepsToCover(end_time, step). Idempotent.
double uniformStep(double step, double end_time);
/// The step of a run on the settings' uniform grid: uniformStep(settings.step, settings.end_time).
inline double uniformStep(const NewmarkSettings& settings) { return uniformStep(settings.step, settings.end_time); }

/// `settings` with each step solved only as precisely as it approximates the motion (`simulate
/// --fast-steps`, docs/integrators.md §10): newton_truncation_fraction = kNewtonTruncationFraction and
/// reuse_svd_rotations.
NewmarkSettings withFastSteps(NewmarkSettings settings);

/// Thrown when a step cannot be completed; says when, where and by how much.
/// What is wrong with a set of settings: the field (named as in a scene file's `settings`:
/// "step", "end_time", "beta", "gamma", "newton_tolerance", "max_newton_iterations",
/// "svd_threshold", "closure_tolerance", "energy_tolerance") and why. An empty field means the settings are valid.
struct SettingsDefect {
  std::string field;
  std::string message;
};
SettingsDefect settingsDefect(const NewmarkSettings& settings);
/// The memory NewmarkIntegrator::simulate takes for its Trajectory: per time point t, q, q̇, q̈, λ,
/// the unprojected q̇ and q̈, the closure error and the iteration count; with `step_matrices`, M and
/// B where the run forms them (formsStepMatrices).
double trajectoryBytes(const Model& model, const NewmarkSettings& settings, bool step_matrices = false);
/// The memory of one time point of it.
double bytesPerTimePoint(const Model& model, const NewmarkSettings& settings, bool step_matrices = false);
/// Whether a run of `model` with `settings` forms M and B at every step, so that
/// NewmarkIntegrator::keepStepMatrices keeps them.
bool formsStepMatrices(const Model& model, const NewmarkSettings& settings);
/// Where each part of a time point's column of Trajectory::step_matrices starts, for `free` free
/// coordinates and `constraints` closure rows, and the column's length.
struct StepMatrixLayout {
  StepMatrixLayout(Eigen::Index free, Eigen::Index constraints)
      : jacobian(free * free),
        partition(jacobian + constraints * free),
        size(partition + SvdPartition::storedFactoredSize(constraints, free)) {}
  Eigen::Index mass = 0;   ///< M (free × free, column-major)
  Eigen::Index jacobian;   ///< B (constraints × free)
  Eigen::Index partition;  ///< B's partition with its factorization of M (SvdPartition::storeFactored)
  Eigen::Index size;
};
/// The same run at half the steps: step / 2, and with a time grid every one of its steps split in two.
NewmarkSettings halvedSteps(NewmarkSettings settings);
/// The largest step of a run: settings.step, or the largest of its time grid's.
double largestStep(const NewmarkSettings& settings);
/// settings.closure_tolerance, or the default of its closure level when it is 0.
double closureTolerance(const NewmarkSettings& settings);

class NewmarkIntegrator {
 public:
  /// The integrator keeps a reference to `model`, which must outlive it and stay unchanged.
  NewmarkIntegrator(const Model& model, NewmarkSettings settings);
  NewmarkIntegrator(Model&& model, NewmarkSettings settings) = delete;

  /// Sets the state at t0: driven coordinates take their prescribed motion, velocities are projected
  /// onto the velocity constraints, and consistent accelerations and multipliers are computed.
  /// q0 must already satisfy the closure equations, with weld cuts in their intended orientation
  /// (see assemble()); otherwise std::invalid_argument.
  void initialize(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, double t0 = 0.0);
  /// Advances one step: to the next multiple of uniformStep(settings), or to the next point of settings.time_grid.
  void step();
  /// Advances one step to t_next > time() (its size t_next − time()); a SimulationError carrying
  /// the step's outcome when it fails.
  void advanceTo(double t_next);
  /// Solves the step to t_next > time() without accepting it. Converged: q(), v(), a(), lambda() are
  /// Newton's solution at t_next, before the projections, and acceptStep() or rejectStep() comes
  /// next, nothing else. Any other outcome says why (smallerStepMayHelp(status) says whether a
  /// smaller step may succeed) and leaves the integrator as it was before the attempt.
  StepOutcome attemptStep(double t_next);
  /// Accepts the attempted step: the projections onto the velocity and acceleration constraints and
  /// the checks of run_checks.hpp. Anything but Converged ends the run: the outcome says why.
  StepOutcome acceptStep();
  /// Returns to the state before the attempted step.
  void rejectStep();
  /// initialize + stepsToCover(end_time, step) steps of uniformStep(settings), the last ending at
  /// end_time, or the steps of settings.time_grid, storing every step.
  /// `progress(t)` is called after each step.
  Trajectory simulate(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                      const std::function<void(double)>& progress = {});
  /// The same into `out`, sized once before time point 0 is stored; `stored(k)` is called on this
  /// thread as soon as time point k is complete in out (its columns, its sensor row), k = 0, 1, …
  /// Another thread may read what `stored` published while the next steps are written: nothing
  /// already stored moves or changes.
  void simulate(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, Trajectory& out,
                const std::function<void(long)>& stored);

  /// Whether simulate() stores each time point's M(q), B(q), B's partition and its factorization of
  /// M (Trajectory::step_matrices), which the exact gradients would otherwise compute again at every
  /// point. Kept only where they are formed:
  /// cut joints closed at position level, M dense (fewer free coordinates than
  /// NewmarkSettings::articulated_mass_from). Off by default.
  void keepStepMatrices(bool keep) { keep_step_matrices_ = keep; }

  double time() const { return t_; }
  long stepCount() const { return step_count_; }
  const Eigen::VectorXd& q() const { return q_; }
  const Eigen::VectorXd& v() const { return v_; }
  const Eigen::VectorXd& a() const { return a_; }
  const Eigen::VectorXd& lambda() const { return lambda_; }
  double closureError() const { return closure_error_; }
  int lastNewtonIterations() const { return last_iterations_; }
  const IntegratorStatistics& statistics() const { return stats_; }
  /// The settings as the run takes them: `step` is uniformStep of those given.
  const NewmarkSettings& settings() const { return settings_; }
  /// q̈ at time(), the start of the step being attempted (after rejectStep(), the accepted one's).
  const Eigen::VectorXd& acceptedAcceleration() const { return a_accepted_; }

 private:
  enum class Refresh { None, Mass, Tangents };
  bool newton(bool fresh_jacobian);
  /// The Newton target newton_truncation_fraction sets, from the current iterate (newmark.hpp).
  double truncationTarget() const;
  /// advanceTo / attemptStep with the step h (t_next − time() when not given: a uniform grid gives
  /// h exactly, where t_next − time() carries the round-off of the times).
  void advance(double t_next, std::optional<double> h);
  bool attempt(double t_next, std::optional<double> h);
  /// attempt() as an outcome: a SimulationError from inside the step, or Newton's failure, becomes
  /// the outcome, with the integrator returned to the state before the attempt.
  StepOutcome attemptOutcome(double t_next, std::optional<double> h);
  /// The work of acceptStep(); a SimulationError when a check fails.
  void accept();
  /// Makes h the step of the next attempt: J's tangent part follows it (γh C_T + βh² K_T) once it has
  /// moved far enough, and Newton's start forgets its history (an extrapolation at equal spacing) when h
  /// changes by more than a factor of 2.
  void setStepSize(double h);
  void updateIterationMatrix();
  void updateMassMatrix();
  /// M(q_) by the CRBA into mass_, and J_ from it (with its tangent part when in use). Needs ws_ as
  /// updateMassMatrix does.
  void formMassMatrix();
  void updateConstraintPartition();
  void setDriven(double t);
  void projectOntoConstraints();
  void checkInitialClosure() const;
  void evaluateResidual();    ///< f_ and its free rows r_free_ at the current state
  void applyNewmarkUpdate();  ///< q, q̇ of the free coordinates from q̈ and the predictors (32)
  /// Cut joints closed at position level: every step then factors M(qₙ₊₁) for its projections,
  /// and the closure rows are positions (with a round-off floor, incrementRoundoffFloor).
  bool closesLoopsAtPositionLevel() const;
  /// The size of a Newton increment of q̈ that round-off in the closure rows alone can cause.
  double incrementRoundoffFloor(double beta_h2) const;
  void measureClosure();
  /// Every sensor at the current state, into `values`. Needs ws_ to hold the geometry with the joint
  /// axes at q_, as initialize() and step() leave it.
  void evaluateSensors(SensorRow values);
  /// The checks of run_checks.hpp after a step; throws SimulationError when one fails.
  void checkStep();
  [[noreturn]] void fail(StepStatus status, const std::string& reason, const Eigen::VectorXd& residual) const;
  /// After Newton failed on the step to t: when no configuration at t closes the loops (assemble()
  /// from the last accepted one leaves a closure error: a link too short for a driven motion), a
  /// SimulationError that says so at the cut joint, distinct from a step too large for Newton;
  /// otherwise nothing.
  void failIfLoopsCannotClose(double t) const;
  /// failIfLoopsCannotClose as an outcome: LoopCannotClose naming the cut, or Converged.
  StepOutcome loopsCloseAt(double t) const;
  /// The element of the coordinate that `matrix` resists least within the free directions.
  std::string unresistedCoordinate(const Eigen::MatrixXd& matrix) const;
  /// For an iteration matrix singular on the free directions: names the coordinate it leaves free.
  [[noreturn]] void failSingular(const std::string& reason, const Eigen::MatrixXd& matrix) const;
  /// Factors V₂ᵀ matrix V₂ in the partition; a singular one ends the run naming `name`.
  void factor(const Eigen::MatrixXd& matrix, const char* name);
  /// Factors M as updateMassMatrix left it: its articulated-body factorization in the partition,
  /// or, when that one is not taken or its Schur complement is singular, factor(mass_, name).
  void factorMass(const char* name);

  const Model& model_;
  NewmarkSettings settings_;
  Workspace<double> ws_;
  Workspace<AdScalar> ad_ws_;
  SvdPartition partition_;
  NewtonRoundoff roundoff_;
  EnergyWatch energy_watch_;
  ClosureCheck closure_check_;
  const Eigen::VectorXd no_rows_;  ///< an empty closure: only the dynamic rows are tested
  TangentMatrices tangents_;
  Eigen::MatrixXd J_;  ///< free × free iteration matrix (33), kept between steps until it goes stale
  Eigen::MatrixXd mass_, tangent_part_;  ///< J = M + (γh C_T + βh² K_T), the parts refreshed separately
  Eigen::MatrixXd damping_, stiffness_;  ///< C_T, K_T on the free coordinates, for tangent_part_ at a new h
  double h_ = 0.0;                       ///< the step being taken (settings_.step unless the steps vary)
  double matrix_step_ = 0.0;             ///< the h at which tangent_part_ was formed
  bool tangents_in_use_ = false;  ///< J has its tangent part (else J = M, see initialize())
  ArticulatedBodyFactorization articulated_mass_;
  bool mass_by_recursion_ = false;  ///< J = M(q), held by articulated_mass_ (J_ and mass_ are stale)

  std::vector<int> free_;
  double t_ = 0.0;
  long step_count_ = 0;
  Eigen::VectorXd q_, v_, a_, lambda_;
  Eigen::VectorXd v_unprojected_, a_unprojected_;  ///< q̇, q̈ before this step's projections
  Eigen::VectorXd q_pred_, v_pred_;  // full-size predictors q̃, ṽ
  Eigen::VectorXd a_start_, lambda_start_, lambda_previous_;
  Eigen::VectorXd a_accepted_;  ///< q̈ₙ, the start of the last retry
  Eigen::VectorXd q_accepted_, v_accepted_, lambda_before_;  ///< qₙ, q̇ₙ and λₙ₋₁, for rejectStep()
  Eigen::VectorXd lambda_older_;  ///< λₙ₋₂, for the quadratic start of λ
  double t_accepted_ = 0.0;
  NewtonPredictor predictor_;          ///< Newton's start, from its converged free accelerations
  Eigen::VectorXd free_accelerations_;  ///< scratch: q̈ on the free coordinates, for predictor_
  Eigen::VectorXd f_, closure_, r_free_, da_, dlambda_, correction_;
  Eigen::VectorXd position_closure_;  ///< b(q) at the last accepted q (or at q₀)
  Eigen::MatrixXd B_free_;
  bool reduced_dirty_ = true;  ///< the partition must factor J again (J or B changed)
  bool keep_step_matrices_ = false;
  double t0_ = 0.0;
  double closure_error_ = 0.0;
  int last_iterations_ = 0;
  double last_relative_residual_ = 0.0;  ///< of the last residual evaluated, in units of ε (NewtonRoundoff)
  double acceleration_scale_ = 0.0;  ///< ‖q̈ₙ‖∞ over the free coordinates, the last accepted step's
  double contraction_ = 0.0;  ///< last measured ‖Δₖ‖/‖Δₖ₋₁‖ of the Newton iteration (0: unknown)
  IntegratorStatistics stats_;
};

}  // namespace mbsopt
