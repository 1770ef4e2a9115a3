// A design problem as the optimizers see it (docs/design.md §5): min b_{k+1} over the scaled design
// variables and b_{k+1}, subject to every transcribed constraint ≤ 0 (= 0 for an equality, after
// the inequalities) and the variables' bounds, with the gradients of the named method. One value
// evaluation is one simulation. The adapter between the two layers below, which know nothing of
// each other: 6-optimizers/ (an NlpProblem) and 5-sensitivity/ (simulations and gradients of a design
// problem).
#pragma once

#include <algorithm>
#include <atomic>
#include <deque>
#include <future>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/thread_budget.hpp"
#include "mbsopt/optimizers/nlp_problem.hpp"

namespace mbsopt {

class DesignNlp : public NlpProblem {
 public:
  /// `gradient_method`: one of gradientMethodChoices() (an alias becomes the name it stands for); `fd_step` for the finite differences;
  /// `gradient_jobs`: the most threads a gradient takes (designGradient; the values do not depend on
  /// it). The threads beyond the caller's own are this problem's, or, with `shared_threads`, borrowed
  /// from it whenever they are idle (the runs of `mbsopt compare` lend theirs to one another).
  DesignNlp(DesignProblem problem, std::string gradient_method, double fd_step = 1e-6, int gradient_jobs = 1,
            std::shared_ptr<ThreadBudget> shared_threads = nullptr);

  Eigen::Index variableCount() const override { return optimisationSize(problem_); }
  Eigen::Index inequalityCount() const override {
    return static_cast<Eigen::Index>(functionals_.size()) - equalityCount();
  }
  /// transcribe() puts the equalities last, as NlpProblem orders them.
  Eigen::Index equalityCount() const override {
    return std::count_if(functionals_.begin(), functionals_.end(), [](const ConstraintFunctional& f) { return f.equality; });
  }
  Eigen::VectorXd lowerBounds() const override { return scaledBounds(&DesignVariable::lower, &ArtificialVariable::lower); }
  Eigen::VectorXd upperBounds() const override { return scaledBounds(&DesignVariable::upper, &ArtificialVariable::upper); }
  Eigen::VectorXd start() const override { return initialPoint(problem_); }
  std::string constraintName(Eigen::Index i) const override { return functionals_[static_cast<std::size_t>(i)].name; }
  void evaluate(const Eigen::VectorXd& x, bool gradients, NlpEvaluation& out) override;
  /// With gradient_jobs ≥ 2 and threads of its own (no shared_threads), simulates x on an idle one
  /// (a spare thread, or this one's while it only waits for such a simulation) while this one goes
  /// on (its own simulation, or a gradient); a point that finds no idle thread waits for the next
  /// evaluation that does. simulation(x) then takes the result: the same to the bit, as
  /// evaluateDesign depends only on the problem and x. Otherwise it does nothing: with shared
  /// threads, a simulation that may be wasted would make a run's cost depend on what the others
  /// left idle.
  void anticipate(const Eigen::VectorXd& x) override;

  /// NlpProblem::gradientCost: finite differences count their simulations (one per design
  /// variable, two central); an exact method's gradient costs what setGradientCost said (a
  /// measurement, measureGradientCost), as much as a simulation until then.
  double gradientCost() const override;
  void setGradientCost(double simulation_equivalents) { gradient_cost_ = simulation_equivalents; }
  /// What one gradient costs at x in simulation-equivalents: for finite differences their count,
  /// else the median over `repetitions` of a gradient's wall time on one thread (its work, whatever
  /// the threads a run gives it) over a simulation's, each run afresh at x with b_{k+1} = 0 (every time point of the cost active: the whole backward
  /// sweep). Outside every count of evaluate(); nothing is kept.
  double measureGradientCost(const Eigen::VectorXd& x, int repetitions = 3) const;

  const DesignProblem& problem() const { return problem_; }
  /// The thread time evaluate() has taken so far [s], whatever the number of threads: each of its
  /// simulations' wall time, each gradient's times the threads it held, and the wall time of every
  /// simulation run ahead on another thread (used or not; a wait for one counts nothing, the waiting
  /// thread being lent meanwhile). The work of the evaluations, comparable between runs that had
  /// different numbers of threads.
  double evaluationThreadSeconds() const { return evaluation_thread_seconds_ + ahead_thread_seconds_.load(); }
  /// The fastest of the simulations evaluate() ran [s] (interference only ever slows one down);
  /// 0 before the first.
  double simulationSeconds() const { return fastest_simulation_s_; }
  /// The simulation at x when it is one of those kept (the first point evaluated and the
  /// kKeptSimulations most recent), else nullptr.
  const DesignResponse* keptSimulation(const Eigen::VectorXd& x) const;
  /// The simulation at x: a kept one, one simulated ahead (anticipate(), waited for), or a new one
  /// (timed, then kept). The reference holds until kKeptSimulations more points are simulated.
  const DesignResponse& simulation(const Eigen::VectorXd& x);
  static constexpr std::size_t kKeptSimulations = 4;
  /// The simulations anticipate() started, and how many of them simulation() then used (the others
  /// ran on a core that was idle, for a point the optimizer did not ask for after all).
  long simulationsAhead() const { return simulations_ahead_; }
  long simulationsAheadUsed() const { return simulations_ahead_used_; }
  const std::vector<ConstraintFunctional>& functionals() const { return functionals_; }

 private:
  /// One bound of every variable, in the scaled units the optimizers see.
  Eigen::VectorXd scaledBounds(double DesignVariable::*variable_bound, double ArtificialVariable::*artificial_bound) const;

  DesignProblem problem_;
  std::vector<ConstraintFunctional> functionals_;
  std::string gradient_method_;
  double fd_step_;
  int gradient_jobs_;
  bool simulate_ahead_;                          ///< threads of its own, at least two
  std::shared_ptr<ThreadBudget> spare_threads_;  ///< the threads beyond the caller's (thread_budget.hpp)
  double evaluation_thread_seconds_ = 0.0;       ///< on the caller's thread
  std::atomic<double> ahead_thread_seconds_ = 0.0;  ///< on the threads of the simulations ahead
  double fastest_simulation_s_ = 0.0;
  std::optional<double> gradient_cost_;
  /// Simulations by point: the first one evaluated, then the most recent, newest first. The
  /// gradients of a point whose values were asked for first reuse its simulation.
  std::optional<std::pair<Eigen::VectorXd, DesignResponse>> first_;
  std::deque<std::pair<Eigen::VectorXd, DesignResponse>> recent_;
  /// Keeps a new simulation as the first or the most recent one; the one it pushes out becomes spare_.
  const DesignResponse& keep(const Eigen::VectorXd& x, DesignResponse response);
  /// The buffers of the last simulation pushed out (empty before the first): the next simulation on
  /// this thread is written into them, and its trajectory then needs no new pages (a new
  /// trajectory's first-touch page faults cost about 6 % of a tram simulation, bench_dynamics:
  /// BM_TramwaySimulation). A simulation that fails leaves the kept ones as they were.
  DesignResponse spare_;
  /// simulation(x), adding to `thread_seconds` the wall time of a simulation run on this thread.
  const DesignResponse& simulation(const Eigen::VectorXd& x, double& thread_seconds);

  /// Simulations started by anticipate(), newest first; the point anticipated last when no core was
  /// free for it. Last among the members: destroyed first, each waiting for its thread.
  long simulations_ahead_ = 0, simulations_ahead_used_ = 0;
  std::optional<Eigen::VectorXd> waiting_;
  struct Ahead {
    Eigen::VectorXd x;
    std::future<DesignResponse> response;
  };
  std::deque<Ahead> ahead_;
  /// The simulation started for x, or ahead_.end().
  std::deque<Ahead>::iterator aheadOf(const Eigen::VectorXd& x);
  /// Starts the waiting point on a spare thread when one is idle, and forgets the oldest finished
  /// simulations ahead beyond kKeptSimulations.
  void startWaiting();
};

}  // namespace mbsopt
