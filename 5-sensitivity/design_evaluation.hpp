// A design problem at one point: simulate, measure the transcribed constraints, and their
// gradients by finite differences (the baseline every other gradient method is compared with).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <vector>

#include "mbsopt/integrators/newmark.hpp"
#include "mbsopt/sensitivity/design_problem.hpp"
#include "mbsopt/sensitivity/time_functional.hpp"

namespace mbsopt {

/// What a design response was measured on.
enum class ResponseParts {
  Simulation,         ///< one simulation: `trajectory` and `functionals` are its own; `parts` is empty
  LoadCases,          ///< parts[c] is load case c's response (its trajectory, and its functionals in the order of
                      ///< loadCaseFunctionals); `functionals` holds every case's in the problem's order, `trajectory`
                      ///< is empty
  ExtrapolationRuns,  ///< parts[j] is Newmark run j + 1's (at h/(j + 1)), of an extrapolated problem
                      ///< (extrapolationRuns(problem) = k ≥ 2); `constraints` is their combination T_{k,k−1}
                      ///< (4-integrators/extrapolation.hpp), `constraint_errors` its estimated discretisation error
                      ///< T_{k,k−1} − T_{k,k}; `trajectory` and `functionals` are empty
};

struct DesignResponse {
  double cost = 0.0;            ///< b_{k+1} [units of the cost sensor]
  Eigen::VectorXd constraints;  ///< measure(φ_j) − tolerance, each ≤ 0 when feasible
  Trajectory trajectory;        ///< with its sensors (Trajectory::sensors)
  /// Per constraint: its value and ∂measure/∂φ_k at every time point (what the gradient methods
  /// chain with ∂φ/∂(q, q̇, q̈)).
  std::vector<TimeFunctionalValue> functionals;
  ResponseParts made_of = ResponseParts::Simulation;
  std::vector<DesignResponse> parts;  ///< the responses it combines (ResponseParts)
  Eigen::VectorXd constraint_errors;  ///< of an extrapolated response; empty otherwise
};

/// Load case c's response of a response made of load cases; std::logic_error otherwise.
const DesignResponse& loadCaseResponse(const DesignResponse& response, std::size_t c);
/// Newmark run j's response (1-based, at h/j) of an extrapolated response; std::logic_error otherwise.
const DesignResponse& extrapolationRunResponse(const DesignResponse& response, int j);

/// The trajectory of load case c of a response (c = 0: the only one of a problem without cases); of an
/// extrapolated response, its finest run's.
const Trajectory& caseTrajectory(const DesignResponse& response, std::size_t c);

/// Simulates the problem's scene at the scaled point x and measures every transcribed constraint.
DesignResponse evaluateDesign(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const Eigen::VectorXd& x);
/// The same into `out`, its trajectory written in place: `stored(k)` is called as soon as time
/// point k of out.trajectory is complete (NewmarkIntegrator::simulate), before the constraints are
/// measured. `keep_step_matrices`: the trajectory keeps each point's M and B where the integrator
/// forms them (NewmarkIntegrator::keepStepMatrices), for the exact gradients. With load cases each
/// case is simulated into out.parts (`stored` must then be empty).
void evaluateDesign(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                    const Eigen::VectorXd& x, DesignResponse& out, const std::function<void(long)>& stored,
                    bool keep_step_matrices = false);

/// The cost's own functional at a response, in SI: its sensor's max |y| or max y over the time grid,
/// its integral or its RMS (ResponseCost); with load cases the largest over them, the worst case that
/// b_{k+1} bounds. What an optimizer's progress is judged by, b_{k+1} being only its bound.
double costFunctional(const DesignProblem& problem, const DesignResponse& response);
/// Of an extrapolated response, the estimated discretisation error of costFunctional (T_{k,k−1} −
/// T_{k,k} of the runs' values: the result minus the exact value); 0 otherwise.
double costFunctionalError(const DesignProblem& problem, const DesignResponse& response);

/// The weights of runs `first` + 1 … k of an extrapolated problem in its combination
/// (extrapolationWeights with the scene's error exponents): first = 1 gives the result, 0 the check.
Eigen::VectorXd runWeights(const DesignProblem& problem, int first);

/// The cost and the constraints at one point (DesignResponse without the histories).
struct DesignValues {
  double cost = 0.0;
  Eigen::VectorXd constraints;
};

/// Gradients with respect to the scaled point x: the cost's, and one row per constraint.
struct DesignGradient {
  Eigen::VectorXd cost;
  Eigen::MatrixXd constraints;
  /// The values at x when the method simulated x itself (the exact methods do), so that a caller
  /// needing both pays one simulation; empty for finite differences.
  std::optional<DesignValues> values;
};

/// ∂/∂b_{k+1} of every constraint, exactly (φ depends on b_{k+1} only through −b_{k+1}); every
/// gradient method shares this column. Scaled: ∂/∂x_{k+1}.
Eigen::VectorXd artificialColumn(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                 const DesignResponse& response);

/// ∂/∂B of every constraint with respect to each of the problem's constraint bounds B (a row per
/// functional, a column per DesignDescription::constraints entry, in its own SI units): exact, as
/// artificialColumn, since B enters only through the functional's offset and level
/// (ConstraintFunctional::offset_per_bound, level_per_bound). A bound shared by every load case moves
/// each case's functionals.
Eigen::MatrixXd boundJacobian(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                              const DesignResponse& response);

/// Forward (one simulation per variable) or central (two) differences in the design variables with
/// step relative_step · max(|x_i|, 1); the artificial column is exact. `simulated`: the simulation
/// at x when the caller has it. The simulations run on `jobs` threads (parallel_runs.hpp); the
/// result does not depend on their number, to the bit.
DesignGradient finiteDifferenceGradient(const DesignProblem& problem,
                                        const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                                        double relative_step, bool central, const DesignResponse* simulated = nullptr,
                                        int jobs = 1);

}  // namespace mbsopt
