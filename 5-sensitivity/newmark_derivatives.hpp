// What the exact gradient methods (`direct`, `adjoint`) share: a design problem simulated at one
// point, and at any time point of its trajectory the derivatives of the Newmark step (32)-(33) — the
// free blocks of M, C_T, K_T and the rows of ∂f/∂b, and with cut joints the derivatives of the
// closure and of the two projections — and the seeds ∂Ψ/∂(q, q̇, q̈) of every transcribed
// constraint (5-sensitivity/README.md, "The discrete map").
#pragma once

#include <Eigen/Core>
#include <condition_variable>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mbsopt/algorithms/svd_partition.hpp"
#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/forward_ad.hpp"
#include "mbsopt/sensitivity/response_jacobian.hpp"

namespace mbsopt {

/// The step derivatives at one converged state, free coordinates only.
struct StepDerivatives {
  Eigen::MatrixXd mass, damping, stiffness;  ///< M, C_T, K_T
  Eigen::MatrixXd parameters;                ///< ∂f/∂b, one column per design variable
};

/// The constraint side of a step with cut joints, free coordinates (m closure equations):
/// B = ∂b/∂q; the derivatives in q (and q̇) of the velocity and acceleration closures at the
/// projected state; and for each projection (Δ its correction, μ its minimum-norm multipliers)
/// G = ∂(M(q)Δ + B(q)ᵀμ)/∂q and P = ∂(M Δ + Bᵀμ)/∂b, which carry its dependence on q and on the
/// design variables through M and B.
struct ClosureDerivatives {
  Eigen::MatrixXd jacobian;                        ///< B; without cut joints it has no rows and the rest is empty
  /// ∂ḃ/∂q at (q_k, q̇_k). It also gives ∂b̈/∂q̇ = 2 ∂ḃ/∂q: b depends on the coordinates alone, so
  /// with ḃ = B q̇ and b̈ = B q̈ + Ḃ q̇, column j of ∂b̈/∂q̇ is Ḃ e_j + (∂B/∂q_j) q̇, and both terms
  /// equal ∂ḃ/∂q_j = (∂B/∂q_j) q̇ because b's second derivatives are symmetric.
  Eigen::MatrixXd velocity_q;
  Eigen::MatrixXd acceleration_q;  ///< ∂b̈/∂q at (q_k, q̇_k, q̈_k)
  Eigen::MatrixXd velocity_projection, acceleration_projection;  ///< G of each projection
  Eigen::MatrixXd velocity_projection_parameters, acceleration_projection_parameters;  ///< P of each
  /// ∂b/∂b, ∂ḃ/∂b, ∂b̈/∂b: how the design variables move the closure itself (m × p). They are not
  /// zero only for a geometric variable (isGeometricParameter); without one they have no columns.
  Eigen::MatrixXd position_parameters, velocity_parameters, acceleration_parameters;
  /// B's SVD partition at the integrator's threshold with M factored (with cut joints), as the
  /// projections' multipliers were computed with it: the sweeps' solves at this point take it
  /// (AugmentedSolver::setConstraintPartition, setFactoredSymmetricMatrix).
  SvdPartition partition;
};

/// ∂Ψ_j/∂q_k, ∂Ψ_j/∂q̇_k, ∂Ψ_j/∂q̈_k: one row per constraint, free coordinates; and the explicit
/// ∂Ψ_j/∂b of the sensors at time point k at a fixed state (a geometric variable moves the point a
/// sensor reads), one column per design variable, or no columns when no variable is geometric; and
/// ∂Ψ_j/∂λ_k, one column per closure equation, for the cut reactions some functional reads, or no
/// columns when none does.
struct ResponseSeeds {
  Eigen::MatrixXd position, velocity, acceleration, parameters, multipliers;
};

/// d(q₀, q̇₀, q̈₀)/db, free coordinates × design variables, and dλ₀/db (closure equations × design
/// variables, the minimum-norm one): the direct method's start. q₀ and q̇₀ depend on b only through
/// a geometric variable that moves a loop (initial_state.hpp).
struct InitialSensitivities {
  Eigen::MatrixXd q, v, a, lambda;
};

class TrajectoryDerivatives {
 public:
  /// Simulates at x, keeping each time point's M and B (Trajectory::step_matrices), unless
  /// `simulated` is that simulation: then it is read where it is (not copied), and must outlive this
  /// object and its copies; its M and B are read when it kept them, computed again otherwise. Throws
  /// std::invalid_argument for cut joints closed at acceleration level. When it simulates with
  /// jobs ≥ 2, the simulation runs on a thread of its own while jobs − 1 threads evaluate the time
  /// points' derivatives, each as soon as its step is stored, from point 1 on (at most kEarlyBytes of
  /// them); the point streams hand those out instead of evaluating them again, the same to the bit.
  TrajectoryDerivatives(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                        const Eigen::VectorXd& x, const DesignResponse* simulated = nullptr, int jobs = 1);

  /// The memory the points evaluated during the simulation may take.
  static constexpr double kEarlyBytes = 256.0 * (1 << 20);
  /// Evaluations that have caught up with the simulation resume when this many new steps are stored.
  static constexpr long kWakeBatch = 16;
  /// How many time points the helpers evaluated during the simulation: points 1 … earlyPoints(),
  /// less any whose evaluation threw (evaluated again, and the error raised, when a sweep asks).
  Eigen::Index earlyPoints() const { return early_.count; }

  Eigen::Index timePoints() const { return response().trajectory.time.size(); }
  double time(Eigen::Index k) const { return response().trajectory.time[k]; }
  Eigen::Index freeCount() const { return static_cast<Eigen::Index>(model_.freeCoordinates().size()); }
  Eigen::Index variableCount() const { return static_cast<Eigen::Index>(parameter_indices_.size()); }
  Eigen::Index functionalCount() const { return static_cast<Eigen::Index>(functionals_.size()); }
  const NewmarkSettings& settings() const { return problem_.scene.settings; }
  /// The step from time point k − 1 to k (k ≥ 1): the settings' uniform step (the integrator's), or
  /// the difference of their time grid's points (a variable step sequence, replayed as simulated).
  double stepSize(Eigen::Index k) const {
    const NewmarkSettings& s = settings();
    if (!s.time_grid) return uniformStep(s);
    return (*s.time_grid)[static_cast<std::size_t>(k)] - (*s.time_grid)[static_cast<std::size_t>(k - 1)];
  }

  Eigen::Index constraintCount() const { return model_.constraintCount(); }
  /// Whether some functional reads a cut reaction: then its seeds carry ∂Ψ/∂λ (ResponseSeeds::multipliers).
  bool readsMultipliers() const { return reads_multipliers_; }

  /// At the state Newton converged to at time point k (before the projections).
  StepDerivatives step(Eigen::Index k);
  /// At the projected state of time point k, with the multipliers that fit it best (the least-squares
  /// λ of f(q, q̇, q̈, λ) = 0): the state of the continuous motion to O(h²), where Newton's q̈* and λ
  /// are off the acceleration closure by O(h).
  StepDerivatives projectedStep(Eigen::Index k);
  /// B = ∂b/∂q at q_k, free columns (no rows without cut joints).
  Eigen::MatrixXd constraintJacobian(Eigen::Index k);
  /// Needs constraintCount() > 0.
  ClosureDerivatives closure(Eigen::Index k);
  ResponseSeeds seeds(Eigen::Index k);
  /// The same into `out`, reusing its storage.
  void seeds(Eigen::Index k, ResponseSeeds& out);
  /// d(q₀, q̇₀, q̈₀)/db: with a geometric variable on a loop, the initial state closed along the
  /// scene's directions (initial_state.hpp) differentiated; then the initial accelerations'
  /// equations f = 0, b̈ = 0 differentiated (as the integrator solves them, in one solve).
  InitialSensitivities initialSensitivities();
  /// The last time point where some functional has a seed weight that is not zero (it depends on the
  /// state there), 0 when there is none after t₀. The seeds of every later point are exact zeros, so
  /// no sweep needs those points: the direct sensitivities stop there, the adjoint starts there.
  Eigen::Index lastSeededPoint() const;

  /// What the sweeps of `direct` and `adjoint` need at time point k and that does not depend on
  /// the sweep: step(k), with cut joints closure(k), and seeds(k).
  struct PointDerivatives {
    StepDerivatives step;
    ClosureDerivatives closure;
    ResponseSeeds seeds;
  };
  class PointStream;

  /// The gradients in the scaled variables from dΨ/db (functionals × design variables, SI): the
  /// variables' scales, the cost b_{k+1}, and the exact column of the artificial variable; with
  /// the values of the simulation they belong to.
  DesignGradient gradient(const Eigen::MatrixXd& dpsi_db) const;

 private:
  const DesignProblem& problem_;
  const std::vector<ConstraintFunctional>& functionals_;
  Eigen::VectorXd x_;
  Model model_;
  const DesignResponse* simulated_;  ///< the caller's simulation at x, or null
  DesignResponse simulation_;        ///< this object's own, without one
  const DesignResponse& response() const { return simulated_ ? *simulated_ : simulation_; }
  std::vector<ParameterIndex> parameter_indices_;  ///< their indices in model_
  /// Per design variable, its direction among the AD passes' parameters, or −1 when f is linear in
  /// it through a force element (a stiffness or a damping): its column of ∂f/∂b is then computed in
  /// double (linearForceParameterColumn), and M and B, so the projections, do not depend on it.
  std::vector<int> ad_parameter_;
  std::vector<ParameterIndex> ad_parameter_indices_;  ///< the model indices of the AD passes' parameters
  /// Whether some linear variable's column reads the frame velocities (linearForceParameterReadsKinematics).
  bool linear_columns_read_kinematics_ = false;
  /// Whether some design variable is geometric (isGeometricParameter): then the closure's own
  /// derivatives in b and the sensors' explicit ones are formed.
  bool geometric_ = false;
  /// Whether some design variable is a number of a driven joint's motion (drivingCoordinate): then
  /// the passes at a time point seed the driven coordinates too (Workspace::driving_model).
  bool drives_ = false;
  /// Sets ws to seed the driven motions at time point k's time, when some variable drives one.
  void driveAt(Eigen::Index k, Workspace<AdScalar>& ws) const;
  /// Whether some functional reads a cut reaction (readsMultipliers): then the seeds carry ∂Ψ/∂λ.
  bool reads_multipliers_ = false;
  std::vector<int> closure_rows_;  ///< 0, …, m − 1
  /// The inputs of the AD passes, listed once: free q, the design parameters f is not linear in, free
  /// q̇ (last, so that a pass of velocities alone can skip what does not depend on them).
  std::vector<AdInput> step_inputs_;
  /// The same followed by free q̈: the inputs of a time point whose sensors are differentiated too.
  std::vector<AdInput> sensed_step_inputs_;
  /// The position of free q̇ in those lists (after free q and the AD parameters): the AD Jacobians'
  /// first column of C_T.
  Eigen::Index firstVelocityInput() const {
    return freeCount() + static_cast<Eigen::Index>(ad_parameter_indices_.size());
  }

  /// The mutable state of the evaluations at a time point: workspaces, and M(q_k), B(q_k) from one
  /// kinematics pass, kept for the time point last asked (a step and its closure share them). One
  /// per thread.
  struct Scratch {
    explicit Scratch(const Model& model) : ws(model), plain_ws(model) {}
    Workspace<AdScalar> ws;
    Workspace<double> plain_ws;  ///< for what needs no AD: M (composite rigid bodies) and B (velocity passes)
    Eigen::Index geometry_point = -1;        ///< the point whose M and B are in mass and jacobian
    Eigen::Index plain_geometry_point = -1;  ///< the point whose geometry is in plain_ws (-1: none)
    Eigen::MatrixXd mass, jacobian;
    // The constants and intermediate results of pointAt's AD passes.
    VectorX<AdScalar> lambda, mu_v, mu_a, projected_v, projected_a, correction_v, correction_a;
    VectorX<AdScalar> f, closure_rates;
    // pointAt's buffers in double: the projections' corrections and multipliers, a vector's free
    // rows, the Jacobian of the AD passes; the sensors selected at a time point and their Jacobians.
    Eigen::VectorXd q, v, closure, plain_correction_v, plain_correction_a, plain_mu_v, plain_mu_a, plain_f, column,
        free_rows;
    Eigen::MatrixXd pass_jacobian;
    std::vector<int> sensor_slot;
    std::vector<const Sensor*> sensors;
    std::vector<ResponseJacobian> sensor_jacobians;
    PointDerivatives point;  ///< an early point before it is packed
  };
  Scratch scratch_;  ///< of the calls on this object's thread
  /// Of the helper threads (a PointStream's, the simulation's), each allocated by the thread that
  /// uses it (helperScratch): from that thread's heap arena, so two threads never write to one cache
  /// line. Allocated together by one thread, they made a simulation beside the evaluations run
  /// 1.6-2.4× slower on a 2-core VM (false sharing), where two processes ran at full speed.
  struct ThreadScratch {
    std::unique_ptr<Scratch> scratch;
    ThreadScratch() = default;
    ThreadScratch(const ThreadScratch&) {}  // a copy's threads allocate their own
    ThreadScratch& operator=(const ThreadScratch&) {
      scratch.reset();
      return *this;
    }
  };
  std::vector<ThreadScratch> thread_scratch_;
  /// Helper t's scratch, created on the calling thread the first time.
  Scratch& helperScratch(std::size_t t);

  /// The time points evaluated during the simulation, before the functionals and so the seeds are
  /// known: every sensor a functional reads is differentiated (functional_sensors_, in that order),
  /// and the seeds are formed when a stream hands the point out (takeEarly). Each point is packed in
  /// a run of `stride` doubles (packPoint): one allocation for them all, none per point, and not
  /// zeroed (the simulation's thread would spend milliseconds writing tens of MB that the
  /// evaluations overwrite). A copy starts without them: its streams evaluate every point.
  struct EarlyPoints {
    std::unique_ptr<double[]> values;  ///< time point k from (k − 1) · stride
    std::vector<char> ready;           ///< per point: evaluated without error, not yet handed out
    Eigen::Index stride = 0;
    Eigen::Index count = 0;  ///< how many were evaluated without error
    EarlyPoints() = default;
    EarlyPoints(const EarlyPoints&) {}
    EarlyPoints& operator=(const EarlyPoints&) {
      *this = EarlyPoints();
      return *this;
    }
    EarlyPoints(EarlyPoints&&) = default;
    EarlyPoints& operator=(EarlyPoints&&) = default;
  };
  EarlyPoints early_;
  std::vector<const Sensor*> functional_sensors_;  ///< the sensors the functionals read, each once
  std::vector<int> functional_sensor_slot_;        ///< per model sensor, its place there, or −1

  /// An upper bound of the doubles packPoint writes for a point of this problem.
  Eigen::Index packedPointSize() const;
  /// A point without its seeds, the Jacobians of the functional sensors, and B's partition with its
  /// factorization of M, at out … end; false when they do not fit.
  static bool packPoint(const PointDerivatives& point, const std::vector<ResponseJacobian>& sensors, double* out,
                        const double* end);
  void unpackPoint(const double* in, PointDerivatives& point, std::vector<ResponseJacobian>& sensors) const;
  /// Simulates into simulation_ on a thread of its own while this thread and jobs − 2 more evaluate
  /// the points already stored into the early store.
  void simulateWhileEvaluating(int jobs);
  /// Point k as evaluated during the simulation, its seeds formed, into `out` (`sensors`: a buffer
  /// for the sensors' Jacobians); false when it was not, or was handed out already.
  bool takeEarly(Eigen::Index k, PointDerivatives& out, std::vector<ResponseJacobian>& sensors);

  /// Hints the processor to bring time point k's state and kept step matrices into its cache, when
  /// the trajectory has that point: a sweep asks for point k while it evaluates its neighbour, which
  /// then finds them there (the first read of a point's matrices otherwise waits for memory: the
  /// sweeps walk 14 MB of them on the tram).
  void prefetch(Eigen::Index k) const;
  /// M(q_k) and B(q_k) into s.mass and s.jacobian: from the trajectory where the simulation kept
  /// them (then no geometry is computed), else computed on s.plain_ws.
  void geometryAt(Eigen::Index k, Scratch& s);
  /// B's partition at the settings' threshold into `partition`, with M factored when B has rows;
  /// throws std::runtime_error when M is singular on B's null space.
  void partitionWithMass(const Eigen::MatrixXd& B, const Eigen::MatrixXd& M, SvdPartition& partition) const;
  /// The geometry of q_k in s.plain_ws, unless it is there already.
  void plainGeometryAt(Eigen::Index k, Scratch& s);
  /// The columns of ∂f/∂b (free rows) of the design variables f is linear in, at (q_k, v), into
  /// `parameters`; the other columns untouched. Computes the geometry of q_k in s.plain_ws when a
  /// column reads it.
  void linearParameterColumns(Eigen::Index k, const Eigen::VectorXd& v, Scratch& s, Eigen::MatrixXd& parameters);
  /// step(k), closure(k) (with cut joints) and seeds(k) together, the AD passes of the first two
  /// shared; into `out`, reusing the storage of its matrices.
  void pointAt(Eigen::Index k, Scratch& s, PointDerivatives& out);
  /// pointAt without the seeds, differentiating the sensors selected in s (selectSensors) too.
  void stepAndClosureAt(Eigen::Index k, Scratch& s, PointDerivatives& out);
  void seedsAt(Eigen::Index k, Scratch& s, ResponseSeeds& out);
  /// ∂Ψ_j/∂φ_k ∂φ/∂y: the weight of constraint j's sensor at time point k.
  double seedWeight(Eigen::Index j, Eigen::Index k) const;
  /// The sensors some constraint is sensitive to at k, each once, into s.sensors and s.sensor_slot;
  /// false when there is none.
  bool selectSensors(Eigen::Index k, Scratch& s) const;
  /// The seeds at k from sensor Jacobians: `slot` gives each model sensor's place in `jacobians`.
  void sensorSeeds(Eigen::Index k, const std::vector<int>& slot, const std::vector<ResponseJacobian>& jacobians,
                   ResponseSeeds& out) const;
  /// Inside a pass of pointAt over sensed_step_inputs_ (inputs first … first + count − 1), with ws at
  /// the kinematics of (q, v, a): each selected sensor's value and its derivatives in those inputs.
  void sensorDerivatives(Scratch& s, const VectorX<AdScalar>& q, const VectorX<AdScalar>& v, const VectorX<AdScalar>& a,
                         Eigen::Index first, Eigen::Index count) const;
};

/// The points of a sweep, from time point `from` to `to` (in either direction, both included), one
/// at a time in that order: jobs − 1 helper threads compute them ahead while the sweep uses them,
/// and when the next one is not ready the sweep's own thread computes the next one nobody has
/// taken, so no thread waits while points remain (the sweep's own work, a few solves a point,
/// overlaps the helpers'). At most kAhead points are held, kRun on one thread. Each thread has
/// workspaces of its own, so the points are the same to the bit whatever the number of threads; a
/// point whose evaluation threw rethrows when the sweep reaches it, as a serial sweep would. The
/// points evaluated during the simulation (earlyPoints()) are handed out directly on the sweep's
/// thread: passed through the helpers, each would cost a wake-up of a helper waiting for a free slot.
class TrajectoryDerivatives::PointStream {
 public:
  /// Points held at once: enough for the helpers to run ahead, little memory (a few kB a point).
  static constexpr long kAhead = 512;
  /// Points the sweep's thread evaluates in a run when it has caught up with the helpers.
  static constexpr long kRun = 64;

  PointStream(TrajectoryDerivatives& derivatives, Eigen::Index from, Eigen::Index to, int jobs);
  ~PointStream();
  PointStream(const PointStream&) = delete;
  PointStream& operator=(const PointStream&) = delete;

  /// The next point in order; valid until the following call.
  const PointDerivatives& next();

 private:
  /// The next point nobody has taken, when it fits in the buffer; −1 otherwise. Needs the lock.
  long take();
  long freeSlots() const;  ///< needs the lock
  /// Whether a helper waiting for free slots has a run of them (or the last points) to take.
  bool helpersMayResume() const;
  /// Evaluates point number `n` of the stream into its slot (outside the lock).
  void evaluate(long n, Scratch& scratch);
  void help(Scratch& scratch);
  std::size_t slot(long n) const { return static_cast<std::size_t>(n % capacity_); }
  /// The time point at `position` in the stream.
  Eigen::Index pointOf(long position) const { return from_ + direction_ * static_cast<Eigen::Index>(position); }

  TrajectoryDerivatives& d_;
  Eigen::Index from_, direction_;
  long total_;         ///< points in the stream
  long position_ = 0;  ///< the position of the point next() hands out next
  /// The ring: the positions begin_ … begin_ + count_ − 1, numbered from 0 in take(), slot() and
  /// evaluate(); the rest are early points.
  long begin_ = 0, count_ = 0;
  long capacity_ = 0;  ///< the ring's slots
  PointDerivatives early_point_;  ///< the early point handed last
  std::vector<ResponseJacobian> early_sensors_;
  std::vector<PointDerivatives> slots_;
  std::vector<std::exception_ptr> failures_;
  std::vector<char> ready_;
  std::mutex mutex_;
  std::condition_variable changed_;
  long taken_ = 0;   ///< points 0 … taken_ − 1 are taken (being evaluated or ready)
  long handed_ = 0;  ///< points 0 … handed_ − 1 were handed to the sweep; the last may be in use
  int waiting_helpers_ = 0;  ///< helpers waiting for free slots
  bool stopping_ = false;
  std::vector<std::jthread> helpers_;  ///< last: joined first, while the rest is alive
};

}  // namespace mbsopt
