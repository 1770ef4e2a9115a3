#include "mbsopt/optimizers/nlopt_optimizer.hpp"

#include <algorithm>
#include <exception>
#include <string>
#include <vector>

#include "mbsopt/optimizers/evaluation_cache.hpp"

namespace mbsopt {

namespace {

/// What the callbacks share: the cache, the result being built, and why a callback gave up.
struct NloptContext {
  EvaluationCache& cache;
  OptimizerResult& result;
  std::string error;
};

Eigen::VectorXd point(unsigned n, const double* x) { return Eigen::Map<const Eigen::VectorXd>(x, n); }

/// Runs `body`; an exception becomes NLopt's forced stop, its message kept for the result.
template <class Body>
void guarded(NloptContext& context, Body&& body) {
  try {
    body();
  } catch (const std::exception& e) {
    context.error = e.what();
    throw nlopt::forced_stop();
  }
}

double objective(unsigned n, const double* x, double* gradient, void* data) {
  auto& context = *static_cast<NloptContext*>(data);
  double value = 0.0;
  guarded(context, [&] {
    const Eigen::VectorXd at = point(n, x);
    const NlpEvaluation& e = context.cache.at(at, gradient != nullptr);
    value = e.cost;
    if (gradient) Eigen::Map<Eigen::VectorXd>(gradient, n) = e.cost_gradient;
    context.cache.recordIteration(at, context.result);
  });
  return value;
}

/// Constraints [first, first + m); NLopt's gradient layout is grad[i n + j] = ∂c_i/∂x_j.
void constraintRows(Eigen::Index first, unsigned m, double* values, unsigned n, const double* x, double* gradient,
                    NloptContext& context) {
  guarded(context, [&] {
    const NlpEvaluation& e = context.cache.at(point(n, x), gradient != nullptr);
    Eigen::Map<Eigen::VectorXd>(values, m) = e.constraints.segment(first, m);
    if (gradient)
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(gradient, m, n) =
          e.constraint_jacobian.middleRows(first, m);
  });
}

void inequalities(unsigned m, double* values, unsigned n, const double* x, double* gradient, void* data) {
  constraintRows(0, m, values, n, x, gradient, *static_cast<NloptContext*>(data));
}

void equalities(unsigned m, double* values, unsigned n, const double* x, double* gradient, void* data) {
  auto& context = *static_cast<NloptContext*>(data);
  constraintRows(context.cache.problem().inequalityCount(), m, values, n, x, gradient, context);
}

std::vector<double> toStd(const Eigen::VectorXd& v) { return {v.data(), v.data() + v.size()}; }

/// The status from NLopt's own return code (EvaluationCache::conclude checks it).
void judge(nlopt::result code, const std::string& words, OptimizerResult& result) {
  result.message = "NLopt: " + words;
  if (code == nlopt::MAXEVAL_REACHED || code == nlopt::MAXTIME_REACHED) {
    result.status = OptimizerStatus::MaxIterations;
  } else if (code > 0 || code == nlopt::ROUNDOFF_LIMITED) {  // roundoff-limited: no further progress possible
    result.status = OptimizerStatus::Converged;
  } else {
    result.status = OptimizerStatus::Failed;
  }
}

/// NLopt's stopping criteria by their own names (nlopt_set_xtol_rel, …), for every algorithm, and
/// NLopt 2.7's algorithm parameters (nlopt_set_param) of MMA and CCSAQ; NLopt itself would accept
/// any parameter name and ignore the unknown ones, so they are checked here. A zero or negative
/// tolerance, stopval −∞ or maxtime ≤ 0 switches that criterion off, as in NLopt.
void setParameters(nlopt::algorithm algorithm, const NamedSettings& settings, nlopt::opt& opt) {
  const std::vector<std::pair<std::string, void (nlopt::opt::*)(double)>> stopping{
      {"xtol_rel", &nlopt::opt::set_xtol_rel}, {"xtol_abs", &nlopt::opt::set_xtol_abs},
      {"ftol_rel", &nlopt::opt::set_ftol_rel}, {"ftol_abs", &nlopt::opt::set_ftol_abs},
      {"stopval", &nlopt::opt::set_stopval},   {"maxtime", &nlopt::opt::set_maxtime}};
  std::vector<std::string> known;
  for (const auto& criterion : stopping) known.push_back(criterion.first);
  if (algorithm == nlopt::LD_MMA || algorithm == nlopt::LD_CCSAQ)
    known.insert(known.end(), {"inner_maxeval", "dual_ftol_rel", "verbosity"});
  for (const auto& [name, value] : settings) {
    if (std::find(known.begin(), known.end(), name) == known.end()) throwUnknownSetting(opt.get_algorithm_name(), name, known);
    const double number = settingNumber(name, value);
    const std::string& key = name;  // (a structured binding cannot be captured before C++20's P1091 in clang)
    const auto criterion = std::find_if(stopping.begin(), stopping.end(), [&](const auto& c) { return c.first == key; });
    if (criterion != stopping.end()) (opt.*(criterion->second))(number);
    else opt.set_param(name.c_str(), number);
  }
}

}  // namespace

OptimizerResult minimizeWithNlopt(const NloptAlgorithm& algorithm, NlpProblem& problem, const OptimizerOptions& options) {
  OptimizerResult result;
  const auto n = static_cast<unsigned>(problem.variableCount());
  nlopt::opt opt(algorithm.algorithm, n);
  result.optimizer = opt.get_algorithm_name();
  if (algorithm.local) {
    nlopt::opt local(*algorithm.local, n);
    local.set_xtol_rel(options.tolerance);
    local.set_ftol_rel(options.tolerance);
    opt.set_local_optimizer(local);
    result.optimizer += " around " + std::string(local.get_algorithm_name());
  }
  EvaluationCache cache(problem, options);
  NloptContext context{cache, result, ""};
  opt.set_lower_bounds(toStd(problem.lowerBounds()));
  opt.set_upper_bounds(toStd(problem.upperBounds()));
  opt.set_min_objective(objective, &context);
  const double tolerance = options.feasibility_tolerance;
  if (problem.inequalityCount() > 0)
    opt.add_inequality_mconstraint(inequalities, &context,
                                   std::vector<double>(static_cast<std::size_t>(problem.inequalityCount()), tolerance));
  if (problem.equalityCount() > 0)
    opt.add_equality_mconstraint(equalities, &context,
                                 std::vector<double>(static_cast<std::size_t>(problem.equalityCount()), tolerance));
  opt.set_xtol_rel(options.tolerance);
  // No test on the relative change of f: NLopt 2.7 applies it feasible or not (MMA and CCSAQ after
  // every outer iteration, SLSQP after every line search), and a design problem's cost, the
  // artificial variable b_{k+1}, stays put while they restore feasibility. It ended MMA and CCSAQ at
  // the infeasible start of problems/suite/shock_isolator.yaml, and SLSQP at k's lower bound on an
  // equality (tests/5-sensitivity/test_design_problem.cpp). They stop on x. The settings may change either (below).
  opt.set_ftol_rel(0.0);
  opt.set_maxeval(options.max_iterations);
  setParameters(algorithm.algorithm, options.settings, opt);

  std::vector<double> x = toStd(problem.start());
  double cost = 0.0;
  nlopt::result code = nlopt::FAILURE;
  std::string words;
  try {
    code = opt.optimize(x, cost);
    words = nlopt_result_to_string(static_cast<nlopt_result>(code));
  } catch (const nlopt::roundoff_limited&) {
    code = nlopt::ROUNDOFF_LIMITED;
    words = "roundoff-limited";
  } catch (const nlopt::forced_stop&) {
    code = nlopt::FORCED_STOP;
    words = "stopped: " + context.error;
  } catch (const std::exception& e) {  // NLopt's failure and invalid-argument codes
    code = opt.last_optimize_result();
    words = e.what();
  }
  judge(code, words, result);
  // NLopt returns the point of least f among those within its constraint tolerance, which for a
  // design problem's epigraph b_{k+1} prefers a b that undercuts its cost by as much as the tolerance
  // allows: the point it stopped at is its last evaluation within that tolerance (MMA's and CCSAQ's
  // last inner iterates may lie just outside it); NLopt's own where none was.
  const Eigen::VectorXd& last = cache.lastFeasibleIterate();
  cache.conclude(result, last.size() > 0 ? last : point(n, x.data()));
  return result;
}

}  // namespace mbsopt
