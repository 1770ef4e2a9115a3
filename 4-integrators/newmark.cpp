#include "mbsopt/integrators/newmark.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/stepper.hpp"

namespace mbsopt {

static_assert(Stepper<NewmarkIntegrator>, "Newmark's steps follow the attempt/accept/reject contract (stepper.hpp)");

namespace {

/// A step in seconds as a message prints it ("0.05").
std::string formatStep(double step) {
  std::ostringstream out;
  out << step;
  return out.str();
}

// Contraction rate of the modified Newton iteration above which the iteration matrix is refreshed.
constexpr double kSlowContraction = 0.05;
// Increments within this factor of the round-off floor are noise: there an iteration that stops
// shrinking has converged (stagnation), and its contraction rate says nothing about the matrix.
constexpr double kNoiseBand = 64.0;
// Steps between two measurements of the Newton contraction rate, and the safety factor on that
// rate when it is used to accept a first iterate.
constexpr long kRateCheckInterval = 16;
constexpr double kRateSafety = 10.0;
// Newton's start (newton_predictor.hpp): with the position-level closure, the quadratic through its
// last three solutions; otherwise the least-squares polynomial of degree 6 through its last 12.
// With the position closure the increments' target is the closure rows' round-off floor: a start
// within it makes stopping after one solve or two a decision on round-off, whose two outcomes
// differ by one increment's round-off (~0.2 of the floor). A degree-4 fit did so on most of the
// tram's steps, and its finite-difference gradients came out 3-7 times noisier (the test at the
// best step failed). Without it the target is the tolerance, far above round-off, and the fit only
// saves iterations (open chains: 1.9-2.4 Newton iterations per step instead of 4.0-4.4).
constexpr int kClosedPredictorDegree = 2, kClosedPredictorWindow = 3;
constexpr int kOpenPredictorDegree = 6, kOpenPredictorWindow = 12;
// A contraction rate is measured only from increments this far above the round-off floor: the next
// increment carries round-off of 0.1-0.2 of the floor (measured on the tram), which must not pass
// for a slow rate. Without position-level closure the floor is 0 and every rate counts: there the
// target, the tolerance, lies far above the increments' round-off.
constexpr double kRateMeasurable = 16.0;
// A step that differs from the one J's tangent part was formed at by at most this fraction keeps J
// (variable steps: no new factorization each step for a change the modified Newton iteration absorbs).
constexpr double kIterationMatrixStepChange = 0.2;

}  // namespace

long stepsToCover(double end_time, double step) {
  return std::max(1L, static_cast<long>(std::ceil(end_time / step * (1.0 - 1e-12))));
}

double uniformStep(double step, double end_time) { return end_time / static_cast<double>(stepsToCover(end_time, step)); }

NewmarkSettings halvedSteps(NewmarkSettings settings) {
  settings.step = 0.5 * uniformStep(settings);
  if (settings.time_grid) {
    const std::vector<double>& grid = *settings.time_grid;
    auto halved = std::make_shared<std::vector<double>>(2 * grid.size() - 1);
    for (std::size_t k = 0; k + 1 < grid.size(); ++k) {
      (*halved)[2 * k] = grid[k];
      (*halved)[2 * k + 1] = 0.5 * (grid[k] + grid[k + 1]);
    }
    halved->back() = grid.back();
    settings.time_grid = std::move(halved);
  }
  return settings;
}

NewmarkSettings withFastSteps(NewmarkSettings settings) {
  settings.newton_truncation_fraction = kNewtonTruncationFraction;
  settings.reuse_svd_rotations = true;
  return settings;
}

double largestStep(const NewmarkSettings& settings) {
  if (!settings.time_grid) return settings.step;
  const std::vector<double>& grid = *settings.time_grid;
  double largest = 0.0;
  for (std::size_t k = 1; k < grid.size(); ++k) largest = std::max(largest, grid[k] - grid[k - 1]);
  return largest;
}

double closureTolerance(const NewmarkSettings& s) {
  if (s.closure_tolerance > 0.0) return s.closure_tolerance;
  return s.closure == ClosureLevel::Position ? 1e-6 : 1e-2;
}

SettingsDefect settingsDefect(const NewmarkSettings& s) {
  const auto finitePositive = [](double x) { return x > 0.0 && std::isfinite(x); };
  if (!finitePositive(s.step)) return {"step", "the time step must be positive and finite"};
  if (!finitePositive(s.end_time)) return {"end_time", "the end time must be positive and finite"};
  if (s.time_grid) {
    const std::vector<double>& grid = *s.time_grid;
    if (grid.size() < 2 || grid.front() != 0.0) return {"time_grid", "a time grid starts at 0 and has a step"};
    for (std::size_t k = 1; k < grid.size(); ++k)
      if (!(grid[k] > grid[k - 1]) || !std::isfinite(grid[k]))
        return {"time_grid", "the time grid must increase strictly and stay finite"};
    if (!(std::abs(grid.back() - s.end_time) <= 1e-12 * s.end_time))
      return {"time_grid", "the time grid ends at " + std::to_string(grid.back()) + " s, not at the end time"};
    if (!(static_cast<double>(grid.size()) <= kMaxNewmarkSteps)) return {"time_grid", "the time grid has too many steps"};
  } else if (s.step > s.end_time * (1.0 + 1e-12)) {
    std::ostringstream text;
    text << "the time step " << s.step << " s is longer than the run (end_time " << s.end_time
         << " s): a run ends at its end time, and a step longer than it would end after it";
    return {"step", text.str()};
  } else if (!(s.end_time / s.step <= kMaxNewmarkSteps)) {
    std::ostringstream text;
    text << "end time / step = " << s.end_time / s.step << " steps, more than the " << kMaxNewmarkSteps
         << " a run may take";
    return {"end_time", text.str()};
  }
  if (!(s.beta > 0.0 && s.beta <= 0.5)) return {"beta", "beta must lie in (0, 1/2]"};
  if (!(s.gamma > 0.0 && s.gamma < 1.0)) return {"gamma", "gamma must lie in (0, 1)"};
  if (!finitePositive(s.newton_tolerance))
    return {"newton_tolerance", "the Newton tolerance must be positive and finite"};
  if (s.max_newton_iterations < 1) return {"max_newton_iterations", "at least one Newton iteration"};
  if (!(s.svd_threshold > 0.0 && s.svd_threshold < 1.0))
    return {"svd_threshold", "the SVD threshold must lie in (0, 1)"};
  if (!(s.closure_tolerance >= 0.0 && std::isfinite(s.closure_tolerance)))
    return {"closure_tolerance", "the closure tolerance must be finite and not negative (0: the default)"};
  if (!(s.newton_truncation_fraction >= 0.0 && s.newton_truncation_fraction <= 1.0))
    return {"newton_truncation_fraction", "the Newton truncation fraction must lie in [0, 1] (0: off)"};
  if (!finitePositive(s.energy_tolerance))
    return {"energy_tolerance", "the energy tolerance must be positive and finite"};
  return {};
}

bool formsStepMatrices(const Model& model, const NewmarkSettings& settings) {
  return settings.closure == ClosureLevel::Position && model.constraintCount() > 0 &&
         static_cast<int>(model.freeCoordinates().size()) < settings.articulated_mass_from;
}

namespace {

StepMatrixLayout stepMatrixLayout(const Model& model) {
  return {static_cast<Eigen::Index>(model.freeCoordinates().size()), model.constraintCount()};
}

}  // namespace

double trajectoryBytes(const Model& model, const NewmarkSettings& settings, bool step_matrices) {
  const double points = settings.time_grid ? static_cast<double>(settings.time_grid->size())
                                           : static_cast<double>(stepsToCover(settings.end_time, settings.step)) + 1.0;
  return points * bytesPerTimePoint(model, settings, step_matrices);
}

double bytesPerTimePoint(const Model& model, const NewmarkSettings& settings, bool step_matrices) {
  double per_point = 6.0 * static_cast<double>(model.coordinateCount()) +
                     static_cast<double>(model.constraintCount()) + static_cast<double>(model.sensors().size()) +
                     2.0 + 0.5;  // the count is an int
  if (step_matrices && formsStepMatrices(model, settings)) per_point += static_cast<double>(stepMatrixLayout(model).size);
  return per_point * sizeof(double);
}

NewmarkIntegrator::NewmarkIntegrator(const Model& model, NewmarkSettings settings)
    : model_(model),
      settings_(settings),
      ws_(model),
      ad_ws_(model),
      partition_(settings.svd_threshold),
      roundoff_(model),
      free_(model.freeCoordinates()),
      predictor_(static_cast<Eigen::Index>(free_.size()),
                 closesLoopsAtPositionLevel() ? kClosedPredictorDegree : kOpenPredictorDegree,
                 closesLoopsAtPositionLevel() ? kClosedPredictorWindow : kOpenPredictorWindow) {
  if (const SettingsDefect defect = settingsDefect(settings_); !defect.field.empty())
    throw std::invalid_argument("Newmark: " + defect.message);
  settings_.step = uniformStep(settings_);  // the run ends at end_time
  const Eigen::Index n = model.coordinateCount();
  q_ = v_ = a_ = Eigen::VectorXd::Zero(n);
  r_free_.resize(static_cast<Eigen::Index>(free_.size()));
  free_accelerations_.resize(static_cast<Eigen::Index>(free_.size()));
  lambda_ = Eigen::VectorXd::Zero(model.constraintCount());
}

void NewmarkIntegrator::fail(StepStatus status, const std::string& reason, const Eigen::VectorXd& residual) const {
  Eigen::Index worst = 0;
  const double norm = residual.size() ? residual.cwiseAbs().maxCoeff(&worst) : 0.0;
  std::string element;
  if (residual.size() && worst < static_cast<Eigen::Index>(free_.size()))
    element = model_.coordinateOwner(free_[static_cast<std::size_t>(worst)]);
  for (Eigen::Index i = 0; i < residual.size(); ++i)
    if (!std::isfinite(residual[i]) && i < static_cast<Eigen::Index>(free_.size()))
      element = model_.coordinateOwner(free_[static_cast<std::size_t>(i)]);
  throw SimulationError(status, reason, t_, step_count_, norm, element);
}

std::string NewmarkIntegrator::unresistedCoordinate(const Eigen::MatrixXd& matrix) const {
  // The direction the matrix does not resist within the free directions V₂: the last right
  // singular vector of V₂ᵀ J V₂, mapped back; its largest component names the coordinate.
  const Eigen::MatrixXd& v2 = partition_.freeDirections();
  const Eigen::MatrixXd reduced = v2.transpose() * matrix * v2;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(reduced, Eigen::ComputeFullV);
  const Eigen::VectorXd direction = v2 * svd.matrixV().col(reduced.cols() - 1);
  Eigen::Index worst = 0;
  direction.cwiseAbs().maxCoeff(&worst);
  return model_.coordinateOwner(free_[static_cast<std::size_t>(worst)]);
}

void NewmarkIntegrator::failSingular(const std::string& reason, const Eigen::MatrixXd& matrix) const {
  const std::string element = unresistedCoordinate(matrix);
  throw SimulationError(StepStatus::StepTooLarge, reason + ": nothing resists a motion of '" + element +
                            "' (a joint with no body beyond it, or a massless loop?)",
                        t_, step_count_, r_free_.size() ? r_free_.norm() : 0.0, element);
}

void NewmarkIntegrator::factor(const Eigen::MatrixXd& matrix, const char* name) {
  if (!partition_.setIterationMatrix(matrix)) {
    // J = M + γh C_T + βh² K_T (33) singular where M is not: its stiffness and damping terms cancel
    // the inertia at this h (gravity on a raised chain, a negative stiffness), so the step is at fault.
    if (&matrix == &J_ && tangents_in_use_ && partition_.setIterationMatrix(mass_)) {
      const std::string element = unresistedCoordinate(matrix);
      throw SimulationError(StepStatus::StepTooLarge,
                            "the iteration matrix M + gamma h C + beta h^2 K is singular on the free directions "
                            "although the mass matrix is not: at h = " + formatStep(h_) +
                                " s its stiffness and damping terms cancel the inertia of '" + element +
                                "', a step too large for Newton here (take a smaller step, or --accuracy)",
                            t_, step_count_, r_free_.size() ? r_free_.norm() : 0.0, element);
    }
    failSingular(std::string(name) + " is singular on the free directions", matrix);
  }
  ++stats_.factorizations;
}

void NewmarkIntegrator::factorMass(const char* name) {
  if (mass_by_recursion_) {
    if (partition_.setIterationMatrix(articulated_mass_)) {
      ++stats_.factorizations;
      return;
    }
    // A singular Schur complement: the dense path decides, and names the coordinate if it is singular too.
    mass_by_recursion_ = false;
    formMassMatrix();
  }
  factor(mass_, name);
}

void NewmarkIntegrator::setDriven(double t) {
  for (int i : model_.drivenCoordinates()) {
    const TimeInput& motion = model_.coordinates()[static_cast<std::size_t>(i)].motion;
    q_[i] = model_.value(motion, t);
    v_[i] = model_.value(motion, t, 1);
    a_[i] = model_.value(motion, t, 2);
    if (!std::isfinite(q_[i]) || !std::isfinite(v_[i]) || !std::isfinite(a_[i])) {
      const std::string& element = model_.coordinateOwner(i);
      throw SimulationError(StepStatus::CheckFailed,
                            "the prescribed motion of '" + element + "' or its derivatives are not finite", t,
                            step_count_, std::numeric_limits<double>::quiet_NaN(), element);
    }
  }
}

void NewmarkIntegrator::updateConstraintPartition() {
  if (model_.constraintCount() == 0) B_free_.resize(0, static_cast<Eigen::Index>(free_.size()));
  else constraintJacobian(model_, ws_, q_, free_, position_closure_, B_free_);
  if (settings_.reuse_svd_rotations) partition_.updateConstraintJacobian(B_free_);
  else partition_.setConstraintJacobian(B_free_);
  reduced_dirty_ = true;
}

void NewmarkIntegrator::updateIterationMatrix() {
  tangentMatrices(model_, ad_ws_, q_, v_, a_, lambda_, t_, tangents_);
  const Eigen::Index nf = static_cast<Eigen::Index>(free_.size());
  mass_.resize(nf, nf);
  damping_.resize(nf, nf);
  stiffness_.resize(nf, nf);
  for (Eigen::Index r = 0; r < nf; ++r)
    for (Eigen::Index c = 0; c < nf; ++c) {
      const int i = free_[static_cast<std::size_t>(r)], j = free_[static_cast<std::size_t>(c)];
      mass_(r, c) = tangents_.mass(i, j);
      damping_(r, c) = tangents_.damping(i, j);
      stiffness_(r, c) = tangents_.stiffness(i, j);
    }
  tangent_part_ = settings_.gamma * h_ * damping_ + settings_.beta * h_ * h_ * stiffness_;
  matrix_step_ = h_;
  J_ = mass_ + tangent_part_;  // (33)
  mass_by_recursion_ = false;
  ++stats_.jacobian_updates;
  reduced_dirty_ = true;
}

void NewmarkIntegrator::setStepSize(double h) {
  if (h == h_) return;
  // Newton's start extrapolates its last solutions at equal spacing: still closer than a constant
  // start while the step changes by up to a factor of 2 (an adaptive run changes it every step).
  if (!(h <= 2.0 * h_ && h >= 0.5 * h_)) predictor_.reset();
  h_ = h;
  if (!tangents_in_use_ || J_.size() == 0 || damping_.size() == 0) return;  // J = M, or formed at the first iterate
  // J's tangent part at the new h, formed and factored again only when h has moved by more than
  // kIterationMatrixStepChange since: the modified Newton iteration converges with a J that far off.
  if (std::abs(h_ / matrix_step_ - 1.0) <= kIterationMatrixStepChange) return;
  tangent_part_ = settings_.gamma * h_ * damping_ + settings_.beta * h_ * h_ * stiffness_;
  matrix_step_ = h_;
  if (!mass_by_recursion_) J_ = mass_ + tangent_part_;  // (33) at the new h
  reduced_dirty_ = true;
}

void NewmarkIntegrator::updateMassMatrix() {
  // Needs ws_ to hold the rotations, positions and joint axes at q_; leaves them in place.
  ++stats_.mass_updates;
  reduced_dirty_ = true;
  // The range-space solves take one solve with M per independent constraint row (and the Schur
  // complement of that size): with the rank above half the free coordinates the partition's
  // reduced matrix is the smaller (the N = 40 four-bar of the hard cases: rank 80 of 81).
  const auto free = static_cast<int>(free_.size());
  mass_by_recursion_ = !tangents_in_use_ && free >= settings_.articulated_mass_from && 2 * partition_.rank() <= free &&
                       articulated_mass_.factor(model_, ws_, free_);
  if (!mass_by_recursion_) formMassMatrix();
}

void NewmarkIntegrator::formMassMatrix() {
  massMatrix(model_, ws_, free_, mass_);
  if (tangents_in_use_) J_ = mass_ + tangent_part_;
  else J_ = mass_;
}

void NewmarkIntegrator::checkInitialClosure() const {
  // Needs updateConstraintPartition at q0 (b and the geometry in ws_).
  if (model_.constraintCount() == 0) return;
  const double error = position_closure_.cwiseAbs().maxCoeff();
  if (!(error <= 1e-9 * (1.0 + q_.cwiseAbs().maxCoeff())))
    throw std::invalid_argument("Newmark: the initial coordinates do not close the loops (closure error " +
                                std::to_string(error) + "); assemble() them first");
  checkWeldOrientations(model_, ws_);
}

void NewmarkIntegrator::evaluateResidual() {
  try {
    residual(model_, ws_, q_, v_, a_, lambda_, t_, f_);
  } catch (const DegenerateElementError& degenerate) {  // an element whose force is undefined in this state
    throw SimulationError(StepStatus::StepTooLarge, degenerate.what(), t_, step_count_, std::numeric_limits<double>::quiet_NaN(),
                          degenerate.element());
  }
  for (std::size_t j = 0; j < free_.size(); ++j) r_free_[static_cast<Eigen::Index>(j)] = f_[free_[j]];
}

void NewmarkIntegrator::initialize(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, double t0) {
  const Eigen::Index n = model_.coordinateCount();
  if (q0.size() != n || v0.size() != n)
    throw std::invalid_argument("Newmark: initial state has " + std::to_string(q0.size()) + " coordinates, the model " +
                                std::to_string(n));
  if (!q0.allFinite() || !v0.allFinite()) throw std::invalid_argument("Newmark: initial state is not finite");
  t_ = t0;
  t0_ = t0;
  h_ = settings_.time_grid ? (*settings_.time_grid)[1] - (*settings_.time_grid)[0] : settings_.step;
  step_count_ = 0;
  predictor_.reset();
  contraction_ = 0.0;
  stats_ = {};
  q_ = q0;
  v_ = v0;
  a_.setZero(n);
  lambda_.setZero(model_.constraintCount());
  setDriven(t0);
  updateConstraintPartition();
  checkInitialClosure();
  // Consistent accelerations: [M Bᵀ; B 0][q̈; λ] = −[f(0, q̇, q); b̈(0)], exact in one solve since
  // f is linear in q̈ and λ, and b̈ in q̈.
  evaluateResidual();
  if (!r_free_.allFinite()) fail(StepStatus::CheckFailed, "the initial residual is not finite", r_free_);
  massMatrix(model_, ws_, free_, mass_);
  factor(mass_, "the mass matrix");
  reduced_dirty_ = true;  // the partition now holds M, not J
  projectOntoConstraints();  // velocities first, then b̈ with q̈ = 0 as the right-hand side
  evaluateResidual();
  closureEquations(model_, ws_, Derivative::Acceleration, closure_);
  partition_.solve(r_free_, closure_, da_, dlambda_);
  for (std::size_t k = 0; k < free_.size(); ++k) a_[free_[k]] += da_[static_cast<Eigen::Index>(k)];
  lambda_ += dlambda_;
  // The first step evaluates the tangent matrices (and B at its first iterate). With position-level
  // closure every step then factors M(qₙ₊₁) for its projections, and J = M lets that one
  // factorization serve the next step's Newton iterations too: the tangent part γh C_T + βh² K_T
  // stays out of J until Newton's contraction asks for it. Otherwise J keeps it from the first step.
  J_.resize(0, 0);
  damping_.resize(0, 0);
  stiffness_.resize(0, 0);
  tangents_in_use_ = !closesLoopsAtPositionLevel();
  v_unprojected_ = v_;
  a_unprojected_ = a_;
  measureClosure();
  energy_watch_.start(model_, ws_, q_, v_, t_, settings_.energy_tolerance);
}

bool NewmarkIntegrator::closesLoopsAtPositionLevel() const {
  return settings_.closure == ClosureLevel::Position && model_.constraintCount() > 0;
}

double NewmarkIntegrator::incrementRoundoffFloor(double beta_h2) const {
  // Needs roundoff_ to have measured the current geometry (measureScales). The closure rows'
  // round-off ε‖s‖ (positions, newton_convergence.hpp), divided by βh² as the rows are, and mapped
  // into q̈ through B⁺, whose gain is 1/σ_r, σ_r the smallest singular value the partition keeps;
  // and at least the round-off of the coordinates themselves, ε‖q‖∞ / βh² (a joint angle that has
  // wound up many turns carries ε|q| into every rotation after it, which the reach does not see).
  // The gain is taken as at most 1: near a singular configuration a small σ_r must not let an
  // increment that is still converging pass for noise (the stagnation test, which needs the
  // increments to have stopped shrinking, handles what it amplifies).
  if (!closesLoopsAtPositionLevel()) return 0.0;
  double coordinates = 1.0;
  for (int i : free_) coordinates = std::max(coordinates, std::abs(q_[i]));
  const double floor = std::numeric_limits<double>::epsilon() * coordinates / beta_h2;
  if (partition_.rank() == 0) return floor;
  const double smallest_kept = partition_.singularValues()[partition_.rank() - 1];
  return std::max(floor, roundoff_.closureRoundoff(model_) / (beta_h2 * std::max(1.0, smallest_kept)));
}

void NewmarkIntegrator::applyNewmarkUpdate() {
  const double h = h_;
  for (int i : free_) {  // (32)
    q_[i] = q_pred_[i] + settings_.beta * h * h * a_[i];
    v_[i] = v_pred_[i] + settings_.gamma * h * a_[i];
  }
}

double NewmarkIntegrator::truncationTarget() const {
  // An error δ of q̈ₙ₊₁ moves qₙ₊₁ by βh²δ (32); the step's local truncation error in q is
  // (β − 1/6) h² (q̈ₙ₊₁ − q̈ₙ) (Zienkiewicz and Xie), so δ ≤ κ |β − 1/6| / β ‖q̈ₙ₊₁ − q̈ₙ‖∞ keeps the
  // iteration's error in q below κ times the discretisation's. Measured on the current iterate.
  double change = 0.0;
  for (int i : free_) change = std::max(change, std::abs(a_[i] - a_accepted_[i]));
  const double beta = settings_.beta;
  return settings_.newton_truncation_fraction * std::abs(beta - 1.0 / 6.0) / beta * change;
}

bool NewmarkIntegrator::newton(bool fresh_jacobian) {
  const double h = h_;
  const double beta_h2 = settings_.beta * h * h;
  const bool position_closure = settings_.closure == ClosureLevel::Position;
  Refresh refresh = fresh_jacobian || J_.size() == 0 ? Refresh::Tangents : Refresh::None;
  if (fresh_jacobian) tangents_in_use_ = true;
  bool mass_refreshed = false;
  double roundoff_floor = 0.0;  // of the increments, set at the first residual (incrementRoundoffFloor)
  double previous = 0.0;
  for (int k = 0; k < settings_.max_newton_iterations; ++k) {
    applyNewmarkUpdate();
    evaluateResidual();
    if (!r_free_.allFinite()) fail(StepStatus::StepTooLarge, "the residual is not finite (NaN or infinity)", r_free_);
    closure_.resize(model_.constraintCount());
    if (model_.constraintCount() > 0)
      closureEquations(model_, ws_, position_closure ? Derivative::Position : Derivative::Acceleration, closure_);
    // Every row of (37) and of the closure (34) at its round-off level: this iterate is a solution
    // (newton_convergence.hpp).
    // The closure rows are positions here; with the paper's acceleration-level closure (38) they
    // have no such scale, and only the increment test below applies.
    if (k == 0) {
      roundoff_.measureScales(model_, ws_, lambda_);
      roundoff_floor = incrementRoundoffFloor(beta_h2);
    }
    last_relative_residual_ =
        roundoff_.relativeResidual(model_, ws_, r_free_, free_, position_closure ? closure_ : no_rows_);
    if (position_closure || model_.constraintCount() == 0) {
      // Not before the first iteration matrix exists: the next steps reuse its tangent part.
      if (last_relative_residual_ <= roundoff_.factor() && J_.size() > 0) {
        last_iterations_ = k;
        return true;
      }
      closure_ /= beta_h2;
    }
    if (refresh == Refresh::Tangents) {
      updateIterationMatrix();
      updateConstraintPartition();
      mass_refreshed = true;
    } else if (refresh == Refresh::Mass) {
      updateMassMatrix();
      mass_refreshed = true;
    }
    refresh = Refresh::None;
    if (reduced_dirty_) {
      if (mass_by_recursion_) factorMass("the iteration matrix");
      else factor(J_, "the iteration matrix");
      reduced_dirty_ = false;
    }
    partition_.solve(r_free_, closure_, da_, dlambda_);
    for (std::size_t j = 0; j < free_.size(); ++j) a_[free_[j]] += da_[static_cast<Eigen::Index>(j)];
    lambda_ += dlambda_;
    ++stats_.newton_iterations;
    last_iterations_ = k + 1;

    double largest = 0.0;
    for (int i : free_) largest = std::max(largest, std::abs(a_[i]));
    const double increment = da_.size() ? da_.cwiseAbs().maxCoeff() : 0.0;
    if (!std::isfinite(increment)) fail(StepStatus::StepTooLarge, "the Newton increment is not finite", r_free_);
    // Converged: the increment is below tolerance, an ∞-norm weighted by tol·(1 + ‖q̈‖∞), or below the
    // round-off floor; or it has stopped shrinking within a few digits of that floor. ‖q̈‖∞ is capped
    // at twice the last accepted step's (plus one): a diverging iterate must not inflate its own
    // tolerance (near a singular configuration it did, and the step was accepted far from a solution).
    const double scale = std::min(largest, 2.0 * acceleration_scale_ + 1.0);
    double target = std::max(settings_.newton_tolerance * (1.0 + scale), roundoff_floor);
    if (settings_.newton_truncation_fraction > 0.0) target = std::max(target, truncationTarget());
    // The contraction rate, where the previous increment stands far enough above the round-off
    // floor for this one not to be noise. Every kRateCheckInterval steps no first iterate is
    // accepted on it, so that the rate is measured again wherever the increments allow.
    if (k > 0 && previous >= kRateMeasurable * roundoff_floor) contraction_ = increment / previous;
    const bool rate_known = contraction_ > 0.0 && step_count_ % kRateCheckInterval != 0;
    // An iterate's error is about the contraction rate times its increment. An increment below the
    // round-off floor carries no information: converged, whatever the rate. Above it, the first
    // iterate, whose rate this step has not measured, is accepted below target only when a recent
    // step measured a fast rate (the convergence test of DASSL/IDA), so that its error stays a small
    // fraction of the target; with accept_by_contraction_rate, whenever that rate says the next
    // increment would be below target.
    const bool first_trusted = rate_known && contraction_ <= kSlowContraction;
    const bool small = increment <= roundoff_floor || (increment <= target && (k > 0 || first_trusted)) ||
                       (k == 0 && settings_.accept_by_contraction_rate && rate_known &&
                        kRateSafety * contraction_ * increment <= target);
    const bool stagnant = k > 0 && increment <= kNoiseBand * roundoff_floor && increment > 0.2 * previous;
    if (small || stagnant) {
      applyNewmarkUpdate();
      return true;
    }
    // Slow contraction above round-off: the reused matrix is stale. Refresh M (cheap) first, and
    // the whole tangent (AD) when that was not enough.
    if (k > 0 && increment > kSlowContraction * previous && increment > kNoiseBand * roundoff_floor) {
      refresh = mass_refreshed ? Refresh::Tangents : Refresh::Mass;
      if (refresh == Refresh::Tangents) tangents_in_use_ = true;  // J keeps them from now on
    }
    previous = increment;
  }
  return false;
}

void NewmarkIntegrator::projectOntoConstraints() {
  // Needs ws_ to hold the geometry at q (updateConstraintPartition leaves it there),
  // and the partition to hold M(q) as its matrix. Each correction Δ is the M-orthogonal projection
  // onto the constraint: min ½ΔᵀMΔ subject to B(x − Δ) + c₀ = 0, i.e. [M Bᵀ; B 0][−Δ; μ] = −[0; c];
  // the kinetic energy removed is then ½ΔᵀMΔ ≥ 0, never more.
  if (model_.constraintCount() == 0) return;
  // Velocities: ḃ = B q̇ + ∂b/∂t = 0.
  frameRates(model_, ws_, v_, a_, KinematicsLevel::Velocity);
  closureEquations(model_, ws_, Derivative::Velocity, closure_);
  partition_.project(closure_, correction_);
  for (std::size_t k = 0; k < free_.size(); ++k) v_[free_[k]] += correction_[static_cast<Eigen::Index>(k)];
  // Accelerations: b̈ = 0.
  frameRates(model_, ws_, v_, a_, KinematicsLevel::Acceleration);
  closureEquations(model_, ws_, Derivative::Acceleration, closure_);
  partition_.project(closure_, correction_);
  for (std::size_t k = 0; k < free_.size(); ++k) a_[free_[k]] += correction_[static_cast<Eigen::Index>(k)];
}

void NewmarkIntegrator::measureClosure() {
  // Needs position_closure_ to hold b(q) (updateConstraintPartition computes it).
  closure_error_ = 0.0;
  if (model_.constraintCount() == 0) return;
  closure_error_ = position_closure_.cwiseAbs().maxCoeff();
  stats_.max_closure_error = std::max(stats_.max_closure_error, closure_error_);
}

void NewmarkIntegrator::step() {
  const long next = step_count_ + 1;
  if (settings_.time_grid) {
    if (next >= static_cast<long>(settings_.time_grid->size()))
      throw std::logic_error("Newmark: a step past the end of the time grid");
    advance((*settings_.time_grid)[static_cast<std::size_t>(next)], std::nullopt);
  } else {  // t from the step count (no round-off drift of the time grid), h exactly the step, the last at T
    const bool last = t0_ == 0.0 && next == stepsToCover(settings_.end_time, settings_.step);
    advance(last ? settings_.end_time : t0_ + static_cast<double>(next) * settings_.step, settings_.step);
  }
}

void NewmarkIntegrator::advanceTo(double t_next) { advance(t_next, std::nullopt); }

void NewmarkIntegrator::advance(double t_next, std::optional<double> h) {
  if (const StepOutcome attempted = attemptOutcome(t_next, h); !attempted.converged()) throw SimulationError(attempted);
  if (const StepOutcome accepted = acceptStep(); !accepted.converged()) throw SimulationError(accepted);
}

StepOutcome NewmarkIntegrator::attemptOutcome(double t_next, std::optional<double> h) {
  try {
    if (attempt(t_next, h))
      return {StepStatus::Converged, "", t_, step_count_, std::numeric_limits<double>::quiet_NaN(), ""};
    fail(StepStatus::NewtonDiverged,
         "Newton did not converge in " + std::to_string(settings_.max_newton_iterations) +
             " iterations (a step too large for Newton, or a singular configuration: a smaller step, or --accuracy, "
             "which retries smaller ones)",
         r_free_);
  } catch (const SimulationError& e) {
    StepOutcome outcome = e.outcome();
    // Where no configuration at t_next closes the loops, that is why, and no smaller step helps.
    if (smallerStepMayHelp(outcome.status))
      if (StepOutcome loops = loopsCloseAt(t_next); !loops.converged()) outcome = std::move(loops);
    rejectStep();
    return outcome;
  }
}

void NewmarkIntegrator::failIfLoopsCannotClose(double t) const {
  if (model_.constraintCount() == 0) return;
  Eigen::VectorXd q = q_accepted_, v = v_accepted_;
  try {
    assemble(model_, q, v, t, 1e-9 * (1.0 + q.cwiseAbs().maxCoeff()), settings_.svd_threshold);
  } catch (const AssemblyError& e) {
    std::string cuts;
    for (int c : e.openCuts()) cuts += (cuts.empty() ? "" : ", ") + model_.cuts()[static_cast<std::size_t>(c)].name;
    std::ostringstream what;
    what << "the loop closed by " << cuts << " cannot be closed: the configuration nearest the last step's leaves a "
         << "closure error of " << e.closureError() << " m (a link too short for the driven motion, or a position the "
         << "loop cannot reach), so Newton could not either";
    throw SimulationError(StepStatus::LoopCannotClose, what.str(), t, step_count_, std::numeric_limits<double>::quiet_NaN(),
                          e.openCuts().empty() ? "" : model_.cuts()[static_cast<std::size_t>(e.openCuts().front())].name);
  }
}

StepOutcome NewmarkIntegrator::attemptStep(double t_next) { return attemptOutcome(t_next, std::nullopt); }

StepOutcome NewmarkIntegrator::loopsCloseAt(double t) const {
  try {
    failIfLoopsCannotClose(t);
  } catch (const SimulationError& e) {
    return e.outcome();
  }
  return {StepStatus::Converged, "", t, step_count_, std::numeric_limits<double>::quiet_NaN(), ""};
}

bool NewmarkIntegrator::attempt(double t_next, std::optional<double> step) {
  if (!(t_next > t_)) throw std::logic_error("Newmark: a step must move time forward");
  setStepSize(step.value_or(t_next - t_));
  const double h = h_;
  const double beta = settings_.beta, gamma = settings_.gamma;
  q_accepted_ = q_;
  v_accepted_ = v_;
  t_accepted_ = t_;
  q_pred_ = q_ + h * v_ + (0.5 - beta) * h * h * a_;  // (32), the parts known at tₙ
  v_pred_ = v_ + (1.0 - gamma) * h * a_;
  // Newton starts from an extrapolation of its own last solutions before projection
  // (newton_predictor.hpp), the multipliers from a linear one (they hardly enter the increments of
  // q̈: V₂ᵀBᵀ = 0 for the partition's B); the solution depends on the start only within the
  // iteration's target, the iteration count does.
  a_start_ = a_;
  if (predictor_.predict(free_accelerations_))
    for (std::size_t k = 0; k < free_.size(); ++k) a_start_[free_[k]] = free_accelerations_[static_cast<Eigen::Index>(k)];
  // λ from the quadratic through the last three (the linear one left the first iterate's λ 100 times
  // further off on the four-bar, and its correction, taken with B at qₙ, made the second iterate
  // contract at 0.08-0.25 instead of 1e-3).
  if (step_count_ >= 2) lambda_start_ = 3.0 * (lambda_ - lambda_previous_) + lambda_older_;
  else lambda_start_ = lambda_;
  lambda_before_ = lambda_previous_;
  lambda_previous_ = lambda_;
  acceleration_scale_ = 0.0;
  for (int i : free_) acceleration_scale_ = std::max(acceleration_scale_, std::abs(a_[i]));
  a_accepted_ = a_;
  a_ = a_start_;
  lambda_ = lambda_start_;
  ++step_count_;
  t_ = t_next;
  setDriven(t_);
  if (newton(false)) return true;
  // Retry from the same start with freshly evaluated tangent matrices; then from the last step's
  // accelerations and multipliers (a constant predictor): near a singular configuration the
  // extrapolated start can lie across the bifurcation, where Newton wanders between branches.
  a_ = a_start_;
  lambda_ = lambda_start_;
  setDriven(t_);
  if (newton(true)) return true;
  a_ = a_accepted_;
  lambda_ = lambda_previous_;
  setDriven(t_);
  return newton(true);
}

void NewmarkIntegrator::rejectStep() {
  q_ = q_accepted_;
  v_ = v_accepted_;
  a_ = a_accepted_;
  lambda_ = lambda_previous_;
  lambda_previous_ = lambda_before_;
  t_ = t_accepted_;
  --step_count_;
  ++stats_.rejected_steps;
  predictor_.reset();
}

StepOutcome NewmarkIntegrator::acceptStep() {
  try {
    accept();
  } catch (const SimulationError& e) {
    return e.outcome();
  }
  return {StepStatus::Converged, "", t_, step_count_, std::numeric_limits<double>::quiet_NaN(), ""};
}

void NewmarkIntegrator::accept() {
  lambda_older_ = lambda_before_;
  for (std::size_t k = 0; k < free_.size(); ++k) free_accelerations_[static_cast<Eigen::Index>(k)] = a_[free_[k]];
  predictor_.record(free_accelerations_);
  v_unprojected_ = v_;
  a_unprojected_ = a_;
  if (closesLoopsAtPositionLevel()) {
    // B and M at qₙ₊₁: exact projections, and a fresh B and M for the next step's iteration matrix.
    updateConstraintPartition();
    updateMassMatrix();
    factorMass("the mass matrix");
    reduced_dirty_ = tangents_in_use_;  // J = M: this factorization is the next step's too
    projectOntoConstraints();
    if (!v_.allFinite() || !a_.allFinite()) fail(StepStatus::StepTooLarge, "the projected rates are not finite", r_free_);
  } else {
    frameGeometry(model_, ws_, q_);
    if (model_.constraintCount() > 0) closureEquations(model_, ws_, Derivative::Position, position_closure_);
  }
  measureClosure();
  checkStep();
  ++stats_.steps;
}

void NewmarkIntegrator::evaluateSensors(SensorRow values) {
  // The geometry at q is in place (updateConstraintPartition or frameGeometry in step(), Newton's last
  // residual in initialize()); the rates are those of the state after the projections.
  frameRates(model_, ws_, v_, a_, KinematicsLevel::Acceleration);
  sensorValues(model_, ws_, q_, v_, a_, lambda_, t_, values);
}

void NewmarkIntegrator::checkStep() {
  // Needs ws_ to hold the positions at q and position_closure_ the closure rows b(q).
  stats_.max_relative_residual =
      std::max(stats_.max_relative_residual, last_relative_residual_ * std::numeric_limits<double>::epsilon());
  if (!q_.allFinite() || !v_.allFinite() || !a_.allFinite() || !lambda_.allFinite())
    fail(StepStatus::StepTooLarge, "the state is not finite (NaN or infinity)", r_free_);
  if (model_.constraintCount() > 0)
    if (const StepDefect defect = closure_check_.check(model_, ws_, position_closure_, closureTolerance(settings_));
        !defect.reason.empty())
      throw SimulationError(StepStatus::StepTooLarge, defect.reason, t_, step_count_,  // another branch, or drift
                            r_free_.size() ? r_free_.cwiseAbs().maxCoeff() : 0.0,
                            defect.element);
  if (const StepDefect defect = energy_watch_.check(model_, ws_, q_, v_, t_); !defect.reason.empty())
    throw SimulationError(StepStatus::StepTooLarge, defect.reason, t_, step_count_,  // energy grew: an unstable step
                          r_free_.size() ? r_free_.cwiseAbs().maxCoeff() : 0.0, "");
}

Trajectory NewmarkIntegrator::simulate(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0,
                                       const std::function<void(double)>& progress) {
  Trajectory out;
  simulate(q0, v0, out, [&](long k) {
    if (progress && k > 0) progress(out.time[k]);
  });
  return out;
}

void NewmarkIntegrator::simulate(const Eigen::VectorXd& q0, const Eigen::VectorXd& v0, Trajectory& out,
                                 const std::function<void(long)>& stored) {
  // Equal steps that end at end_time (settings_.step is the uniform step, see the constructor).
  if (const double bytes = trajectoryBytes(model_, settings_, keep_step_matrices_); !(bytes <= kMaxTrajectoryBytes))
    throw std::length_error("the trajectory would take " + std::to_string(bytes / (1 << 30)) +
                            " GiB, more than the limit of 4 GiB (kMaxTrajectoryBytes)");
  const long steps = settings_.time_grid
                         ? static_cast<long>(settings_.time_grid->size()) - 1
                         : stepsToCover(settings_.end_time, settings_.step);
  initialize(q0, v0, 0.0);
  const Eigen::Index n = model_.coordinateCount();
  out.time.resize(steps + 1);
  out.q.resize(n, steps + 1);
  out.v.resize(n, steps + 1);
  out.a.resize(n, steps + 1);
  out.lambda.resize(model_.constraintCount(), steps + 1);
  out.v_unprojected.resize(n, steps + 1);
  out.a_unprojected.resize(n, steps + 1);
  out.sensors.resize(steps + 1, static_cast<Eigen::Index>(model_.sensors().size()));
  out.closure_error.resize(steps + 1);
  out.newton_iterations.resize(steps + 1);
  // M, B, B's partition and its factorization of M at qₖ, as the projections used them (M dense:
  // formsStepMatrices).
  const bool keep_matrices = keep_step_matrices_ && formsStepMatrices(model_, settings_);
  const StepMatrixLayout layout = stepMatrixLayout(model_);
  out.step_matrices.resize(keep_matrices ? layout.size : 0, keep_matrices ? steps + 1 : 0);
  auto store = [&](long k, int iterations) {
    out.time[k] = t_;
    out.q.col(k) = q_;
    out.v.col(k) = v_;
    out.a.col(k) = a_;
    out.lambda.col(k) = lambda_;
    out.v_unprojected.col(k) = v_unprojected_;
    out.a_unprojected.col(k) = a_unprojected_;
    out.closure_error[k] = closure_error_;
    out.newton_iterations[k] = iterations;
    if (keep_matrices) {
      double* column = out.step_matrices.col(k).data();
      std::copy(mass_.data(), mass_.data() + mass_.size(), column + layout.mass);
      std::copy(B_free_.data(), B_free_.data() + B_free_.size(), column + layout.jacobian);
      partition_.storeFactored(column + layout.partition);  // factored with M(qₖ) for the projections
    }
    if (out.sensors.cols() > 0) evaluateSensors(out.sensors.row(k));
    if (stored) stored(k);
  };
  store(0, 0);
  for (long k = 1; k <= steps; ++k) {
    step();
    store(k, last_iterations_);
  }
  out.statistics = stats_;
}

}  // namespace mbsopt
