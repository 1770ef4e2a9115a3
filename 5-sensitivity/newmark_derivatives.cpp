#include "mbsopt/sensitivity/newmark_derivatives.hpp"

#include <Eigen/QR>
#include <Eigen/SVD>
#include <algorithm>
#include <numeric>
#include <stdexcept>

#include "mbsopt/algorithms/closure.hpp"
#include "mbsopt/algorithms/kinematics.hpp"
#include "mbsopt/algorithms/mass_matrix.hpp"
#include "mbsopt/algorithms/residual.hpp"
#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/algorithms/tangent.hpp"
#include "mbsopt/sensitivity/augmented_solve.hpp"
#include "mbsopt/sensitivity/forward_ad.hpp"
#include "mbsopt/sensitivity/initial_state.hpp"
#include "mbsopt/sensitivity/parameter_jacobian.hpp"
#include "mbsopt/sensitivity/response_jacobian.hpp"

namespace mbsopt {

namespace {

Model checkedModel(const DesignProblem& problem, const Eigen::VectorXd& x) {
  if (!problem.load_cases.empty())
    throw std::logic_error("exact gradients: a problem with load cases is differentiated case by case (designGradient)");
  if (extrapolationRuns(problem) > 1)
    throw std::logic_error("exact gradients: an extrapolated problem is differentiated run by run (designGradient)");
  if (problem.scene.model.constraintCount() > 0 && problem.scene.settings.closure != ClosureLevel::Position)
    throw std::invalid_argument("exact gradients: loops closed at acceleration level are not supported (use fd)");
  Model model = problem.scene.model;
  applyDesign(problem, x, model);
  return model;
}

/// out = x's entries at `rows`, reusing out's storage (an Eigen view indexed by a std::vector copies
/// the vector, an allocation per call).
void gather(const Eigen::VectorXd& x, const std::vector<int>& rows, Eigen::VectorXd& out) {
  out.resize(static_cast<Eigen::Index>(rows.size()));
  for (std::size_t r = 0; r < rows.size(); ++r) out[static_cast<Eigen::Index>(r)] = x[rows[r]];
}

/// out = the rows `rows` of source's columns [first, first + count), reusing out's storage.
void copyRows(const Eigen::MatrixXd& source, const std::vector<int>& rows, Eigen::Index row_offset, Eigen::Index first,
              Eigen::Index count, Eigen::MatrixXd& out) {
  out.resize(static_cast<Eigen::Index>(rows.size()), count);
  for (std::size_t r = 0; r < rows.size(); ++r)
    out.row(static_cast<Eigen::Index>(r)) = source.row(row_offset + rows[r]).segment(first, count);
}

/// out = one column per design variable: the rows `rows` of source's column first + direction[j]
/// for a variable with an AD direction, zero for the others (−1), reusing out's storage.
void copyParameterRows(const Eigen::MatrixXd& source, const std::vector<int>& rows, Eigen::Index row_offset,
                       Eigen::Index first, const std::vector<int>& direction, Eigen::MatrixXd& out) {
  out.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(direction.size()));
  for (std::size_t j = 0; j < direction.size(); ++j)
    for (std::size_t r = 0; r < rows.size(); ++r)
      out(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(j)) =
          direction[j] >= 0 ? source(row_offset + rows[r], first + direction[j]) : 0.0;
}

/// The sensors of the functionals j for which reads(j), each once (±y share one), into `sensors`,
/// and per model sensor its place there, or −1, into `slot`.
template <class Reads>
void collectSensors(const Model& model, const std::vector<ConstraintFunctional>& functionals, Reads reads,
                    std::vector<int>& slot, std::vector<const Sensor*>& sensors) {
  slot.assign(model.sensors().size(), -1);
  sensors.clear();
  sensors.reserve(model.sensors().size());  // (allocates once)
  for (std::size_t j = 0; j < functionals.size(); ++j) {
    const auto sensor = static_cast<std::size_t>(functionals[j].sensor);
    if (slot[sensor] >= 0 || !reads(static_cast<Eigen::Index>(j))) continue;
    slot[sensor] = static_cast<int>(sensors.size());
    sensors.push_back(&model.sensors()[sensor]);
  }
}

}  // namespace

TrajectoryDerivatives::TrajectoryDerivatives(const DesignProblem& problem,
                                             const std::vector<ConstraintFunctional>& functionals,
                                             const Eigen::VectorXd& x, const DesignResponse* simulated, int jobs)
    : problem_(problem),
      functionals_(functionals),
      x_(x),
      model_(checkedModel(problem, x)),
      simulated_(simulated),
      scratch_(model_) {
  for (const DesignVariable& v : problem.design.variables) parameter_indices_.push_back(v.index);
  for (const ParameterIndex index : parameter_indices_) {
    const bool linear = isLinearForceParameter(model_, index);
    ad_parameter_.push_back(linear ? -1 : static_cast<int>(ad_parameter_indices_.size()));
    if (!linear) ad_parameter_indices_.push_back(index);
    linear_columns_read_kinematics_ = linear_columns_read_kinematics_ || linearForceParameterReadsKinematics(model_, index);
    geometric_ = geometric_ || isGeometricParameter(model_, index);
    drives_ = drives_ || drivingCoordinate(model_, index) >= 0;
  }
  closure_rows_.resize(static_cast<std::size_t>(model_.constraintCount()));
  std::iota(closure_rows_.begin(), closure_rows_.end(), 0);
  const std::vector<int>& free = model_.freeCoordinates();
  const std::vector<AdInput> free_q = adInputs(AdInput::Kind::Position, free);
  const std::vector<AdInput> free_v = adInputs(AdInput::Kind::Velocity, free);
  step_inputs_ = adInputs({free_q, parameterInputs(ad_parameter_indices_.size()), free_v});
  sensed_step_inputs_ = adInputs({step_inputs_, adInputs(AdInput::Kind::Acceleration, free)});
  collectSensors(model_, functionals_, [](Eigen::Index) { return true; }, functional_sensor_slot_, functional_sensors_);
  reads_multipliers_ = std::any_of(functional_sensors_.begin(), functional_sensors_.end(),
                                   [](const Sensor* sensor) { return mbsopt::readsMultipliers(*sensor); });
  if (simulated) return;
  if (jobs >= 2) simulateWhileEvaluating(jobs);
  else evaluateDesign(problem_, functionals_, x_, simulation_, {}, /*keep_step_matrices=*/true);
}

void TrajectoryDerivatives::linearParameterColumns(Eigen::Index k, const Eigen::VectorXd& v, Scratch& s,
                                                   Eigen::MatrixXd& parameters) {
  if (ad_parameter_indices_.size() == parameter_indices_.size()) return;  // every variable has an AD direction
  s.q = response().trajectory.q.col(k);
  if (linear_columns_read_kinematics_) {
    plainGeometryAt(k, s);
    frameRates(model_, s.plain_ws, v, v, KinematicsLevel::Velocity);  // (q̈ is not read at velocity level)
  }
  for (std::size_t j = 0; j < ad_parameter_.size(); ++j) {
    if (ad_parameter_[j] >= 0) continue;
    linearForceParameterColumn(model_, s.plain_ws, s.q, v, time(k), parameter_indices_[j], s.column);
    gather(s.column, model_.freeCoordinates(), s.free_rows);
    parameters.col(static_cast<Eigen::Index>(j)) = s.free_rows;
  }
}

void TrajectoryDerivatives::partitionWithMass(const Eigen::MatrixXd& B, const Eigen::MatrixXd& M,
                                              SvdPartition& partition) const {
  partition.setThreshold(settings().svd_threshold);
  partition.setConstraintJacobian(B);
  // Without cut joints there are no projections, and no solve with M.
  if (B.rows() > 0 && !partition.setIterationMatrix(M))
    throw std::runtime_error("exact gradients: singular step matrix");
}

void TrajectoryDerivatives::prefetch(Eigen::Index k) const {
  const Trajectory& tr = response().trajectory;
  if (k < 0 || k >= tr.time.size()) return;
  constexpr Eigen::Index kLine = 64 / sizeof(double);  // doubles per cache line
  const auto lines = [](const double* data, Eigen::Index size) {
    for (Eigen::Index i = 0; i < size; i += kLine) __builtin_prefetch(data + i);
    if (size > 0) __builtin_prefetch(data + size - 1);  // a column need not start on a line
  };
  if (tr.step_matrices.cols() > k) lines(tr.step_matrices.col(k).data(), tr.step_matrices.rows());
  for (const Eigen::MatrixXd* x : {&tr.q, &tr.v, &tr.a, &tr.v_unprojected, &tr.a_unprojected, &tr.lambda})
    lines(x->col(k).data(), x->rows());
}

void TrajectoryDerivatives::geometryAt(Eigen::Index k, Scratch& s) {
  if (k == s.geometry_point) return;
  const Trajectory& tr = response().trajectory;
  const Eigen::Index nf = freeCount(), m = model_.constraintCount();
  if (tr.step_matrices.cols() > k) {  // M and B as the simulation formed them at q_k: the same values
    const StepMatrixLayout layout(nf, m);
    s.mass = Eigen::Map<const Eigen::MatrixXd>(tr.step_matrices.col(k).data() + layout.mass, nf, nf);
    s.jacobian = Eigen::Map<const Eigen::MatrixXd>(tr.step_matrices.col(k).data() + layout.jacobian, m, nf);
  } else {
    s.q = tr.q.col(k);
    if (m > 0) {  // B's pass leaves the rotations, positions and joint axes at q_k in plain_ws
      mbsopt::constraintJacobian(model_, s.plain_ws, s.q, model_.freeCoordinates(), s.closure, s.jacobian);
    } else {
      frameGeometry(model_, s.plain_ws, s.q);
      s.jacobian.resize(0, nf);
    }
    s.plain_geometry_point = k;
    massMatrix(model_, s.plain_ws, model_.freeCoordinates(), s.mass);
  }
  s.geometry_point = k;
}

void TrajectoryDerivatives::plainGeometryAt(Eigen::Index k, Scratch& s) {
  if (k == s.plain_geometry_point) return;
  s.q = response().trajectory.q.col(k);
  frameGeometry(model_, s.plain_ws, s.q);
  s.plain_geometry_point = k;
}

StepDerivatives TrajectoryDerivatives::step(Eigen::Index k) {
  PointDerivatives point;
  pointAt(k, scratch_, point);
  return point.step;
}

void TrajectoryDerivatives::driveAt(Eigen::Index k, Workspace<AdScalar>& ws) const {
  if (!drives_) return;
  ws.driving_model = &model_;
  ws.driving_time = time(k);
}

StepDerivatives TrajectoryDerivatives::projectedStep(Eigen::Index k) {
  const Trajectory& tr = response().trajectory;
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(model_.constraintCount());
  if (model_.constraintCount() > 0) {  // Bᵀλ = −f(q, q̇, q̈, 0) on the free rows, least squares
    const Eigen::VectorXd q = tr.q.col(k), v = tr.v.col(k), a = tr.a.col(k);
    Eigen::VectorXd f;
    residual(model_, scratch_.plain_ws, q, v, a, lambda, tr.time[k], f);
    scratch_.plain_geometry_point = -1;  // (it holds q_k's geometry, but no longer as plainGeometryAt left it)
    const Eigen::MatrixXd transposed = constraintJacobian(k).transpose();
    lambda = transposed.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(-f(model_.freeCoordinates()));
  }
  // M = ∂f/∂q̈ in double; C_T, K_T and ∂f/∂b in one set of AD passes over the step's inputs, and
  // the columns of the parameters f is linear in in double.
  const Eigen::Index nf = freeCount();
  const std::vector<int>& free = model_.freeCoordinates();
  driveAt(k, scratch_.ws);
  const Eigen::MatrixXd d = residualJacobian(model_, scratch_.ws, tr.q.col(k), tr.v.col(k), tr.a.col(k), lambda,
                                             tr.time[k], step_inputs_, ad_parameter_indices_);
  geometryAt(k, scratch_);
  StepDerivatives out{scratch_.mass, {}, {}, {}};
  const Eigen::Index velocities = firstVelocityInput();
  copyRows(d, free, 0, velocities, nf, out.damping);
  copyRows(d, free, 0, 0, nf, out.stiffness);
  copyParameterRows(d, free, 0, nf, ad_parameter_, out.parameters);
  scratch_.v = tr.v.col(k);
  linearParameterColumns(k, scratch_.v, scratch_, out.parameters);
  return out;
}

Eigen::MatrixXd TrajectoryDerivatives::constraintJacobian(Eigen::Index k) {
  geometryAt(k, scratch_);
  return scratch_.jacobian;
}


void TrajectoryDerivatives::sensorDerivatives(Scratch& s, const VectorX<AdScalar>& q, const VectorX<AdScalar>& v,
                                              const VectorX<AdScalar>& a, Eigen::Index first, Eigen::Index count) const {
  // The pass's inputs are sensed_step_inputs_: free q [0, nf), the AD parameters, free q̇, free q̈
  // (last nf).
  const Eigen::Index nf = freeCount(), velocities = firstVelocityInput();
  for (std::size_t i = 0; i < s.sensors.size(); ++i) {
    // A cut reaction reads Newton's multipliers λ_k, a constant of the passes (s.lambda).
    const AdScalar y = sensorValue(model_, *s.sensors[i], s.ws, q, v, a, s.lambda);
    ResponseJacobian& J = s.sensor_jacobians[i];
    J.value = y.value();
    if (first == 0) multiplierDerivatives(model_, s.ws, *s.sensors[i], J);
    for (Eigen::Index j = 0; j < count; ++j) {
      const Eigen::Index input = first + j;
      if (input < nf) J.position[input] = y.derivatives()[j];
      else if (input >= velocities + nf) J.acceleration[input - velocities - nf] = y.derivatives()[j];
      else if (input >= velocities) J.velocity[input - velocities] = y.derivatives()[j];
      else J.parameters[input - nf] = y.derivatives()[j];
    }
  }
}

void TrajectoryDerivatives::pointAt(Eigen::Index k, Scratch& s, PointDerivatives& out) {
  selectSensors(k, s);
  stepAndClosureAt(k, s, out);
  sensorSeeds(k, s.sensor_slot, s.sensor_jacobians, out.seeds);
}

void TrajectoryDerivatives::stepAndClosureAt(Eigen::Index k, Scratch& s, PointDerivatives& out) {
  driveAt(k, s.ws);
  const Trajectory& tr = response().trajectory;
  const std::vector<int>& free = model_.freeCoordinates();
  const Eigen::Index n = model_.coordinateCount(), m = model_.constraintCount(), nf = freeCount();
  geometryAt(k, s);
  // The sensors' derivatives come from the same passes (at the projected state, q̈ seeded too).
  const bool sensed = !s.sensors.empty();
  const std::vector<AdInput>& inputs = sensed ? sensed_step_inputs_ : step_inputs_;
  // One Jacobian per sensor a functional reads, sized once: a point fills those of its selected
  // sensors (the first s.sensors.size()), and no point allocates.
  if (s.sensor_jacobians.size() < functional_sensors_.size()) s.sensor_jacobians.resize(functional_sensors_.size());
  for (ResponseJacobian& J : s.sensor_jacobians) {
    J.position.resize(nf);
    J.velocity.resize(nf);
    J.acceleration.resize(nf);
    J.parameters.resize(static_cast<Eigen::Index>(ad_parameter_indices_.size()));
  }
  // Each projection's correction Δ and its minimum-norm multipliers μ (Bᵀμ = −M Δ, free rows), from
  // B's partition at the settings' threshold with M factored, the integrator's own where it kept
  // them; the sweeps' solves at this point take the same partition.
  s.plain_correction_v = tr.v.col(k) - tr.v_unprojected.col(k);
  s.plain_correction_a = tr.a.col(k) - tr.a_unprojected.col(k);
  s.plain_mu_v.resize(m);
  s.plain_mu_a.resize(m);
  SvdPartition& partition = out.closure.partition;
  if (tr.step_matrices.cols() > k) {  // as the simulation computed them at q_k from the same B and M
    const StepMatrixLayout layout(nf, m);
    partition.loadFactored(tr.step_matrices.col(k).data() + layout.partition, m, nf, s.mass);
  } else {
    partitionWithMass(s.jacobian, s.mass, partition);
  }
  if (m > 0) {
    gather(s.plain_correction_v, free, s.free_rows);
    s.plain_f.noalias() = s.mass * s.free_rows;
    s.plain_f = -s.plain_f;
    partition.transposedPseudoInverse(s.plain_f, s.plain_mu_v);
    gather(s.plain_correction_a, free, s.free_rows);
    s.plain_f.noalias() = s.mass * s.free_rows;
    s.plain_f = -s.plain_f;
    partition.transposedPseudoInverse(s.plain_f, s.plain_mu_a);
  }
  // The constants of the passes.
  seedVector(tr.lambda.col(k), 0, 0, 0, s.lambda);
  seedVector(s.plain_mu_v, 0, 0, 0, s.mu_v);
  seedVector(s.plain_mu_a, 0, 0, 0, s.mu_a);
  seedVector(s.plain_correction_v, 0, 0, 0, s.correction_v);
  seedVector(s.plain_correction_a, 0, 0, 0, s.correction_a);
  // One evaluation per pass over the step's inputs (free q, the design parameters, free q̇) shares
  // the geometry at q_k between four functions of it, in rows [f; ḃ; b̈; f_v; f_a]: f at the state
  // Newton converged to (K_T, ∂f/∂b, C_T); the closure rates at the projected state, q̇ seeded the
  // same way (∂ḃ/∂q, ∂b̈/∂q, and ∂ḃ/∂b, ∂b̈/∂b); each projection's M(q)Δ + B(q)ᵀμ at q̇ = 0 (its G
  // and P); and with a geometric variable b itself in rows [b] after them (∂b/∂b). A pass
  // of velocities alone evaluates f only, and writes only its rows: ∂b̈/∂q̇ = 2 ∂ḃ/∂q comes from the
  // passes over q (ClosureDerivatives), ḃ's derivative in q̇ is B, and M(q)Δ + B(q)ᵀμ does not depend
  // on q̇. With sensors to differentiate, free q̈ is seeded last, and each sensor is evaluated at the
  // projected state.
  const Eigen::Index rows = m > 0 ? 3 * n + 2 * m + (geometric_ ? m : 0) : n;
  const Eigen::Index velocities = firstVelocityInput();
  Eigen::MatrixXd& d = s.pass_jacobian;
  d.resize(rows, static_cast<Eigen::Index>(sensed_step_inputs_.size()));  // the widest pass: sized once
  VectorX<AdScalar>& g = s.ws.seeded_f;
  bool geometry_in_ws = false;  // q_k's geometry in s.ws, from a pass seeded in q or a parameter
  const auto projectedRates = [&](const SeededState& state, Eigen::Index first, Eigen::Index count) {
    s.projected_v = state.v;  // the pass's derivative lanes at the projected values
    s.projected_a = state.a;
    for (Eigen::Index i = 0; i < n; ++i) {
      s.projected_v[i].value() = tr.v(i, k);
      s.projected_a[i].value() = tr.a(i, k);
    }
    frameRates(model_, s.ws, s.projected_v, s.projected_a, KinematicsLevel::Acceleration);
    if (sensed) sensorDerivatives(s, state.q, s.projected_v, s.projected_a, first, count);
  };
  const auto evaluate = [&](const SeededState& state, Eigen::Index first, Eigen::Index count) {
    g.resize(rows);
    const bool seeds_geometry = first < velocities;  // the pass seeds some q or parameter
    if (seeds_geometry) {
      forwardKinematics(model_, s.ws, state.q, state.v, state.a, KinematicsLevel::Acceleration);
      geometry_in_ws = true;
    } else {  // q and the parameters are constants of this pass: q_k's geometry without derivatives
      if (geometry_in_ws) {
        dropGeometryDerivatives(model_, s.ws);
      } else {
        plainGeometryAt(k, s);
        constantGeometry(model_, s.plain_ws, s.ws);
      }
      frameRates(model_, s.ws, state.v, state.a, KinematicsLevel::Acceleration);
    }
    residualFromKinematics(model_, s.ws, state.q, state.v, state.a, s.lambda, tr.time[k], s.f);
    g.head(n) = s.f;
    if (m == 0) {  // no projections: the state Newton converged to is the trajectory's
      if (sensed) sensorDerivatives(s, state.q, state.v, state.a, first, count);
    } else if (seeds_geometry) {
      projectedRates(state, first, count);
      closureEquations(model_, s.ws, Derivative::Acceleration, s.closure_rates);
      g.segment(n + m, m) = s.closure_rates;
      closureEquations(model_, s.ws, Derivative::Velocity, s.closure_rates);
      g.segment(n, m) = s.closure_rates;
      frameAccelerationsAtRest(model_, s.ws, s.correction_v);
      inertialAndLoopForcesFromKinematics(model_, s.ws, s.correction_v, s.mu_v, s.f);
      g.segment(n + 2 * m, n) = s.f;
      frameAccelerationsAtRest(model_, s.ws, s.correction_a);
      inertialAndLoopForcesFromKinematics(model_, s.ws, s.correction_a, s.mu_a, s.f);
      g.segment(2 * n + 2 * m, n) = s.f;
      if (geometric_) {
        closureEquations(model_, s.ws, Derivative::Position, s.closure_rates);
        g.tail(m) = s.closure_rates;
      }
    } else if (sensed) {  // only the sensors read the projected state
      projectedRates(state, first, count);
    }
    const Eigen::Index written = seeds_geometry ? rows : n;
    for (Eigen::Index i = 0; i < written; ++i) d.row(i).segment(first, count) = g[i].derivatives().head(count);
  };
  forEachAdPass(s.ws, tr.q.col(k), tr.v_unprojected.col(k), tr.a_unprojected.col(k), inputs, ad_parameter_indices_,
                evaluate);
  // Columns: free q [0, nf), the AD passes' design parameters [nf, velocities), free q̇ from
  // velocities on; the parameters f is linear in (force elements' stiffness and damping) in double, and with zero
  // columns in the projections (M and B do not depend on them).
  out.step.mass = s.mass;
  copyRows(d, free, 0, velocities, nf, out.step.damping);
  copyRows(d, free, 0, 0, nf, out.step.stiffness);
  copyParameterRows(d, free, 0, nf, ad_parameter_, out.step.parameters);
  s.v = tr.v_unprojected.col(k);
  linearParameterColumns(k, s.v, s, out.step.parameters);
  ClosureDerivatives& c = out.closure;
  c.jacobian = s.jacobian;  // no rows without cut joints
  if (m == 0) return;
  c.velocity_q = d.block(n, 0, m, nf);
  c.acceleration_q = d.block(n + m, 0, m, nf);
  copyRows(d, free, n + 2 * m, 0, nf, c.velocity_projection);
  copyParameterRows(d, free, n + 2 * m, nf, ad_parameter_, c.velocity_projection_parameters);
  copyRows(d, free, 2 * n + 2 * m, 0, nf, c.acceleration_projection);
  copyParameterRows(d, free, 2 * n + 2 * m, nf, ad_parameter_, c.acceleration_projection_parameters);
  if (!geometric_) {
    for (Eigen::MatrixXd* x : {&c.position_parameters, &c.velocity_parameters, &c.acceleration_parameters})
      x->resize(m, 0);
    return;
  }
  copyParameterRows(d, closure_rows_, 3 * n + 2 * m, nf, ad_parameter_, c.position_parameters);
  copyParameterRows(d, closure_rows_, n, nf, ad_parameter_, c.velocity_parameters);
  copyParameterRows(d, closure_rows_, n + m, nf, ad_parameter_, c.acceleration_parameters);
}

InitialSensitivities TrajectoryDerivatives::initialSensitivities() {
  const Eigen::Index nf = freeCount(), p = variableCount(), m = constraintCount();
  PointDerivatives point;
  pointAt(0, scratch_, point);
  const StepDerivatives& s = point.step;
  const ClosureDerivatives& c = point.closure;
  InitialSensitivities out{Eigen::MatrixXd::Zero(nf, p), Eigen::MatrixXd::Zero(nf, p), {}, {}};
  Eigen::MatrixXd top = -s.parameters, bottom = Eigen::MatrixXd::Zero(m, p);
  if (designMovesLoopClosure(problem_)) {
    // q₀ = q₀ˢ + V₁ z and q̇₀ = q̇₀ˢ + V₁ w on b = 0 and ḃ = 0 (initial_state.hpp) differentiated.
    const Eigen::MatrixXd V1 = closingDirections(problem_.scene);
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> closing(c.jacobian * V1);
    out.q = V1 * closing.solve(-c.position_parameters);
    out.v = V1 * closing.solve(-(c.velocity_q * out.q + c.velocity_parameters));
    top -= s.stiffness * out.q + s.damping * out.v;
    bottom = -(c.acceleration_q * out.q + 2.0 * c.velocity_q * out.v + c.acceleration_parameters);
  }
  // f(q₀, q̇₀, q̈₀, λ₀; b) = 0 and b̈ = 0: [M Bᵀ; B 0][S_a; S_λ] = [−∂f/∂b − K_T S_q − C_T S_v;
  // −∂b̈/∂q S_q − ∂b̈/∂q̇ S_v − ∂b̈/∂b], ∂b̈/∂q̇ = 2 ∂ḃ/∂q (ClosureDerivatives); the integrator's λ₀ is
  // that system's minimum-norm one, and so is S_λ.
  AugmentedSolver solver(c.jacobian, settings().svd_threshold);
  solver.setMatrix(s.mass);
  solver.solve(top, bottom, out.a, out.lambda);
  return out;
}

ClosureDerivatives TrajectoryDerivatives::closure(Eigen::Index k) {
  PointDerivatives point;
  pointAt(k, scratch_, point);
  return point.closure;
}

ResponseSeeds TrajectoryDerivatives::seeds(Eigen::Index k) {
  ResponseSeeds out;
  seeds(k, out);
  return out;
}

void TrajectoryDerivatives::seeds(Eigen::Index k, ResponseSeeds& out) { seedsAt(k, scratch_, out); }

Eigen::Index TrajectoryDerivatives::lastSeededPoint() const {
  Eigen::Index last = 0;
  for (Eigen::Index j = 0; j < functionalCount(); ++j)
    for (Eigen::Index k = timePoints() - 1; k > last; --k)
      if (seedWeight(j, k) != 0.0) {  // (NaN included)
        last = k;
        break;
      }
  return last;
}

double TrajectoryDerivatives::seedWeight(Eigen::Index j, Eigen::Index k) const {  // ∂Ψ/∂φ_k ∂φ/∂y
  const auto f = static_cast<std::size_t>(j);
  return functionals_[f].sign * response().functionals[f].gradient[k];
}

bool TrajectoryDerivatives::selectSensors(Eigen::Index k, Scratch& scratch) const {
  collectSensors(model_, functionals_, [&](Eigen::Index j) { return seedWeight(j, k) != 0.0; }, scratch.sensor_slot,
                 scratch.sensors);
  return !scratch.sensors.empty();
}

void TrajectoryDerivatives::sensorSeeds(Eigen::Index k, const std::vector<int>& slot,
                                        const std::vector<ResponseJacobian>& jacobians, ResponseSeeds& out) const {
  const Eigen::Index m = functionalCount(), nf = freeCount();
  out.position.setZero(m, nf);
  out.velocity.setZero(m, nf);
  out.acceleration.setZero(m, nf);
  out.parameters.setZero(m, geometric_ ? variableCount() : 0);
  out.multipliers.setZero(m, reads_multipliers_ ? constraintCount() : 0);
  for (Eigen::Index j = 0; j < m; ++j) {
    const double weight = seedWeight(j, k);
    if (weight == 0.0) continue;
    const auto sensor = static_cast<std::size_t>(functionals_[static_cast<std::size_t>(j)].sensor);
    const ResponseJacobian& J = jacobians[static_cast<std::size_t>(slot[sensor])];
    out.position.row(j) = weight * J.position;
    out.velocity.row(j) = weight * J.velocity;
    out.acceleration.row(j) = weight * J.acceleration;
    if (J.multipliers.size() > 0) out.multipliers.row(j) = weight * J.multipliers;
    if (!geometric_) continue;
    for (std::size_t v = 0; v < ad_parameter_.size(); ++v)
      if (ad_parameter_[v] >= 0) out.parameters(j, static_cast<Eigen::Index>(v)) = weight * J.parameters[ad_parameter_[v]];
  }
}

void TrajectoryDerivatives::seedsAt(Eigen::Index k, Scratch& scratch, ResponseSeeds& out) {
  driveAt(k, scratch.ws);
  const Trajectory& tr = response().trajectory;
  if (selectSensors(k, scratch)) {  // every selected sensor in one set of passes
    const Eigen::VectorXd lambda = tr.lambda.rows() > 0 ? Eigen::VectorXd(tr.lambda.col(k)) : Eigen::VectorXd();
    responseJacobians(model_, scratch.ws, scratch.sensors, tr.q.col(k), tr.v.col(k), tr.a.col(k),
                      model_.freeCoordinates(), scratch.sensor_jacobians,
                      geometric_ ? ad_parameter_indices_ : std::vector<ParameterIndex>{}, &lambda);
  }
  sensorSeeds(k, scratch.sensor_slot, scratch.sensor_jacobians, out);
}

DesignGradient TrajectoryDerivatives::gradient(const Eigen::MatrixXd& dpsi_db) const {
  const Eigen::Index nx = x_.size();
  DesignGradient out;
  out.cost = Eigen::VectorXd::Zero(nx);
  out.cost[nx - 1] = problem_.design.artificial.scale;  // the cost is b_{k+1} = x_{k+1} · scale
  out.constraints.resize(functionalCount(), nx);
  for (Eigen::Index i = 0; i < variableCount(); ++i)
    out.constraints.col(i) = dpsi_db.col(i) * problem_.design.variables[static_cast<std::size_t>(i)].scale;
  out.constraints.col(nx - 1) = artificialColumn(problem_, functionals_, response());
  out.values = DesignValues{response().cost, response().constraints};
  return out;
}

}  // namespace mbsopt
