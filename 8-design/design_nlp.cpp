#include "mbsopt/design/design_nlp.hpp"

#include <algorithm>
#include <chrono>
#include <memory>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/design/constraint_verdicts.hpp"

namespace mbsopt {

namespace {

/// Adds the wall time from its construction to its destruction to `total`, however the scope ends.
class ElapsedTimeInto {
 public:
  explicit ElapsedTimeInto(std::atomic<double>& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~ElapsedTimeInto() { total_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  ElapsedTimeInto(const ElapsedTimeInto&) = delete;
  ElapsedTimeInto& operator=(const ElapsedTimeInto&) = delete;

 private:
  std::atomic<double>& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

DesignNlp::DesignNlp(DesignProblem problem, std::string gradient_method, double fd_step, int gradient_jobs,
                     std::shared_ptr<ThreadBudget> shared_threads)
    : problem_(std::move(problem)),
      functionals_(transcribe(problem_)),
      gradient_method_(std::move(gradient_method)),
      fd_step_(fd_step),
      gradient_jobs_(std::max(gradient_jobs, 1)),
      simulate_ahead_(gradient_jobs_ >= 2 && !shared_threads),
      spare_threads_(shared_threads ? std::move(shared_threads) : std::make_shared<ThreadBudget>(gradient_jobs_ - 1)) {
  gradient_method_ = gradientMethod(gradient_method_).name;  // an alias resolved; an unknown name throws
}

Eigen::VectorXd DesignNlp::scaledBounds(double DesignVariable::*variable_bound,
                                        double ArtificialVariable::*artificial_bound) const {
  const DesignDescription& d = problem_.design;
  Eigen::VectorXd bounds(variableCount());
  for (std::size_t i = 0; i < d.variables.size(); ++i)
    bounds[static_cast<Eigen::Index>(i)] = d.variables[i].*variable_bound / d.variables[i].scale;
  bounds[bounds.size() - 1] = d.artificial.*artificial_bound / d.artificial.scale;
  return bounds;
}

const DesignResponse* DesignNlp::keptSimulation(const Eigen::VectorXd& x) const {
  if (first_ && first_->first == x) return &first_->second;
  for (const auto& [point, response] : recent_)
    if (point == x) return &response;
  return nullptr;
}

const DesignResponse& DesignNlp::keep(const Eigen::VectorXd& x, DesignResponse response) {
  if (!first_) {
    first_.emplace(x, std::move(response));
    return first_->second;
  }
  recent_.emplace_front(x, std::move(response));
  if (recent_.size() > kKeptSimulations) {
    spare_ = std::move(recent_.back().second);  // its buffers, for the next simulation
    recent_.pop_back();
  }
  return recent_.front().second;
}

const DesignResponse& DesignNlp::simulation(const Eigen::VectorXd& x) {
  double thread_seconds = 0.0;
  return simulation(x, thread_seconds);
}

const DesignResponse& DesignNlp::simulation(const Eigen::VectorXd& x, double& thread_seconds) {
  if (const DesignResponse* kept = keptSimulation(x)) return *kept;
  if (const auto ahead = aheadOf(x); ahead != ahead_.end()) {
    std::future<DesignResponse> response = std::move(ahead->response);
    ahead_.erase(ahead);
    ++simulations_ahead_used_;
    spare_threads_->giveBack(1);  // this thread only waits: it lends itself meanwhile
    startWaiting();
    response.wait();
    spare_threads_->reclaim();
    return keep(x, response.get());  // what evaluateDesign threw, it throws here
  }
  startWaiting();
  const auto start_time = std::chrono::steady_clock::now();
  evaluateDesign(problem_, functionals_, x, spare_, {});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  fastest_simulation_s_ = fastest_simulation_s_ > 0.0 ? std::min(fastest_simulation_s_, seconds) : seconds;
  thread_seconds += seconds;
  return keep(x, std::move(spare_));
}

void DesignNlp::anticipate(const Eigen::VectorXd& x) {
  if (!simulate_ahead_ || keptSimulation(x) || aheadOf(x) != ahead_.end()) return;
  waiting_ = x;
  startWaiting();
}

std::deque<DesignNlp::Ahead>::iterator DesignNlp::aheadOf(const Eigen::VectorXd& x) {
  return std::find_if(ahead_.begin(), ahead_.end(), [&](const Ahead& a) { return a.x == x; });
}

void DesignNlp::startWaiting() {
  const auto finished = [](const Ahead& a) {
    return a.response.wait_for(std::chrono::seconds(0)) == std::future_status::ready;
  };
  while (ahead_.size() > kKeptSimulations && finished(ahead_.back())) ahead_.pop_back();
  if (!waiting_) return;
  auto thread = std::make_unique<BorrowedThreads>(*spare_threads_, 1);
  if (thread->count() == 0) return;
  // The problem and the functionals are only read, by evaluateDesign as by this thread.
  ahead_.push_front({*waiting_, std::async(std::launch::async, [this, thread = std::move(thread), x = *waiting_]() mutable {
                       const std::unique_ptr<BorrowedThreads> held = std::move(thread);  // given back as it ends
                       const ElapsedTimeInto timed(ahead_thread_seconds_);
                       return evaluateDesign(problem_, functionals_, x);
                     })});
  waiting_.reset();
  ++simulations_ahead_;
}

void DesignNlp::evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) {
  const DesignResponse& response = simulation(x, evaluation_thread_seconds_);
  if (gradients) {  // on the simulation just run or kept: the values' simulation is not paid twice
    const auto start_time = std::chrono::steady_clock::now();
    const BorrowedThreads spare(*spare_threads_, gradient_jobs_ - 1);
    const int threads = 1 + spare.count();
    DesignGradient g = designGradient(gradient_method_, problem_, functionals_, x, fd_step_, &response, threads);
    out.cost_gradient = std::move(g.cost);
    out.constraint_jacobian = std::move(g.constraints);
    evaluation_thread_seconds_ +=
        threads * std::chrono::duration<double>(std::chrono::steady_clock::now() - start_time).count();
  }
  out.cost = response.cost;
  out.constraints = response.constraints;
  out.reported_cost = costFunctional(problem_, response);
  out.excess_over_tolerance = excessOverTolerance(constraintVerdicts(problem_, response));
}

double DesignNlp::gradientCost() const {
  const double variables = static_cast<double>(problem_.design.variables.size());
  if (const int per_variable = gradientMethod(gradient_method_).simulations_per_variable; per_variable > 0)
    return per_variable * variables;
  return gradient_cost_.value_or(1.0);
}

double DesignNlp::measureGradientCost(const Eigen::VectorXd& x, int repetitions) const {
  if (gradientMethod(gradient_method_).simulations_per_variable > 0) return gradientCost();
  const auto seconds_since = [](std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  // b_{k+1} = 0 puts the cost's every time point in its constraint (|y| − b ≥ 0): a gradient's
  // whole backward sweep, its dearest case. At a start where b_{k+1} bounds the cost with room to
  // spare no point is seeded, and a gradient costs next to nothing.
  Eigen::VectorXd at = x;
  at[at.size() - 1] = 0.0;
  std::vector<double> ratios;
  for (int k = 0; k < std::max(repetitions, 1); ++k) {
    auto start_time = std::chrono::steady_clock::now();
    const DesignResponse response = evaluateDesign(problem_, functionals_, at);
    const double simulation_s = seconds_since(start_time);
    start_time = std::chrono::steady_clock::now();
    designGradient(gradient_method_, problem_, functionals_, at, fd_step_, &response, 1);
    ratios.push_back(seconds_since(start_time) / simulation_s);
  }
  std::nth_element(ratios.begin(), ratios.begin() + static_cast<std::ptrdiff_t>(ratios.size() / 2), ratios.end());
  return ratios[ratios.size() / 2];
}

}  // namespace mbsopt
