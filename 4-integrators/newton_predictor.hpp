// Where the Newton iteration of a Newmark step starts: an extrapolation of the solutions it
// converged to on the last steps (the free accelerations before projection, a smooth function of
// time).
//
// The iteration converges to the same solution from any start close enough; the start decides how
// many iterations that takes: a step stops after one solve when its first increment, about the
// start's error, is already below the increments' target. The quadratic extrapolation of the last
// three solutions misses that target by far wherever the motion is fast against the step (its
// error is of order h³ times the accelerations' third derivative). An exact extrapolation of higher
// degree has an error of higher order but amplifies the solutions' own round-off (by ‖w‖₂ = 58.6 at
// degree 6); a least-squares polynomial of degree d fitted to the last w solutions (w > d + 1) and
// evaluated one step ahead keeps the higher order at a far smaller gain (7.9 at degree 6 over 12,
// against 4.4 for the quadratic). The integrator chooses d and w by the kind of target
// (newmark.cpp: the round-off floor of closure rows, or the tolerance).
//
// The start is a fixed, smooth function of the past solutions: an iterate accepted after k solves
// carries an error of about ρᵏ times the start's error (ρ the contraction rate), so a start chosen
// among several by a discrete rule would add, to the jumps of the acceptance decisions themselves,
// jumps wherever a change of the design flips the choice, which finite differences of design
// gradients would see.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mbsopt {

class NewtonPredictor {
 public:
  /// Predictions of vectors of `size` entries (the free coordinates) by the least-squares polynomial
  /// of `degree` through the last `window` solutions (window > degree ≥ 0, else
  /// std::invalid_argument); before `window` solutions are known, by the exact extrapolation through
  /// the last one, two or three of them (constant, linear, quadratic).
  NewtonPredictor(Eigen::Index size, int degree, int window);

  /// Forgets every solution (a new run).
  void reset() { count_ = 0; }
  /// The start of the next step's iteration into `start` (sized here); false, and `start` unchanged,
  /// before any solution is known.
  bool predict(Eigen::VectorXd& start) const;
  /// Keeps the solution the iteration converged to on this step for the next predictions.
  void record(const Eigen::VectorXd& solution);

  /// The weights w of the prediction Σᵢ wᵢ y₋ᵢ from the last `window` samples y₀ (the newest), y₋₁, …
  /// at unit spacing by the least-squares polynomial of `degree`, evaluated one step ahead
  /// (window > degree ≥ 0, else std::invalid_argument).
  static std::vector<double> extrapolationWeights(int degree, int window);

 private:
  /// Per number of solutions known (index 1 … window; 0 unused), the weights the prediction uses.
  std::vector<std::vector<double>> weights_;
  Eigen::MatrixXd history_;  ///< the last `window` solutions, a ring of columns
  int newest_ = -1;          ///< column of the newest solution
  int count_ = 0;            ///< solutions known (at most the window)
};

}  // namespace mbsopt
