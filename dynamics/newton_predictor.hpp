// Where the Newton iteration of a Newmark step starts: an extrapolation of the solutions it
// converged to on the last steps (the free accelerations before projection, a smooth function of
// time).
//
// The iteration converges to the same solution from any start close enough; the start decides how
// many iterations that takes: a step stops after one solve when its first increment, about the
// start's error, is already below the increments' target. The quadratic extrapolation of the last
// three solutions misses that target by far wherever the motion is fast against the step (its
// error is of order h³ times the accelerations' third derivative), and an exact extrapolation of
// higher degree amplifies the solutions' own round-off. A least-squares polynomial of degree d
// fitted to the last w solutions (w > d + 1) and evaluated one step ahead does better on both
// counts: its error is of higher order and it averages the round-off. The integrator chooses d and
// w by the kind of target (newmark.cpp: the round-off floor of closure rows, or the tolerance).
//
// The start is a fixed, smooth function of the past solutions: an iterate accepted after k solves
// carries an error of about ρᵏ times the start's error (ρ the contraction rate), so a start chosen
// among several by a discrete rule would make the trajectory jump wherever a change of the design
// flips the choice, and finite differences of design gradients would see the jumps.
#pragma once

#include <Eigen/Core>
#include <vector>

namespace mbsopt {

class NewtonPredictor {
 public:
  /// Predictions of vectors of `size` entries (the free coordinates) by the least-squares polynomial
  /// of `degree` through the last `window` solutions (window > degree); before `window` solutions
  /// are known, by that of degree min(known − 1, 2) through those known (through one, two or three
  /// of them: the constant, linear and quadratic extrapolations).
  NewtonPredictor(Eigen::Index size, int degree, int window);

  /// Forgets every solution (a new run).
  void reset() { count_ = 0; }
  /// The start of the next step's iteration into `start` (sized here); false, and `start` unchanged,
  /// before any solution is known.
  bool predict(Eigen::VectorXd& start) const;
  /// Keeps the solution the iteration converged to on this step for the next predictions.
  void record(const Eigen::VectorXd& solution);

  /// The weights w of the prediction Σᵢ wᵢ y₋ᵢ from the last `window` samples y₀ (the newest), y₋₁, …
  /// at unit spacing by the least-squares polynomial of `degree`, evaluated one step ahead.
  static std::vector<double> extrapolationWeights(int degree, int window);

 private:
  /// Per number of solutions known (index 1 … window), the weights the prediction uses.
  std::vector<std::vector<double>> weights_;
  Eigen::MatrixXd history_;  ///< the last `window` solutions, a ring of columns
  int newest_ = -1;          ///< column of the newest solution
  int count_ = 0;            ///< solutions known (at most the window)
};

}  // namespace mbsopt
