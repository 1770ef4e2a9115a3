// The integrator's work-precision study (`mbsopt precision SCENE`): runs of a scene at
// several steps and with several variants of the Newmark integrator, each compared with a reference
// solution (a CSV file, or a run at a tiny step) at time points that lie on every run's grid.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/design/precision_run.hpp"

namespace mbsopt {

/// A compared quantity: a coordinate (the column of q) or a sensor (of sensorHistory), by name.
struct Quantity {
  std::string name;
  bool sensor = false;
  Eigen::Index index = 0;
};

/// The coordinate or sensor `name` of the model; std::invalid_argument (with a suggestion) if neither.
Quantity findQuantity(const Model& model, const std::string& name);

struct ReferenceSolution {
  std::string file;    ///< the CSV it was read from; empty for a run
  double step = 0.0;   ///< the reference run's step [s]; 0 for a file
  double seconds = 0.0;  ///< the reference run's wall time
  std::vector<Quantity> quantities;
  Eigen::VectorXd times;   ///< the compared times [s], ascending
  Eigen::MatrixXd values;  ///< times × quantities, SI units
};

/// newmark, damped, fast-newton, fast-steps, acceleration-closure, extrapolation.
const std::vector<std::string>& integratorVariantNames();
/// Whether the variant runs the extrapolation (the integrators' registry says which that is);
/// std::invalid_argument for an unknown name.
bool runsExtrapolation(const std::string& variant);

/// The scene's settings changed as `variant` says: newmark keeps β and γ; damped takes γ = ½ + α,
/// β = (γ + ½)²/4; fast-newton accepts by contraction rate; fast-steps solves each step to a fraction of its
/// truncation error (withFastSteps); acceleration-closure closes loops at the
/// acceleration level. std::invalid_argument for an unknown name.
NewmarkSettings variantSettings(NewmarkSettings settings, const std::string& variant, double alpha);

/// The time points of (0, end_time] that lie on the grid of every step (the compared times when the
/// reference is a run); std::invalid_argument when there is none.
Eigen::VectorXd commonGridTimes(const std::vector<double>& steps, double end_time);

/// Throws std::invalid_argument naming the first time that is not a grid point of every step, or that
/// lies beyond the end of the runs (⌈end_time / h⌉ steps).
void requireOnGrids(const Eigen::VectorXd& times, const std::vector<double>& steps, double end_time);

/// Reads a CSV with the header `t,<name>,...` (names: coordinates or sensors of the model) and one row
/// per output time. Compares `quantities` (all in the file), by default the file's sensors, or every
/// column when it has none. A SceneError naming the file and line for anything wrong in it.
ReferenceSolution readReferenceCsv(const std::string& path, const Model& model,
                                   const std::vector<std::string>& quantities);

/// The scene run with its own β, γ at `step`, sampled at `times`; `quantities` by default every
/// coordinate; with `runs` > 1 the extrapolation of that many runs with `step` as its macro step.
/// `progress(t)` is called after each step of a single run.
ReferenceSolution referenceRun(const Scene& scene, double step, int runs, const Eigen::VectorXd& times,
                               const std::vector<std::string>& quantities,
                               const std::function<void(double)>& progress = {});

/// One run of the sweep, timed over `repeat` runs and compared with the reference; a SimulationError
/// (or a result that is not finite) makes it a failed run with the message. The extrapolation variant
/// takes `step` as its macro step, with `runs` runs, and reports its own error estimate.
PrecisionRun measureIntegratorRun(const Scene& scene, const std::string& variant, double step, double alpha, int runs,
                                  const ReferenceSolution& reference, int repeat);

}  // namespace mbsopt
