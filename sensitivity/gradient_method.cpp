#include "mbsopt/sensitivity/gradient_method.hpp"

#include <algorithm>
#include <stdexcept>

#include "mbsopt/sensitivity/continuous_adjoint.hpp"
#include "mbsopt/sensitivity/direct_sensitivity.hpp"
#include "mbsopt/sensitivity/discrete_adjoint.hpp"

namespace mbsopt {

const std::vector<std::string>& gradientMethodNames() {
  static const std::vector<std::string> names{"adjoint", "continuous-adjoint", "direct", "fd_forward", "fd_central"};
  return names;
}

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
    const DesignResponse* response = simulated ? &simulated->load_cases.at(c) : nullptr;
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
    const DesignResponse* response = simulated ? &simulated->runs.at(static_cast<std::size_t>(j - 1)) : nullptr;
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

DesignGradient designGradient(const std::string& method, const DesignProblem& problem,
                              const std::vector<ConstraintFunctional>& functionals, const Eigen::VectorXd& x,
                              double fd_step, const DesignResponse* simulated, int jobs) {
  const bool exact = method == "adjoint" || method == "continuous-adjoint" || method == "direct";
  if (exact && extrapolationRuns(problem) > 1)
    return perExtrapolationRun(method, problem, functionals, x, fd_step, simulated, jobs);
  if (exact && !problem.load_cases.empty()) return perLoadCase(method, problem, functionals, x, fd_step, simulated, jobs);
  if (method == "adjoint") return adjointGradient(problem, functionals, x, simulated, jobs);
  if (method == "continuous-adjoint") return continuousAdjointGradient(problem, functionals, x, simulated);
  if (method == "direct") return directGradient(problem, functionals, x, simulated, jobs);
  if (method == "fd_forward") return finiteDifferenceGradient(problem, functionals, x, fd_step, false, simulated, jobs);
  requireGradientMethod(method);
  return finiteDifferenceGradient(problem, functionals, x, fd_step, true, simulated, jobs);  // fd_central
}

void requireGradientMethod(const std::string& method) {
  const auto& names = gradientMethodNames();
  if (std::find(names.begin(), names.end(), method) != names.end()) return;
  std::string known;
  for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown gradient method '" + method + "' (known: " + known + ")");
}

}  // namespace mbsopt
