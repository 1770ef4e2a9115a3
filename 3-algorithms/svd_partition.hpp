// Solution of the augmented Newton system (41)
//     [ J  Bᵀ ] [ Δx ]     [ r ]
//     [ B  0  ] [ Δμ ] = − [ g ]
// through the singular value decomposition of the constraint Jacobian (43)-(48):
// B = U₁ S₁ V₁ᵀ keeping the singular values above a relative threshold, so redundant constraints
// and singular configurations drop out; Δx = V₁ x_r + V₂ x_n with
//     x_r = −S₁⁻¹ U₁ᵀ g                         (third row of (48))
//     (V₂ᵀ J V₂) x_n = −V₂ᵀ (r + J V₁ x_r)       (second row)
//     Δμ = −U₁ S₁⁻¹ V₁ᵀ (r + J Δx)               (first row; minimum-norm multipliers)
// The SVD is the one-sided Jacobi SVD of Bᵀ (one_sided_jacobi.hpp), V₂ the complement of V₁ from
// V₁'s Householder reflectors (householder_basis.hpp).
//
// When J = M is given by its articulated-body factorization (articulated_body.hpp), the same system
// is solved through the range of Bᵀ instead, with no O(n³) term: BᵀΔμ = V₁ν, and
//     Δx = −M⁻¹ (r + V₁ ν),   (V₁ᵀ M⁻¹ V₁) ν = −(x_r + V₁ᵀ M⁻¹ r),   Δμ = U₁ S₁⁻¹ ν,
// which satisfy the three rows of (48) as the partition's solution does (V₁ᵀΔx = x_r, and the first
// row of (41) projected on V₁ and V₂): the same Δx and the same minimum-norm Δμ, to round-off.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include "mbsopt/linalg/condition_estimate.hpp"
#include "mbsopt/linalg/householder_basis.hpp"
#include "mbsopt/linalg/one_sided_jacobi.hpp"
#include "mbsopt/algorithms/articulated_body.hpp"

namespace mbsopt {

class SvdPartition {
 public:
  explicit SvdPartition(double relative_threshold = 1e-8) : threshold_(relative_threshold) {}

  /// SVD of B (m × n, m may be 0), V₁ and V₂. Call again whenever B changes.
  void setConstraintJacobian(const Eigen::MatrixXd& B);
  /// The same for a B near the last one (the next step's), its SVD started from the last one's
  /// (OneSidedJacobiSvd::update) and its sweeps stopped once the columns of V₁ are orthogonal to
  /// kFastOrthogonality: about half the sweeps. V₂ still spans the null space of B to round-off (it
  /// is the complement of V₁'s span, which is the range of Bᵀ whatever the sweeps did), so the
  /// projections keep the constraints; the solves' range part, B V₁ S₁⁻¹ U₁ᵀ = I + O(kFastOrthogonality
  /// · cond B), makes Newton converge at that rate instead of exactly. For `--fast-steps`, whose
  /// Newton stops far above it (NewmarkSettings::reuse_svd_rotations).
  void updateConstraintJacobian(const Eigen::MatrixXd& B);
  /// The partition of B as `other` holds it after its setConstraintJacobian(B): its factors copied,
  /// the same to the bit as setConstraintJacobian(B) here at `other`'s threshold. Forgets the
  /// factored matrix. Allocates nothing once the buffers have `other`'s sizes.
  void copyConstraintFactors(const SvdPartition& other);
  /// The entries store() writes for a B of m rows and n columns (the factors at the largest rank,
  /// min(m, n)).
  static Eigen::Index storedSize(Eigen::Index m, Eigen::Index n);
  /// The factors of the last setConstraintJacobian into `out` (storedSize entries), for load().
  void store(double* out) const;
  /// The factors store() wrote for a B of m rows and n columns, as if setConstraintJacobian(B) ran
  /// here at the threshold of the partition that stored them: the same to the bit. Forgets the
  /// factored matrix.
  void load(const double* in, Eigen::Index m, Eigen::Index n);
  /// The entries storeFactorization() writes for n columns (V₂ and the LU factors of V₂ᵀJV₂, sized
  /// for rank 0, their largest).
  static Eigen::Index storedFactorizationSize(Eigen::Index n) { return 2 * n * n + n; }
  /// V₂ and the LU factors of V₂ᵀJV₂ from the last setIterationMatrix(J) with a dense J into `out`
  /// (storedFactorizationSize entries), for loadFactorization().
  void storeFactorization(double* out) const;
  /// What storeFactorization() wrote, J being the matrix it factored, after load() of the same
  /// partition: as if setIterationMatrix(J) had returned true here, the same to the bit.
  void loadFactorization(const double* in, const Eigen::MatrixXd& J);
  /// The entries storeFactored() writes for a B of m rows and n columns: the partition, and when B
  /// has rows its factorization.
  static Eigen::Index storedFactoredSize(Eigen::Index m, Eigen::Index n);
  /// store(), followed when B has rows by storeFactorization() (the projections' solves need the
  /// factorization only with rows).
  void storeFactored(double* out) const;
  /// What storeFactored() wrote for a B of m rows and n columns, J the matrix it factored (not read
  /// without rows): load() and loadFactorization().
  void loadFactored(const double* in, Eigen::Index m, Eigen::Index n, const Eigen::MatrixXd& J);
  /// The relative threshold of the next setConstraintJacobian.
  void setThreshold(double relative_threshold) { threshold_ = relative_threshold; }
  /// Factor the reduced matrix V₂ᵀ J V₂. Returns false when it is singular: its reciprocal condition
  /// number in the 1-norm, as Hager and Higham's O(n²) estimator gives it (condition_estimate.hpp),
  /// below kSingular (1e-13), or not finite. The estimate is skipped when a cheaper lower bound of the
  /// reciprocal condition already lies above twice that (reciprocalConditionLowerBound): the answer is
  /// the same. Needs setConstraintJacobian first.
  bool setIterationMatrix(const Eigen::MatrixXd& J);
  /// J = M by its articulated-body factorization: the range-space solves above, O(n r) per solve
  /// after r solves with M here. Returns false when the Schur complement V₁ᵀM⁻¹V₁ (r × r) is not
  /// positive definite, or its Cholesky pivots spread by more than 1/kSingular (singular). `inverse`
  /// is used by reference until the next setIterationMatrix: it must stay alive and unchanged.
  bool setIterationMatrix(const ArticulatedBodyFactorization& inverse);

  void solve(const Eigen::VectorXd& r, const Eigen::VectorXd& g, Eigen::VectorXd& dx, Eigen::VectorXd& dmu) const;
  /// solve() for several right-hand sides, the columns of R (n × p) and G (m × p): the columns of dx
  /// and, when `dmu` is given, of *dmu are those solve() gives, bit for bit (solve() is the same code
  /// on one column), for one pass of each product over the block instead of p calls. The exact
  /// gradients' sweeps solve 4 to 12 columns per step. Allocates nothing once the buffers have
  /// these sizes.
  void solveColumns(const Eigen::MatrixXd& R, const Eigen::MatrixXd& G, Eigen::MatrixXd& dx, Eigen::MatrixXd* dmu) const;
  /// solveColumns(R, 0, dx, &dmu): the constraint rows' right-hand side zero, as in the adjoint's
  /// transposed solves (AugmentedSolver::solveTransposed). Then X_r = 0 and ΔX = V₂ X_n alone, and
  /// the products of X_r, which add exact zeros, are skipped: the same bits.
  void solveColumns(const Eigen::MatrixXd& R, Eigen::MatrixXd& dx, Eigen::MatrixXd& dmu) const;
  /// Δx of the system with r = 0 (a projection onto the constraints), without the multipliers.
  void project(const Eigen::VectorXd& g, Eigen::VectorXd& dx) const;
  /// Minimum-norm least-squares solution of B Δx = c: Δx = V₁ S₁⁻¹ U₁ᵀ c (= B⁺c).
  void pseudoInverse(const Eigen::VectorXd& c, Eigen::VectorXd& dx) const;
  /// Minimum-norm least-squares solution of Bᵀ μ = w: μ = U₁ S₁⁻¹ V₁ᵀ w (= (Bᵀ)⁺w), the singular
  /// values below the threshold dropped.
  void transposedPseudoInverse(const Eigen::VectorXd& w, Eigen::VectorXd& mu) const;

  int rank() const { return rank_; }
  int constraintRows() const { return static_cast<int>(u1_.rows()); }
  const Eigen::VectorXd& singularValues() const { return singular_values_; }
  /// V₂: an orthonormal basis of the directions the constraints leave free (the degrees of freedom).
  const Eigen::MatrixXd& freeDirections() const;
  /// V₁: an orthonormal basis of the directions the constraints fix (the row space of B), n × rank.
  const Eigen::MatrixXd& constrainedDirections() const { return v1_; }

 private:
  /// setConstraintJacobian (from_last false) or updateConstraintJacobian (true).
  void partition(const Eigen::MatrixXd& B, bool from_last);
  /// The orthogonality of updateConstraintJacobian's columns, relative to the product of their norms:
  /// about √ε, as the rank threshold; about one Jacobi sweep fewer than to round-off (4 a step on
  /// Andrews' squeezer).
  static constexpr double kFastOrthogonality = 1e-8;
  /// Up to this many coordinates V₂ᵀ J V₂ is formed from the explicit V₂ (a few small products beat
  /// applying reflectors); from there on by the reflectors of V₁, O(n² r) instead of O(n³)
  /// (bench_dynamics: BM_ClosedChainNewmarkStep, BM_TramwaySimulation).
  static constexpr Eigen::Index kReflectorsFrom = 16;
  /// A reduced matrix whose reciprocal condition number (1-norm) is below this is singular.
  static constexpr double kSingular = 1e-13;
  /// Up to this size the cheap lower bound is tried before the estimate. The triangles' comparison
  /// matrices grow exponentially with n: on the closed chains of bench_dynamics the bound is 3e-4
  /// against Hager's 5e-3 at n = 6 and 1e-51 against 8e-7 at n = 62, where it would only add a sweep.
  static constexpr Eigen::Index kBoundUpTo = 16;

  double threshold_;
  int rank_ = 0;
  Eigen::MatrixXd transposed_;                ///< Bᵀ
  OneSidedJacobiSvd jacobi_;                   ///< Bᵀ = V Σ Uᵀ
  HouseholderBasis complement_;                ///< V₁ = Q [R; 0]: V₂ is the rest of Q
  Eigen::VectorXd singular_values_;
  Eigen::MatrixXd u1_, v1_;
  mutable Eigen::MatrixXd v2_;    ///< formed on first use after setConstraintJacobian (freeDirections)
  mutable bool v2_stale_ = false;
  Eigen::VectorXd inverse_s1_;
  Eigen::MatrixXd J_;
  Eigen::MatrixXd j_v2_, rotated_, reduced_matrix_;  ///< J V₂; Qᵀ J Q; V₂ᵀ J V₂
  LuFactors reduced_;
  const ArticulatedBodyFactorization* inverse_ = nullptr;  ///< set: the range-space solves
  Eigen::MatrixXd inverse_v1_;                             ///< M⁻¹ V₁
  Eigen::LLT<Eigen::MatrixXd> schur_;                      ///< V₁ᵀ M⁻¹ V₁
  ConditionEstimator condition_;
  Eigen::VectorXd bound_scratch_;
  mutable Eigen::VectorXd x_r_, work_;  // buffers of the solves: no allocation
  mutable Eigen::VectorXd column_, nu_;                        // buffers of the range-space solves
  mutable Eigen::MatrixXd x_r_block_, x_n_block_, work_block_, reduced_block_, multiplier_block_, zero_block_;  // of the block solves
  mutable Eigen::VectorXd column_r_, column_g_, column_dx_, column_dmu_;  // its range-space columns

  /// Δx of (48) into dx, r = 0 when null.
  void increment(const Eigen::VectorXd* r, const Eigen::VectorXd& g, Eigen::VectorXd& dx) const;
  // The rows of (48) on p columns of raw column-major data, shared by the solves of one column and
  // of a block:
  /// X_r = −S₁⁻¹ U₁ᵀ G (third row) into x_r (rank × p).
  void rangeCoordinates(const double* g, Eigen::Index p, double* x_r) const;
  /// ΔX = V₁ X_r + V₂ X_n with (V₂ᵀ J V₂) X_n = −V₂ᵀ (R + J V₁ X_r) (second row), R = 0 when null,
  /// X_r = 0 when null (its products, exact zeros, skipped: the same bits). Needs R or X_r.
  void partitionIncrement(const double* r, const double* x_r, Eigen::Index p, double* dx) const;
  /// The minimum-norm multipliers ΔM = −U₁ S₁⁻¹ V₁ᵀ (R + J ΔX) (first row).
  void partitionMultipliers(const double* r, const double* dx, Eigen::Index p, double* dmu) const;
  /// The same through the range of Bᵀ, leaving ν in nu_.
  void rangeSpaceIncrement(const Eigen::VectorXd* r, Eigen::VectorXd& dx) const;
};

}  // namespace mbsopt
