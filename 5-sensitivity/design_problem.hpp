// A design problem (docs/design.md §4, paper §3): a scene, design variables that are named model
// parameters with bounds and scales, a cost and constraints on responses over time. As in the paper,
// the max-over-time cost becomes an artificial design variable b_{k+1} (17)-(19), and every
// "max over t ≤ bound" a constraint on a time functional of φ(t) = ±y(t) − bound (15)-(16). The
// transcription chooses that functional (the grid maximum by default, the paper's ∫⟨φ⟩dt, or
// another) and its tolerance.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/integrators/scene.hpp"
#include "mbsopt/sensitivity/time_functional.hpp"

namespace mbsopt {

/// A model parameter resolved once to its place in the model's parameter vector, its bounds [SI] and
/// the scale in which the optimizers see it: x = value / scale, so that every x is of order 1-100.
/// Made by designVariable; the dotted name stays for the reports.
struct DesignVariable {
  std::string parameter;  ///< its dotted name (Model::parameterNames())
  ParameterIndex index{};
  double lower = 0.0, upper = 0.0, scale = 1.0;
};

/// The parameter `parameter` of `model` as a design variable; throws std::invalid_argument naming it
/// when the model has no such parameter.
DesignVariable designVariable(const Model& model, std::string parameter, double lower, double upper, double scale);

/// The artificial variable b_{k+1} that carries a max-over-time cost (17)-(19).
struct ArtificialVariable {
  double initial = 0.0, lower = 0.0, upper = 0.0, scale = 1.0;
};

/// What of a response over time a cost or constraint is about: its extreme, max |y| or max y (through
/// the transcription); its integral ∫₀^τ y dt or its root mean square √((1/τ)∫₀^τ y² dt) (exact
/// functionals, not transcribed); for constraints only, its minimum min y (transcribed) or its final
/// value y(τ) (exact).
enum class ResponseMeasure { MaxAbs, Max, Min, Integral, FinalValue, Rms };

/// Minimise a sensor's extreme over time (MaxAbs or Max), its integral or its RMS.
struct ResponseCost {
  std::string sensor;
  ResponseMeasure of = ResponseMeasure::MaxAbs;
};

/// Keep the maximum, the integral or the final value of a sensor below a bound, or its minimum above
/// it; or, with `equality`, make its integral or final value equal to `bound`.
struct ResponseConstraint {
  std::string sensor;
  ResponseMeasure of = ResponseMeasure::MaxAbs;
  double bound = 0.0;
  bool equality = false;  ///< Integral or FinalValue only
  /// How far the reports let the constraint's value lie beyond its bound and still call the design
  /// feasible, in SI units (the file's `tolerance:`); empty: the reports' default.
  std::optional<double> tolerance;
};

/// How each "max over t of φ ≤ 0" becomes one number: measure(φ) ≤ tolerance.
struct Transcription {
  /// The grid maximum by default: the formulation every optimizer can take (the paper's ∫⟨φ⟩dt has a
  /// zero gradient wherever it is met, on which MMA and CCSAQ cannot move; its problems name it).
  TimeMeasure measure = TimeMeasure::GridMax;
  double tolerance = 0.0;  ///< ε ≥ 0 (a small ε > 0 gives the constraint a strictly feasible interior)
  double rho = 50.0;       ///< KS sharpness [1 / units of φ]
  /// The run's time points split into this many equal windows, each extreme measured on each window
  /// as a constraint of its own: separate peaks of one sign, which a single grid maximum would
  /// switch between at a kink, become separate smooth constraints (transcribeWindows).
  int windows = 1;
};

/// A load case as a scene file's `design:` section names it: its numbers' values (`set:`), by their
/// dotted names, on top of the scene's.
struct LoadCaseDescription {
  std::string name;
  std::vector<std::pair<std::string, double>> set;
};

/// What a scene file's `design:` section says.
struct DesignDescription {
  std::vector<DesignVariable> variables;
  ResponseCost cost;
  ArtificialVariable artificial;
  std::vector<ResponseConstraint> constraints;
  Transcription transcription;
  std::vector<LoadCaseDescription> load_cases;
};

/// One load case of a design problem: the mechanism under other numbers (a speed, a track, a load),
/// simulated on its own with the same design variables.
struct LoadCase {
  std::string name;
  Scene scene;
};

struct DesignProblem {
  Scene scene;
  DesignDescription design;
  /// None: the problem simulates `scene`. Several: each case's scene is simulated, every constraint
  /// holds in each case (named NAME_CASE), and the cost is the worst case's (its epigraph takes
  /// b_{k+1} in every case); `scene` is the scene as written, whose model names the parameters and
  /// sensors.
  std::vector<LoadCase> load_cases;
};

/// Case c of a problem with load cases as a problem of its own: its scene, the same design.
DesignProblem loadCaseProblem(const DesignProblem& problem, std::size_t c);

/// Newmark runs whose values the problem combines: the scene's settings.extrapolation_runs when its
/// integrator is the extrapolation, else 1 (4-integrators/extrapolation.hpp).
int extrapolationRuns(const DesignProblem& problem);
/// Run j (1-based) of an extrapolated problem as a problem of its own: the scene's macro step
/// uniformStep(settings) over j, one Newmark run, ending at the end time (as every run does).
DesignProblem extrapolationRunProblem(const DesignProblem& problem, int j);

/// How a transcribed constraint uses the artificial variable b_{k+1}.
enum class ArtificialUse {
  None,
  InSamples,     ///< φ(t) = sign · y(t) − offset − b_{k+1}: the epigraph of an extreme (17)-(19)
  AfterMeasure,  ///< measure(φ) − b_{k+1}: the epigraph of an exact cost (an integral, an RMS)
};

/// One transcribed constraint: measure(φ) − level − (b_{k+1} after the measure) − tolerance ≤ 0 (= 0
/// for an equality) with φ(t) = sign · y(t) − offset − (b_{k+1} in the samples).
struct ConstraintFunctional {
  std::string name;  ///< "a_lat_above", "yaw_front_below", "drift_integral", ...
  int sensor = 0;    ///< index into the model's sensors
  double sign = 1.0;
  double offset = 0.0;
  ArtificialUse artificial = ArtificialUse::None;
  TimeMeasure measure = TimeMeasure::PositivePart;  ///< the transcription's, or an exact functional's
  double tolerance = 0.0;
  bool equality = false;  ///< an exact functional (Integral, FinalValue) that must vanish
  double level = 0.0;     ///< subtracted from the measure's value (an RMS constraint's bound)
  int window = 0, windows = 1;  ///< the measure reads window `window` of `windows` (windowPoints)
  int load_case = 0;            ///< the load case whose simulation it measures (DesignProblem::load_cases)
  /// The entry of DesignDescription::constraints it transcribes (−1: the cost's epigraph), and how its
  /// offset and level move with that constraint's bound B: ∂offset/∂B and ∂level/∂B (boundJacobian).
  int constraint = -1;
  double offset_per_bound = 0.0, level_per_bound = 0.0;
};

/// The functionals of load case c, in their order, and where each stands in `functionals`.
std::vector<ConstraintFunctional> loadCaseFunctionals(const std::vector<ConstraintFunctional>& functionals, int c,
                                                      std::vector<Eigen::Index>* rows = nullptr);

/// The time points [first, first + count) of window `window` of `windows` on a grid of `points`
/// (t_0 … t_{N}, N = points − 1): window i holds the points from ⌈i N / W⌉ to ⌈(i + 1) N / W⌉ − 1,
/// the last one t_N too, so every point lies in exactly one window. Throws std::invalid_argument when
/// a window would hold fewer than two points.
std::pair<Eigen::Index, Eigen::Index> windowPoints(int window, int windows, Eigen::Index points);

/// The index of the sensor `name` in the model; throws std::invalid_argument naming it if absent.
int sensorIndex(const Model& model, const std::string& name);

/// The exact functional of an integral, RMS or final-value measure; none for an extreme.
std::optional<TimeMeasure> exactMeasure(ResponseMeasure of);

/// Empty when a cost or constraint may use `sensor`, i.e. when the design gradients can
/// differentiate it (a function of the state alone, isStateSensor, or a cut reaction, which also
/// reads the multipliers λ); otherwise why not.
std::string designSensorDefect(const Sensor& sensor);

/// A cut reaction y = c·λ is a function of the design only when c lies in the range of B: redundant
/// closure equations (a planar loop closed by a spatial revolute cut) leave the multipliers along
/// null(Bᵀ) to the history of Newton's iterations. Empty when that holds at the scene's initial state
/// (to kDeterminateReaction of ‖c‖) or the sensor is no cut reaction; otherwise why not.
std::string reactionDeterminacyDefect(const Scene& scene, const Sensor& sensor);
inline constexpr double kDeterminateReaction = 1e-6;

/// The constraints of the problem in the order the optimizers see them (NlpProblem: inequalities,
/// then equalities): those of the cost (with the artificial variable), then the inequalities of each
/// constraint, each MaxAbs giving two (y above, −y above) and a Min one (−y above −bound), then the
/// equalities. An integral constraint ∫y dt ≤ bound (= bound) is ∫(y − bound/τ) dt ≤ 0 (= 0); a final
/// value y(τ) − bound ≤ 0 (= 0). Names are unique: a repeated one gets its rank ("y_above_2").
/// Throws std::invalid_argument naming an unknown sensor or one designSensorDefect refuses, or a
/// design variable whose index names another parameter in the scene's model or a load case's.
std::vector<ConstraintFunctional> transcribe(const DesignProblem& problem);

/// Number of optimisation variables: the design variables and the artificial one.
inline Eigen::Index optimisationSize(const DesignProblem& problem) {
  return static_cast<Eigen::Index>(problem.design.variables.size()) + 1;
}

/// The scaled starting point: each design variable's value in the scene, then b_{k+1}.
Eigen::VectorXd initialPoint(const DesignProblem& problem);

/// Sets the design variables of x (scaled) on `model`; returns b_{k+1} in SI units.
double applyDesign(const DesignProblem& problem, const Eigen::VectorXd& x, Model& model);

/// Checks names, bounds and scales; throws std::invalid_argument with what is wrong.
void validate(const DesignProblem& problem);

}  // namespace mbsopt
