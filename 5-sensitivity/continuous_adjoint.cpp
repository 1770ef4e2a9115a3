#include "mbsopt/sensitivity/continuous_adjoint.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>
#include <algorithm>
#include <optional>
#include <stdexcept>
#include <string>

#include <Eigen/QR>

#include "mbsopt/sensitivity/augmented_solve.hpp"
#include "mbsopt/sensitivity/initial_state.hpp"
#include "mbsopt/sensitivity/newmark_derivatives.hpp"

namespace mbsopt {

namespace {

/// One time point's adjoint sources, per unit of time and halved (the trapezoidal rule's h/2 g_k),
/// after the acceleration responses are substituted (paper (59)-(63), with the loop closure):
/// q̈ = L(−(C q̇ + K q + ∂f/∂b), −(∂b̈/∂q q + ∂b̈/∂q̇ q̇)) linearised, so a seed ḡ_a on q̈ becomes
/// −t̄ K − b̄ ∂b̈/∂q on q, −t̄ C − b̄ ∂b̈/∂q̇ on q̇ and −t̄ ∂f/∂b directly on b, (t̄, b̄) its transposed solve;
/// a seed on the multipliers λ of the same system (a cut reaction) enters that solve beside ḡ_a.
/// `closure`: the point's closure derivatives when the caller has them, else null.
struct HalfSources {
  Eigen::MatrixXd position, velocity;
};

HalfSources substituteAccelerations(TrajectoryDerivatives& d, Eigen::Index k, const StepDerivatives& s,
                                    const ClosureDerivatives* closure, double half_over_weight,
                                    Eigen::MatrixXd& dpsi_db) {
  ResponseSeeds seeds = d.seeds(k);
  if (seeds.parameters.cols() > 0) dpsi_db += seeds.parameters;  // the sensors' explicit ∂Ψ/∂b
  const bool multipliers = seeds.multipliers.cols() > 0 && !seeds.multipliers.isZero(0.0);
  if (seeds.acceleration.cwiseAbs().maxCoeff() > 0.0 || multipliers) {
    Eigen::MatrixXd tbar, bbar;
    const Eigen::MatrixXd jacobian = d.constraintJacobian(k);
    solveAugmentedTransposed(s.mass, jacobian, seeds.acceleration, d.settings().svd_threshold, tbar, bbar,
                             multipliers ? &seeds.multipliers : nullptr);
    seeds.position -= tbar * s.stiffness;
    seeds.velocity -= tbar * s.damping;
    dpsi_db -= tbar * s.parameters;
    if (d.constraintCount() > 0) {
      std::optional<ClosureDerivatives> own;  // the point's closure, unless the caller has it
      const ClosureDerivatives& c = closure ? *closure : own.emplace(d.closure(k));
      seeds.position -= bbar * c.acceleration_q;
      seeds.velocity -= 2.0 * bbar * c.velocity_q;  // ∂b̈/∂q̇ = 2 ∂ḃ/∂q (ClosureDerivatives)
      // A geometric variable moves b̈ itself: −b̄ ∂b̈/∂b.
      if (c.acceleration_parameters.cols() > 0) dpsi_db -= bbar * c.acceleration_parameters;
    }
  }
  return {half_over_weight * seeds.position, half_over_weight * seeds.velocity};
}

/// An orthonormal basis of the null space of B (the paper's V₂, (43)-(48)): the right singular
/// vectors whose singular values are at most `threshold` times the largest, as in the integrator.
Eigen::MatrixXd independentDirections(const Eigen::MatrixXd& B, double threshold) {
  if (B.rows() == 0) return Eigen::MatrixXd::Identity(B.cols(), B.cols());
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeFullV);
  const Eigen::VectorXd& sigma = svd.singularValues();
  Eigen::Index rank = 0;
  while (rank < sigma.size() && sigma[rank] > threshold * sigma[0] && sigma[0] > 0.0) ++rank;
  return svd.matrixV().rightCols(B.cols() - rank);
}

}  // namespace

DesignGradient continuousAdjointGradient(const DesignProblem& problem,
                                         const std::vector<ConstraintFunctional>& functionals,
                                         const Eigen::VectorXd& x, const DesignResponse* simulated) {
  // The sensitivity equations of the loop-closed motion, first order in (s, u) = d(q, q̇)/db:
  //   M u̇ + C u + K s + Bᵀσ + ∂f/∂b = 0,  ṡ − u = 0,  B s + ∂b/∂b = 0,  s(0) = S_q₀, u(0) = S_v₀,
  // with K including the loop forces' geometric stiffness (the paper's (58) with (57)'s closure).
  // ∂b/∂b, S_q₀ and S_v₀ vanish unless a geometric variable moves a loop (initial_state.hpp).
  // With adjoints (w, p, ν) of the three, integration by parts as in (50)-(52) gives, for
  // Ψ = ∫ (g_q s + g_q̇ u) dt,
  //   d(M w)/dt = Cᵀw − p + g_q̇ᵀ,  dp/dt = Kᵀw + Bᵀν + g_qᵀ,  B w = 0,  w(τ) = p(τ) = 0   (53)/(64)
  //   dΨ/db = ∫ wᵀ ∂f/∂b dt + ∫ νᵀ ∂b/∂b dt − p(0)ᵀ S_q₀ − w(0)ᵀ M(0) S_v₀          (56)/(65)
  // (w is the paper's λ up to sign; the paper's design leaves the closure alone, so its (56) has the
  // first term only). Instead of reducing the equations to (57)'s independent
  // directions V₂, whose time derivative that reduction would need, the closure stays as B w = 0
  // with the multiplier ν. The trapezoidal rule backward from t_{k+1} to t_k, rows = constraints:
  //   w_k M_k = w_{k+1} M_{k+1} − h/2 (F_k + F_{k+1}),  F = w C − p + g_q̇,
  //   p_k = p_{k+1} − h/2 (w_k K_k + g_q,k + w_{k+1} K_{k+1} + g_q,k+1) − ν̄ B̄,  B_k w_kᵀ = 0,
  // with ν̄ = ∫ν dt over the step and B̄ = ½(B_k + B_{k+1}), the midpoint rule for ∫Bᵀν dt (B_k
  // alone would make it first order). Eliminating p_k: w_k A + ½h ν̄ B̄ = R with A = M + ½h C + ¼h² K,
  // the transposed trapezoidal Newmark matrix. So w_k = ξ V₂ᵀ with V₂ the independent directions of
  // B_k, and ν̄ drops out against those of B̄: ξ (V₂ᵀ Aᵀ V̄₂) = R V̄₂.
  if (problem.scene.settings.time_grid)
    throw std::invalid_argument("the continuous adjoint integrates backward at a fixed step; this problem's steps vary "
                                "(a time grid): use the discrete adjoint or the direct method, exact for any steps");
  TrajectoryDerivatives d(problem, functionals, x, simulated);
  const bool moves_loops = designMovesLoopClosure(problem);
  const double h = uniformStep(d.settings()), half = 0.5 * h, threshold = d.settings().svd_threshold;
  const Eigen::Index N = d.timePoints() - 1, rows = d.functionalCount(), nf = d.freeCount();
  // The trapezoidal rule's weights on the uniform grid: h/2 at both ends, h inside.
  const auto weight = [&](Eigen::Index k) { return k == 0 || k == N ? half : h; };
  Eigen::MatrixXd dpsi_db = Eigen::MatrixXd::Zero(rows, d.variableCount());
  // At t_{k+1}: w M, h/2 F, p and h/2 (w K + g_q), starting from w(τ) = p(τ) = 0. They stay exact
  // zeros back to the point after the last seed: the integration starts there.
  const Eigen::Index start = std::min(d.lastSeededPoint() + 1, N);
  Eigen::MatrixXd momentum = Eigen::MatrixXd::Zero(rows, nf), half_flux, p = Eigen::MatrixXd::Zero(rows, nf);
  Eigen::MatrixXd half_force;
  Eigen::MatrixXd later_jacobian = d.constraintJacobian(start);
  // A design that moves a loop needs each point's ∂b/∂b; its closure then serves the substitution too.
  std::optional<ClosureDerivatives> closure;
  if (moves_loops) closure = d.closure(start);
  Eigen::MatrixXd later_closure_b = closure ? closure->position_parameters : Eigen::MatrixXd();
  StepDerivatives s = d.projectedStep(start);
  HalfSources g = substituteAccelerations(d, start, s, closure ? &*closure : nullptr, half / weight(start), dpsi_db);
  half_flux = g.velocity;
  half_force = g.position;
  for (Eigen::Index k = start - 1; k >= 0; --k) {
    s = d.projectedStep(k);
    if (moves_loops) closure = d.closure(k);
    g = substituteAccelerations(d, k, s, closure ? &*closure : nullptr, half / weight(k), dpsi_db);
    const Eigen::MatrixXd A = s.mass + half * s.damping + half * half * s.stiffness;
    // w A + ½h ν̄ B = w_{k+1}M_{k+1} − h/2 F_{k+1} − h/2 g_q̇,k + ½h (p_{k+1} − h/2 (w_{k+1}K_{k+1} + g_q,k+1) − h/2 g_q,k)
    const Eigen::MatrixXd rhs = momentum - half_flux - g.velocity + half * (p - half_force - g.position);
    const Eigen::MatrixXd jacobian = d.constraintJacobian(k);
    const Eigen::MatrixXd V2 = independentDirections(jacobian, threshold);
    const Eigen::MatrixXd V2_mean = independentDirections(0.5 * (jacobian + later_jacobian), threshold);
    if (V2.cols() != V2_mean.cols())
      throw std::invalid_argument("continuous adjoint: the rank of the loop closure changes near t = " +
                               std::to_string(d.time(k)) + " s (a singular configuration); use adjoint or direct");
    const Eigen::MatrixXd reduced = V2_mean.transpose() * A.transpose() * V2;  // V̄₂ᵀ Aᵀ V₂ ξᵀ = V̄₂ᵀ Rᵀ
    const Eigen::MatrixXd w = reduced.partialPivLu().solve(V2_mean.transpose() * rhs.transpose()).transpose() * V2.transpose();
    if (moves_loops) {
      // ν̄ from ½h ν̄ B̄ = R − w A (minimum norm: redundant rows carry none), then ∫νᵀ ∂b/∂b dt over
      // the step by the midpoint rule, as ∫Bᵀν dt.
      const Eigen::MatrixXd& closure_b = closure->position_parameters;
      const Eigen::MatrixXd mean = 0.5 * (jacobian + later_jacobian);
      const Eigen::MatrixXd nu =
          mean.transpose().completeOrthogonalDecomposition().solve((rhs - w * A).transpose()).transpose() / half;
      dpsi_db += nu * (0.5 * (closure_b + later_closure_b));
      later_closure_b = closure_b;
    }
    later_jacobian = jacobian;
    const Eigen::MatrixXd wM = w * s.mass, wC = w * s.damping;
    p = (wM + half * wC + g.velocity - momentum + half_flux) / half;  // the first equation solved for p_k
    momentum = wM;
    half_flux = half * (wC - p) + g.velocity;
    half_force = half * (w * s.stiffness) + g.position;
    dpsi_db += weight(k) * (w * s.parameters);
  }
  if (moves_loops) {  // the initial state closed on the design's loops: −p(0)ᵀ S_q₀ − w(0)ᵀ M(0) S_v₀
    const InitialSensitivities initial = d.initialSensitivities();
    dpsi_db -= p * initial.q + momentum * initial.v;
  }
  return d.gradient(dpsi_db);
}

}  // namespace mbsopt
