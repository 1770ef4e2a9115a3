#include "mbsopt/optimizers/ipopt_optimizer.hpp"

#include <IpIpoptApplication.hpp>
#include <IpTNLP.hpp>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include "mbsopt/optimizers/evaluation_cache.hpp"

namespace mbsopt {

namespace {

using Ipopt::Index;
using Ipopt::Number;

constexpr Number kInfinity = 1e19;  // Ipopt's nlp_lower/upper_bound_inf

/// The NlpProblem as Ipopt's TNLP: g(x) ≤ 0 as g ∈ [−∞, 0], h(x) = 0 as h ∈ [0, 0]; dense Jacobian.
class ProblemAsTnlp : public Ipopt::TNLP {
 public:
  ProblemAsTnlp(EvaluationCache& cache, OptimizerResult& result) : cache_(cache), result_(result) {}

  std::string error;           ///< the last evaluation's failure, if any
  Eigen::VectorXd final_point;  ///< Ipopt's final iterate (finalize_solution); empty before

  bool get_nlp_info(Index& n, Index& m, Index& nnz_jac_g, Index& nnz_h_lag, IndexStyleEnum& index_style) override {
    n = static_cast<Index>(problem().variableCount());
    m = static_cast<Index>(problem().inequalityCount() + problem().equalityCount());
    nnz_jac_g = n * m;
    nnz_h_lag = 0;  // limited-memory Hessian
    index_style = C_STYLE;
    return true;
  }

  bool get_bounds_info(Index n, Number* x_l, Number* x_u, Index m, Number* g_l, Number* g_u) override {
    Eigen::Map<Eigen::VectorXd>(x_l, n) = problem().lowerBounds();
    Eigen::Map<Eigen::VectorXd>(x_u, n) = problem().upperBounds();
    for (Index i = 0; i < m; ++i) {
      g_l[i] = i < problem().inequalityCount() ? -kInfinity : 0.0;
      g_u[i] = 0.0;
    }
    return true;
  }

  bool get_starting_point(Index n, bool, Number* x, bool, Number*, Number*, Index, bool, Number*) override {
    Eigen::Map<Eigen::VectorXd>(x, n) = problem().start();
    return true;
  }

  bool eval_f(Index n, const Number* x, bool, Number& obj_value) override {
    return evaluated(n, x, false, [&](const NlpEvaluation& e) { obj_value = e.cost; });
  }

  bool eval_grad_f(Index n, const Number* x, bool, Number* grad_f) override {
    return evaluated(n, x, true, [&](const NlpEvaluation& e) { Eigen::Map<Eigen::VectorXd>(grad_f, n) = e.cost_gradient; });
  }

  bool eval_g(Index n, const Number* x, bool, Index m, Number* g) override {
    return evaluated(n, x, false, [&](const NlpEvaluation& e) { Eigen::Map<Eigen::VectorXd>(g, m) = e.constraints; });
  }

  bool eval_jac_g(Index n, const Number* x, bool, Index m, Index, Index* iRow, Index* jCol, Number* values) override {
    if (values == nullptr) {  // the structure: dense, row by row
      for (Index i = 0; i < m; ++i)
        for (Index j = 0; j < n; ++j) {
          iRow[i * n + j] = i;
          jCol[i * n + j] = j;
        }
      return true;
    }
    return evaluated(n, x, true, [&](const NlpEvaluation& e) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(values, m, n) =
          e.constraint_jacobian;
    });
  }

  /// The final iterate, whose point the cache reports where Ipopt converged (EvaluationCache::conclude);
  /// the verdict is OptimizeTNLP's return.
  void finalize_solution(Ipopt::SolverReturn, Index n, const Number* x, const Number*, const Number*, Index,
                         const Number*, const Number*, Number, const Ipopt::IpoptData*,
                         Ipopt::IpoptCalculatedQuantities*) override {
    final_point = Eigen::Map<const Eigen::VectorXd>(x, n);
  }

  bool intermediate_callback(Ipopt::AlgorithmMode, Index, Number obj_value, Number inf_pr, Number, Number,
                             Number d_norm, Number, Number, Number, Index, const Ipopt::IpoptData*,
                             Ipopt::IpoptCalculatedQuantities*) override {
    cache_.recordIteration(obj_value, inf_pr, d_norm, result_);
    // Stops only when the budget refused an evaluation (returning nothing here is Ipopt#661's
    // undefined behaviour): Ipopt would otherwise shorten its step against every refusal.
    return cache_.budgetSpent().empty();
  }

 private:
  NlpProblem& problem() { return cache_.problem(); }

  /// Evaluates at x and hands the result over; a failed evaluation returns false, so that Ipopt
  /// shortens its step instead of aborting.
  template <class Use>
  bool evaluated(Index n, const Number* x, bool gradients, Use&& use) {
    try {
      use(cache_.at(Eigen::Map<const Eigen::VectorXd>(x, n), gradients));
      return true;
    } catch (const std::exception& e) {
      error = e.what();
      return false;
    }
  }

  EvaluationCache& cache_;
  OptimizerResult& result_;
};

/// Ipopt's name of its return status (IpReturnCodes_inc.h).
std::string returnStatusName(Ipopt::ApplicationReturnStatus code) {
  switch (code) {
    case Ipopt::Solve_Succeeded: return "Solve_Succeeded";
    case Ipopt::Solved_To_Acceptable_Level: return "Solved_To_Acceptable_Level";
    case Ipopt::Infeasible_Problem_Detected: return "Infeasible_Problem_Detected";
    case Ipopt::Search_Direction_Becomes_Too_Small: return "Search_Direction_Becomes_Too_Small";
    case Ipopt::Diverging_Iterates: return "Diverging_Iterates";
    case Ipopt::User_Requested_Stop: return "User_Requested_Stop";
    case Ipopt::Feasible_Point_Found: return "Feasible_Point_Found";
    case Ipopt::Maximum_Iterations_Exceeded: return "Maximum_Iterations_Exceeded";
    case Ipopt::Restoration_Failed: return "Restoration_Failed";
    case Ipopt::Error_In_Step_Computation: return "Error_In_Step_Computation";
    case Ipopt::Maximum_CpuTime_Exceeded: return "Maximum_CpuTime_Exceeded";
    case Ipopt::Not_Enough_Degrees_Of_Freedom: return "Not_Enough_Degrees_Of_Freedom";
    case Ipopt::Invalid_Problem_Definition: return "Invalid_Problem_Definition";
    case Ipopt::Invalid_Option: return "Invalid_Option";
    case Ipopt::Invalid_Number_Detected: return "Invalid_Number_Detected";
    case Ipopt::Unrecoverable_Exception: return "Unrecoverable_Exception";
    case Ipopt::NonIpopt_Exception_Thrown: return "NonIpopt_Exception_Thrown";
    case Ipopt::Insufficient_Memory: return "Insufficient_Memory";
    case Ipopt::Internal_Error: return "Internal_Error";
  }
  return "return status " + std::to_string(static_cast<int>(code));
}

/// Ipopt's return (EvaluationCache::conclude checks it).
void judge(Ipopt::ApplicationReturnStatus code, const ProblemAsTnlp& tnlp, OptimizerResult& result) {
  switch (code) {
    case Ipopt::Solve_Succeeded:
    case Ipopt::Solved_To_Acceptable_Level:
      result.status = OptimizerStatus::Converged;
      break;
    case Ipopt::Maximum_Iterations_Exceeded:
    case Ipopt::Maximum_CpuTime_Exceeded:
      result.status = OptimizerStatus::MaxIterations;
      break;
    default:
      result.status = OptimizerStatus::Failed;
  }
  result.message = "Ipopt: " + returnStatusName(code) + " (" + std::to_string(static_cast<int>(code)) + ")";
  if (!tnlp.error.empty()) result.message += "; last failed evaluation: " + tnlp.error;
}

/// Any registered Ipopt option, typed as Ipopt registers it, its value checked against its range.
void setOptions(const NamedSettings& settings, Ipopt::IpoptApplication& app) {
  for (const auto& [name, value] : settings) {
    const Ipopt::SmartPtr<const Ipopt::RegisteredOption> option = app.RegOptions()->GetOption(name);
    if (Ipopt::IsNull(option)) throw std::invalid_argument("Ipopt has no option '" + name + "'");
    bool valid = false;
    switch (option->Type()) {
      case Ipopt::OT_Number: {
        const double number = settingNumber(name, value);
        valid = option->IsValidNumberSetting(number) && app.Options()->SetNumericValue(name, number);
        break;
      }
      case Ipopt::OT_Integer: {
        const double number = settingNumber(name, value);
        if (std::abs(number) > 2e9 || std::floor(number) != number) break;  // not an Index
        const auto integer = static_cast<Index>(number);
        valid = option->IsValidIntegerSetting(integer) && app.Options()->SetIntegerValue(name, integer);
        break;
      }
      default:
        valid = option->IsValidStringSetting(value) && app.Options()->SetStringValue(name, value);
    }
    if (!valid) throw std::invalid_argument("Ipopt's option " + name + " cannot take '" + value + "'");
  }
}

}  // namespace

OptimizerResult minimizeWithIpopt(NlpProblem& problem, const OptimizerOptions& options) {
  OptimizerResult result;
  result.optimizer = "Ipopt (L-BFGS Hessian)";
  EvaluationCache cache(problem, options);
  const Ipopt::SmartPtr<ProblemAsTnlp> tnlp = new ProblemAsTnlp(cache, result);
  // One Ipopt application at a time in a process: its linear solver (MUMPS, sequential) keeps
  // global state, and so may its option registry.
  static std::mutex one_at_a_time;
  const std::scoped_lock lock(one_at_a_time);
  const Ipopt::SmartPtr<Ipopt::IpoptApplication> app = IpoptApplicationFactory();
  app->Options()->SetStringValue("hessian_approximation", "limited-memory");
  app->Options()->SetStringValue("sb", "yes");  // no banner
  app->Options()->SetIntegerValue("print_level", 0);
  app->Options()->SetIntegerValue("max_iter", options.max_iterations);
  app->Options()->SetNumericValue("tol", options.tolerance);
  app->Options()->SetNumericValue("constr_viol_tol", options.feasibility_tolerance);
  // Ipopt relaxes every bound by 1e-8 (relative) by default and evaluates there: a design problem's
  // bounds can be physical (a mass > 0), and the best point must respect them.
  app->Options()->SetNumericValue("bound_relax_factor", 0.0);
  setOptions(options.settings, *app);
  if (app->Initialize() != Ipopt::Solve_Succeeded) throw std::runtime_error("Ipopt: initialisation failed");
  const Ipopt::ApplicationReturnStatus code = app->OptimizeTNLP(tnlp);
  judge(code, *tnlp, result);
  cache.conclude(result, tnlp->final_point);
  return result;
}

}  // namespace mbsopt
