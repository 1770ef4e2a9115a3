#include "mbsopt/sensitivity/gradient_method.hpp"

#include <algorithm>
#include <stdexcept>

#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"

namespace mbsopt {

namespace {

/// An exact method on a problem with load cases: each case's gradient on its own simulation, its rows
/// put where its functionals stand.
DesignGradient perLoadCase(const std::string& method, const DesignProblem& problem,
                           const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                           double fd_step, const DesignResponse* simulated, int jobs) {
  DesignGradient out;
  out.constraints.resize(static_cast<Eigen::Index>(functionals.size()), x.size());
  DesignValues values{0.0, Eigen::VectorXd(static_cast<Eigen::Index>(functionals.size()))};
  bool every_value = true;
  std::vector<Eigen::Index> rows;
  for (std::size_t c = 0; c < problem.load_cases.size(); ++c) {
    const std::vector<ConstraintFunctional> own = loadCaseFunctionals(functionals, static_cast<int>(c), &rows);
    const DesignResponse* response = simulated ? &loadCaseResponse(*simulated, c) : nullptr;
    const DesignGradient g = designGradient(method, loadCaseProblem(problem, c), own, x, fd_step, response, jobs);
    out.cost = g.cost;
    for (std::size_t i = 0; i < rows.size(); ++i) {
      out.constraints.row(rows[i]) = g.constraints.row(static_cast<Eigen::Index>(i));
      if (g.values) values.constraints[rows[i]] = g.values->constraints[static_cast<Eigen::Index>(i)];
    }
    if (g.values) values.cost = g.values->cost;
    every_value = every_value && g.values.has_value();
  }
  if (every_value) out.values = std::move(values);
  return out;
}

/// An exact method on an extrapolated problem: each run's gradient (runs 2 … k, those of the result
/// T_{k,k−1}) on its own simulation, combined with the result's weights; the values likewise.
DesignGradient perExtrapolationRun(const std::string& method, const DesignProblem& problem,
                                   const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                                   double fd_step, const DesignResponse* simulated, int jobs) {
  const Eigen::VectorXd w = runWeights(problem, 1);
  DesignGradient out;
  DesignValues values;
  bool every_value = true;
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const int j = static_cast<int>(i) + 2;
    const DesignResponse* response = simulated ? &extrapolationRunResponse(*simulated, j) : nullptr;
    const DesignGradient g =
        designGradient(method, extrapolationRunProblem(problem, j), functionals, x, fd_step, response, jobs);
    if (i == 0) {
      out.cost = g.cost;
      out.constraints = w[0] * g.constraints;
      if (g.values) values = {g.values->cost, w[0] * g.values->constraints};
    } else {
      out.constraints += w[i] * g.constraints;
      if (g.values) values.constraints += w[i] * g.values->constraints;
    }
    every_value = every_value && g.values.has_value();
  }
  if (every_value) out.values = std::move(values);
  return out;
}

}  // namespace

namespace {

DesignGradient adjoint(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                       const Eigen::VectorXd& x, double, const DesignResponse* simulated, int jobs) {
  return adjointGradient(problem, functionals, x, simulated, jobs);
}
DesignGradient continuousAdjoint(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                 const Eigen::VectorXd& x, double, const DesignResponse* simulated, int) {
  return continuousAdjointGradient(problem, functionals, x, simulated);
}
DesignGradient direct(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                      const Eigen::VectorXd& x, double, const DesignResponse* simulated, int jobs) {
  return directGradient(problem, functionals, x, simulated, jobs);
}
DesignGradient forwardDifferences(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                  const Eigen::VectorXd& x, double fd_step, const DesignResponse* simulated, int jobs) {
  return finiteDifferenceGradient(problem, functionals, x, fd_step, false, simulated, jobs);
}
DesignGradient centralDifferences(const DesignProblem& problem, const std::vector<ConstraintFunctional>& functionals,
                                  const Eigen::VectorXd& x, double fd_step, const DesignResponse* simulated, int jobs) {
  return finiteDifferenceGradient(problem, functionals, x, fd_step, true, simulated, jobs);
}

/// Other names a command line accepts for a registered method.
const std::vector<std::pair<std::string, std::string>>& aliases() {
  static const std::vector<std::pair<std::string, std::string>> table{{"fd", "fd_central"}};
  return table;
}

}  // namespace

const std::vector<GradientMethodInfo>& gradientMethods() {
  static const std::vector<GradientMethodInfo> registry{
      {"adjoint", "the discrete adjoint of the Newmark recursion, one backward sweep for all functionals", true, 0,
       &adjoint},
      {"continuous-adjoint", "the adjoint ODE of the equations of motion integrated backwards; its error falls with h",
       true, 0, &continuousAdjoint},
      {"direct", "direct differentiation: the sensitivities of q, v, a to each variable carried forward", true, 0,
       &direct},
      {"fd_forward", "forward differences of the whole problem, one simulation per variable", false, 1,
       &forwardDifferences},
      {"fd_central", "central differences of the whole problem, two simulations per variable (alias: fd)", false, 2,
       &centralDifferences},
  };
  return registry;
}

std::vector<std::string> gradientMethodNames() {
  std::vector<std::string> names;
  for (const GradientMethodInfo& info : gradientMethods()) names.push_back(info.name);
  return names;
}

std::vector<std::string> gradientMethodChoices() {
  std::vector<std::string> choices = gradientMethodNames();
  for (const auto& alias : aliases()) choices.push_back(alias.first);
  return choices;
}

const GradientMethodInfo& gradientMethod(const std::string& name) {
  std::string canonical = name;
  for (const auto& [alias, method] : aliases())
    if (alias == name) canonical = method;
  for (const GradientMethodInfo& info : gradientMethods())
    if (info.name == canonical) return info;
  std::string known;
  for (const std::string& choice : gradientMethodChoices()) known += (known.empty() ? "" : ", ") + choice;
  throw std::invalid_argument("unknown gradient method '" + name + "' (known: " + known + ")");
}

DesignGradient designGradient(const std::string& method, const DesignProblem& problem,
                              const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                              double fd_step, const DesignResponse* simulated, int jobs) {
  const GradientMethodInfo& info = gradientMethod(method);
  if (info.differentiates_each_simulation && extrapolationRuns(problem) > 1)
    return perExtrapolationRun(method, problem, functionals, x, fd_step, simulated, jobs);
  if (info.differentiates_each_simulation && !problem.load_cases.empty())
    return perLoadCase(method, problem, functionals, x, fd_step, simulated, jobs);
  return info.gradient(problem, functionals, x, fd_step, simulated, jobs);
}

}  // namespace mbsopt
