// When a Newton iterate of the Newmark step solves its equations (37), with the closure (34), as
// well as floating point allows, whatever the model's size, units and step.
//
// The increment test ‖Δq̈‖∞ ≤ tol·(1 + ‖q̈‖∞) cannot be met when round-off in the equations, amplified
// on its way to q̈, exceeds tol: the closure rows are positions of size ε·(reach of the model), divided
// by βh², then mapped through B⁺ (1/σ_min), and σ_min is small near a singular configuration. So the
// iteration also stops when every row of the residual is at its own round-off level, each measured
// in its own units (the weights of IDA/DASSL, with the relative part taken from the row's terms):
//     dynamic row i (24):            |rᵢ| ≤ c ε Sᵢ
//     closure row, coincidence:      |bₖ| ≤ c ε (ρ_a + ρ_b)
//     closure row, orthogonality:    |bₖ| ≤ c ε (d_a + d_b + 1)
// ρ_f is the reach of frame f, the length of the path of element translations from the ground (a
// bound on the terms its position sums); d_f the number of elements on that path. Sᵢ is a running
// error bound of the backward recursion (22)-(24) that computes rᵢ: the same recursion on the
// magnitudes of its terms, the body wrenches m(a_c − g), Iα + ω×Iω + c×F and the cut reactions λ,
// with every lever arm taken at the reach of its frame (the round-off of a position is ε·reach).
// Terms left out (springs, actuation) only make Sᵢ smaller, so the test stays on the safe side.
// An iterate that passes is as accurate as its equations can say: further iterations would move it
// only by round-off amplified by the conditioning.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/workspace.hpp"

namespace mbsopt {

/// Per frame, the reach ρ: the length of the path of element translations from the ground, from the
/// positions in ws. (The depth d, the number of elements on that path, is Frame::depth.)
void frameReach(const Model& model, const Workspace<double>& ws, std::vector<double>& reach);

/// The scale of closure row `row` of cut `cut` (its rows start at 0): ρ_a + ρ_b for a coincidence row,
/// d_a + d_b + 1 for an orthogonality row.
double closureRowScale(const Model& model, const CutJoint& cut, int row, const std::vector<double>& reach);

/// Round-off levels of the rows of the Newton equations at one state.
class NewtonRoundoff {
 public:
  /// Safety factor c on ε·scale for a row that sums a few dozen rounded terms.
  static constexpr double kFactor = 64.0;

  /// Reads the bodies' parameters once: `model` must stay unchanged while this is used with it.
  explicit NewtonRoundoff(const Model& model);

  /// Measures the rows' scales (the frames' reach, the running error bounds Sᵢ) at the
  /// state in ws (kinematics at Acceleration level) with λ the multipliers. The Newton iterates of
  /// one step change these scales (reaches, body wrenches, multipliers) by a relative amount far
  /// below the test's factor 64: the scales of a step's first iterate serve all its iterates.
  void measureScales(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& lambda);

  /// The largest ratio |row| / (ε · its scale) over the free rows r of the residual and the closure
  /// rows `closure` (positions and orthogonalities, not divided by βh²), with the scales of the last
  /// measureScales. ws must hold the joint axes of that state. A value below factor() means every
  /// row is at round-off. `closure` may be empty (closure rows not tested).
  double relativeResidual(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& r,
                          const std::vector<int>& free, const Eigen::VectorXd& closure) const;

  /// ε ‖s‖₂ with s the closure rows' scales (ρ_a + ρ_b, d_a + d_b + 1) of the last measureScales:
  /// how far round-off alone can leave the closure rows from zero. Divided by βh² and by B's
  /// smallest retained singular value (when above 1), it is how far that round-off moves a Newton
  /// increment of q̈ (the floor below which increments carry no information).
  double closureRoundoff(const Model& model) const;

  /// The factor c of this model: kFactor, or its number of frames when that is larger. A row sums up
  /// to one term per frame (a joint's row the wrenches of every frame beyond it, a closure row the
  /// translations of a path), and a sum of d rounded terms may carry (d − 1)·ε/2 times the sum of
  /// their magnitudes (Higham, "Accuracy and Stability of Numerical Algorithms", 2nd ed., §4.2). On a
  /// closed chain of 128 links (257 frames) Newton's residual stalls at 70-90 ε·S, above 64.
  double factor() const { return factor_; }

 private:
  void setWrenchMagnitudes(const Model& model, const Workspace<double>& ws, const Eigen::VectorXd& lambda);

  std::vector<double> reach_;                 ///< per frame
  std::vector<double> force_, moment_;        ///< per frame: magnitudes of the terms of its wrench
  /// Per body: its mass, |c| (centre of mass from the frame origin) and Σ|I_ij|.
  struct BodyMagnitudes {
    double mass, centre_of_mass, inertia;
  };
  std::vector<BodyMagnitudes> bodies_;
  double factor_;
};

}  // namespace mbsopt
