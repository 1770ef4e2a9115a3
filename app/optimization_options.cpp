#include "app/optimization_options.hpp"

#include "mbsopt/sensitivity/formulation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "app/option_checks.hpp"

namespace mbsopt {

void addSweepOptions(CLI::App& command, SweepAxes& axes, RunChoice& shared) {
  command.add_option("--optimizers", axes.optimizers, "Optimizers to run")
      ->delimiter(',')
      ->check(CLI::IsMember(optimizerNames()))
      ->capture_default_str();
  command.add_option("--gradients", axes.gradients, "Gradient methods (fd = fd_central)")
      ->delimiter(',')
      ->check(CLI::IsMember(gradientMethodChoices()))
      ->capture_default_str();
  command.add_option("--formulations", axes.formulations,
                     "Formulations (see `mbsopt optimize --help`); default: each problem's own")
      ->delimiter(',')
      ->check(CLI::IsMember(formulationNames()));
  command
      .add_option_function<double>(
          "--epsilon", [&shared](double epsilon) { shared.epsilon = epsilon; },
          "ε ≥ 0 of every run, with the problem's measure or each of --formulations (see `mbsopt optimize --help`); "
          "default: each problem's own")
      ->check(nonNegativeNumber());
}

void addBudgetOptions(CLI::App& command, RunChoice& choice) {
  command.add_option("--budget", choice.budget.simulation_equivalents,
                     "The budget of each run in simulation-equivalents, alike for every optimizer: a simulation "
                     "counts 1, a gradient --gradient-cost; an evaluation that would exceed it is not made, and the "
                     "run ends with its best point, status max_iterations (default: none)")
      ->check(positiveNumber());
  command.add_option("--wall-time", choice.budget.wall_time_s,
                     "The wall time of each run's optimizer [s]: no evaluation starts after it (default: none)")
      ->check(positiveNumber());
  command
      .add_option_function<double>(
          "--gradient-cost", [&choice](double cost) { choice.gradient_cost = cost; },
          "What one gradient counts in simulation-equivalents (default: for finite differences their simulations, "
          "one per design variable or two with fd_central; for an exact method the median of three timed "
          "gradient/simulation pairs on one thread at the start with b_{k+1} = 0, where the whole backward sweep runs)")
      ->check(positiveNumber());
  command.add_option("--max-iter", choice.max_iterations,
                     "Each optimizer's own limit (NLopt: objective evaluations; Ipopt and SDCC: their own "
                     "iterations); --budget is the one that counts alike for all")
      ->check(positiveInteger())
      ->capture_default_str();
}

void addSettingOption(CLI::App& command, std::vector<std::string>& settings) {
  command.add_option("--setting", settings,
                     "An optimizer's own setting, NAME=VALUE for every optimizer that runs or OPTIMIZER.NAME=VALUE "
                     "for one (ipopt.mu_strategy=adaptive); repeat for several. sdcc: active_set_epsilon, "
                     "initial_step_bound, shrink_factor, growth_factor, growth_ratio, acceptance_ratio, "
                     "min_step_bound, stationarity_tolerance, initial_penalty, penalty_factor, weights (one per "
                     "variable, comma-separated) (6-optimizers/sdcc.hpp); ipopt: any Ipopt option, e.g. "
                     "mu_strategy=adaptive or tol=1e-10; slsqp, mma, ccsaq: NLopt's stopping criteria xtol_rel "
                     "(default 1e-6), xtol_abs, ftol_rel (default 0: NLopt applies it at infeasible points too, where "
                     "b_{k+1} stays put while feasibility is restored), ftol_abs, stopval, maxtime [s]; mma, ccsaq "
                     "also inner_maxeval, dual_ftol_rel, verbosity. An unknown name is an error")
      ->allow_extra_args(false);
}

}  // namespace mbsopt
