#include "app/optimize_command.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/sensitivity/parallel_runs.hpp"
#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/gnuplot.hpp"
#include "mbsopt/design/accurate_optimization.hpp"
#include "mbsopt/design/optimization_plots.hpp"
#include "mbsopt/design/optimization_run.hpp"
#include "mbsopt/design/run_record.hpp"
#include "app/exit_status.hpp"
#include "app/optimization_options.hpp"
#include "app/option_checks.hpp"
#include "app/output_paths.hpp"
#include "app/registry_choices.hpp"
#include "app/scene_argument.hpp"

namespace mbsopt {

namespace {

struct OptimizeOptions {
  SceneArgument problem;
  RunChoice choice;
  std::string json;
  std::string out;
  double accuracy = 0.0;  ///< > 0: optimizeToAccuracy
};

/// What the discretisation estimates say of a run driven by accuracy, for the JSON record.
nlohmann::json discretisationJson(const AccurateOptimization& accurate) {
  const auto estimate = [](const DiscretisationError& e) {
    return nlohmann::json{{"step", e.step},
                          {"variable_steps", e.variable_steps},
                          {"break_times", e.break_times},
                          {"cost_functional", e.cost},
                          {"cost_error", e.cost_error},
                          {"order", e.order},
                          {"constraint_errors", std::vector<double>(e.constraint_errors.data(),
                                                                     e.constraint_errors.data() + e.constraint_errors.size())},
                          {"constraint_values", std::vector<double>(e.constraint_values.data(),
                                                                     e.constraint_values.data() + e.constraint_values.size())},
                          {"largest_counted", e.largest()}};
  };
  nlohmann::json out = {{"tolerance", accurate.tolerance}, {"met", accurate.met}};
  out["grid_choice"] = nlohmann::json::array();
  for (const DiscretisationError& e : accurate.grid_choice) out["grid_choice"].push_back(estimate(e));
  out["rounds"] = nlohmann::json::array();
  for (std::size_t r = 0; r < accurate.rounds.size(); ++r) {
    const OptimizerResult& result = accurate.rounds[r].result;
    out["rounds"].push_back({{"at_optimum", estimate(accurate.at_optimum[r])},
                             {"status", toString(result.status)},
                             {"simulation_equivalents", result.simulation_equivalents},
                             {"wall_time_s", result.wall_time_s}});
  }
  return out;
}

/// The paper's figures 6-8 for one run: cost, max violation and design variables against
/// iterations, and the cost's sensor over time at the start and at the final design.
void plotRun(const std::string& directory, const std::string& problem, const OptimizationRun& run) {
  std::vector<PlotPanel> history = convergencePanels({{run.choice.optimizer, &run}}, false);
  history.push_back(designPanel(run));
  plotPanels(directory + "/history", "optimisation of " + problem, history);
  PlotPanel response{.xlabel = "t [s]",
                     .ylabel = run.cost_sensor + " [" + run.cost_sensor_unit + "]",
                     .markers = false};
  PlotSeries initial{"start", {}}, final{"final design", {}};
  for (Eigen::Index k = 0; k < run.time.size(); ++k) {
    initial.points.emplace_back(run.time[k], run.initial_history[k]);
    final.points.emplace_back(run.time[k], run.final_history[k]);
  }
  response.series = {initial, final};
  plotPanels(directory + "/response", "the cost's sensor at the start and at the final design", {response});
}

/// Whether the final design meets each constraint in its own units: the unmet ones, or the one
/// closest to its bound.
void printVerdicts(const std::vector<ConstraintVerdict>& verdicts) {
  if (verdicts.empty()) return;
  const auto print = [](const ConstraintVerdict& v) {
    std::printf("  %s = %.8g %s, %s %.8g, beyond it by %.3g (allowed %.3g)\n", v.name.c_str(), v.value, v.unit.c_str(),
                v.equality ? "asked" : "bound", v.bound, v.excess, v.tolerance);
  };
  const auto unmet = std::count_if(verdicts.begin(), verdicts.end(), [](const ConstraintVerdict& v) { return !v.met(); });
  if (unmet > 0) {
    std::printf("NOT feasible in the problem's units: %ld of %zu constraints unmet\n", static_cast<long>(unmet),
                verdicts.size());
    for (const ConstraintVerdict& v : verdicts)
      if (!v.met()) print(v);
    return;
  }
  std::printf("feasible in the problem's units: every one of %zu constraints met; the closest to its bound:\n",
              verdicts.size());
  print(*std::max_element(verdicts.begin(), verdicts.end(), [](const ConstraintVerdict& a, const ConstraintVerdict& b) {
    return a.excess - a.tolerance < b.excess - b.tolerance;
  }));
}

/// Which point the summary reports, and why (OptimizerResult::reported).
void printReportedPoint(const OptimizationRun& run) {
  const std::string iteration = run.reported_iteration >= 0 ? ", iteration " + std::to_string(run.reported_iteration) : "";
  if (run.result.status == OptimizerStatus::Unsupported) {
    std::printf("reported: the start (the optimizer cannot take this problem and evaluated nothing)\n");
    return;
  }
  switch (run.result.reported) {
    case ReportedPoint::Final:
      std::printf("reported: the optimizer's final point%s, where its own test passed and every constraint holds "
                  "within its tolerance\n", iteration.c_str());
      if (!std::isnan(run.cheapest_cost)) {
        const double below = run.responses[run.cost_response].get<double>() - run.cheapest_cost;
        std::printf("  the cheapest feasible iterate (%s) has %s %.3g %s lower",
                    run.cheapest_iteration >= 0 ? ("iteration " + std::to_string(run.cheapest_iteration)).c_str()
                                                : "a trial point",
                    run.cost_response.c_str(), below, run.cost_unit.c_str());
        if (!std::isnan(run.tolerance_worth))
          std::printf(", %s the %.3g %s the constraints' tolerances are worth here", below <= run.tolerance_worth ? "within" : "MORE than",
                      run.tolerance_worth, run.cost_unit.c_str());
        std::printf("\n");
      }
      return;
    case ReportedPoint::CheapestFeasible:
      std::printf("reported: the cheapest feasible iterate%s (least %s among the points that meet every "
                  "constraint within its tolerance; the run did not converge)\n",
                  iteration.c_str(), run.cost_response.c_str());
      return;
    case ReportedPoint::LeastInfeasible:
      std::printf("reported: the least infeasible point evaluated%s (no point evaluated meets every constraint)\n",
                  iteration.c_str());
      return;
  }
}

/// What relaxing each active bound is worth at the reported point (a converged run's multipliers).
void printBoundWorth(const OptimizationRun& run) {
  if (run.result.status != OptimizerStatus::Converged || !run.result.first_order) return;
  if (run.bound_worth.empty()) {
    std::printf("no constraint or bound is active at the optimum: relaxing one is worth nothing\n");
    return;
  }
  std::printf("what relaxing each active bound is worth at the optimum (from the optimizer's multipliers, the paper's "
              "(7)-(8)):\n");
  for (const BoundWorth& w : run.bound_worth) {
    const std::string unit = w.unit.empty() ? "SI unit" : w.unit;
    char value[32];
    std::snprintf(value, sizeof value, "%.8g", w.bound);
    const std::string bound = w.unit.empty() ? value : std::string(value) + " " + w.unit;
    const char* relation = w.equality ? "=" : w.raising_relaxes ? "<=" : ">=";
    if (w.equality)
      std::printf("  %s %s %s: raising it by one %s changes %s by %.4g %s\n", w.name.c_str(), relation, bound.c_str(),
                  unit.c_str(), run.cost_response.c_str(), w.derivative, run.cost_unit.c_str());
    else
      std::printf("  %s %s %s: %s it by one %s lowers %s by %.4g %s\n", w.name.c_str(), relation, bound.c_str(),
                  w.raising_relaxes ? "raising" : "lowering", unit.c_str(), run.cost_response.c_str(),
                  w.relaxingLowersCostBy(), run.cost_unit.c_str());
  }
}

void printIteration(const IterationRecord& r) {
  std::printf("%5d  %14.8e  %11.3e  %10.3e  %6ld  %6ld\n", r.iteration, r.cost, r.max_violation, r.step,
              r.value_evaluations, r.gradient_evaluations);
  std::fflush(stdout);
}

void optimize(const OptimizeOptions& options) {
  const SceneSource source = resolveScene(options.problem.scene);
  checkOutputFile("--json", options.json, source.path);
  checkOutputDirectory("--out", options.out);
  const DesignProblem problem = loadDesignProblem(source, parseOverrides(source, options.problem.sets));
  std::string why;
  const RunChoice c = options.accuracy > 0.0 ? accurateChoice(problem, options.choice, &why) : options.choice;
  std::printf("optimize %s with %s, %s gradients, %s formulation\n", source.path.c_str(), c.optimizer.c_str(),
              c.gradient.c_str(), c.formulation.empty() ? "the problem's" : c.formulation.c_str());
  if (!why.empty()) std::printf("%s\n", why.c_str());
  std::optional<AccurateOptimization> accurate;
  if (options.accuracy > 0.0) {
    accurate = optimizeToAccuracy(problem, c, options.accuracy, printIteration, [](const std::string& news) {
      std::printf("%s\n", news.c_str());
      if (news.starts_with("optimizing")) std::printf(" iter  b_{k+1}         max_viol     step        sims   grads\n");
      std::fflush(stdout);
    });
  } else {
    std::printf(" iter  b_{k+1}         max_viol     step        sims   grads\n");
  }
  OptimizationRun run = accurate ? accurate->rounds.back() : runOptimization(problem, c, printIteration);
  if (accurate) {  // the start is the first grid's; the histories (and response.png) are the last grid's
    run.start = accurate->rounds.front().start;
    run.initial_cost = accurate->rounds.front().initial_cost;
  }
  const OptimizerResult& r = run.result;
  std::printf("%s: %s (%s)\n", r.optimizer.c_str(), toString(r.status).c_str(), r.message.c_str());
  std::printf("b_{k+1} %.8g, max violation %.3g, %d iterations, %ld simulations, %ld gradients: %.4g "
              "simulation-equivalents (a gradient counted %.3g, %s; %.0f simulations' thread time), %.3g s\n",
              r.cost, r.max_violation, r.iterations, r.value_evaluations, r.gradient_evaluations,
              r.simulation_equivalents, run.gradient_cost, run.gradient_cost_source.c_str(), run.thread_time_simulations,
              r.wall_time_s);
  printReportedPoint(run);
  if (run.simulations_ahead > 0)
    std::printf("%ld of the simulations ran ahead on a spare core, while another point was evaluated (%ld more ran "
                "ahead for a point not asked for after all)\n",
                run.simulations_ahead_used, run.simulations_ahead - run.simulations_ahead_used);
  const auto spaced = [](const std::string& unit) { return unit.empty() ? unit : " " + unit; };
  for (std::size_t i = 0; i < run.design.size(); ++i)
    std::printf("  %s = %.8g%s\n", problem.design.variables[i].parameter.c_str(), run.design[i],
                spaced(run.variable_units[i]).c_str());
  for (const auto& [name, value] : run.responses.items())
    std::printf("  %s = %.6g%s\n", name.c_str(), value.get<double>(),
                spaced(run.response_units.value(name, std::string())).c_str());
  const double final_cost = run.responses[run.cost_response].get<double>();
  const std::string unit = spaced(run.cost_unit);
  std::printf("%s = %.8g%s, %s by %.4g %% from %.8g%s at the start", run.cost_response.c_str(), final_cost, unit.c_str(),
              final_cost <= run.initial_cost ? "lowered" : "RAISED",
              100.0 * std::abs(run.initial_cost - final_cost) / run.initial_cost, run.initial_cost, unit.c_str());
  std::printf("\n");
  if (accurate) {
    const DiscretisationError& e = accurate->at_optimum.back();
    double wall = 0.0, equivalents = 0.0;
    for (const OptimizationRun& round : accurate->rounds) {
      wall += round.result.wall_time_s;
      equivalents += round.result.simulation_equivalents;
    }
    std::printf("%s = %.8g +- %.2g %s at the optimum (discretisation error at %s, from h, h/2 and h/4: order "
                "%.2g; constraints' up to %.2g, of those that can be active %.2g); accuracy %g %s after %zu grid%s (%.4g simulation-equivalents, %.3g s)\n",
                run.cost_response.c_str(), e.cost, e.cost_error, run.cost_unit.c_str(), describeGrid(e).c_str(), e.order,
                e.largestConstraintError(), e.largestActiveConstraintError(), accurate->tolerance,
                accurate->met ? "met" : "NOT met", accurate->rounds.size(), accurate->rounds.size() == 1 ? "" : "s",
                equivalents, wall);
  }
  printVerdicts(run.verdicts);
  printBoundWorth(run);
  nlohmann::json record = toJson(run, source.path);
  if (accurate) record["discretisation"] = discretisationJson(*accurate);
  if (!options.json.empty())
    writeAtomically(options.json, [&](std::ostream& out) { out << record.dump(2) << '\n'; });
  if (!options.out.empty()) {
    writeAtomically(options.out + "/result.json", [&](std::ostream& out) { out << record.dump(2) << '\n'; });
    plotRun(options.out, source.path, run);
    std::printf("wrote %s/result.json, history.png, response.png (with their .dat and .gp)\n", options.out.c_str());
  }
  if (r.status != OptimizerStatus::Converged)
    throw NotConverged(r.optimizer + " did not converge: " + toString(r.status) + " (exit status 2)");
  if (accurate && !accurate->met)
    throw NotConverged("the discretisation error at the optimum exceeds --accuracy after " +
                       std::to_string(kMaxAccuracyRounds) + " grids (exit status 2)");
}

}  // namespace

void registerOptimizeCommand(CLI::App& app) {
  auto options = std::make_shared<OptimizeOptions>();
  CLI::App* command = app.add_subcommand(
      "optimize",
      "Minimise a design problem's cost (the paper's artificial variable b_{k+1}) subject to its constraints with "
      "one optimizer and one gradient method; prints an iteration table (cost, max violation, step, simulations and "
      "gradients so far) and a summary with the final design and its responses. Exit status: 0 when the optimizer "
      "converged, 2 when it did not (failed, stopped by its budget, or cannot take the problem; the outputs are "
      "written all the same), 1 on an error");
  addSceneArgument(*command, options->problem, true);
  command->add_option("--optimizer", options->choice.optimizer, "The optimizer: " + describedChoices(optimizers()))
      ->check(CLI::IsMember(optimizerNames()))
      ->capture_default_str();
  command->add_option("--gradient", options->choice.gradient, "The gradient method: " + describedChoices(gradientMethods()))
      ->check(CLI::IsMember(gradientMethodChoices()))
      ->capture_default_str();
  command->add_option("--formulation", options->choice.formulation,
                      "How each max-over-time constraint becomes one number (default: the problem's own, the scene "
                      "file's design.transcription; grid_max where it names none): " + describedChoices(formulations()))
      ->check(CLI::IsMember(formulationNames()));
  command
      ->add_option_function<double>(
          "--epsilon", [options](double epsilon) { options->choice.epsilon = epsilon; },
          "ε ≥ 0: each transcribed constraint becomes measure ≤ ε, with the problem's measure or --formulation's "
          "(the paper's ∫⟨φ⟩dt has a zero gradient where satisfied; ε > 0 gives it an interior); default: the "
          "problem's own (design.transcription.tolerance)")
      ->check(nonNegativeNumber());
  addBudgetOptions(*command, options->choice);
  addSettingOption(*command, options->choice.settings);
  options->choice.gradient_jobs = machineThreads();
  command->add_option("--jobs", options->choice.gradient_jobs,
                      "Threads for each gradient (default: this machine's hardware threads): the simulations of "
                      "finite differences, the step derivatives of adjoint and direct (their sweep itself is "
                      "sequential; continuous-adjoint runs on one); with 2 or more, SDCC's next trial point is "
                      "simulated on a spare core while the current one is. The results do not depend on it, and "
                      "thread_time_simulations only through the threads' overheads and the "
                      "simulations run ahead for nothing")
      ->check(positiveInteger())
      ->capture_default_str();
  command->add_option("--json", options->json,
                      "Write the result as JSON: problem, mbsopt_version, command_line, variables[{parameter, unit, lower, "
                      "upper, scale, start, final}] (SI), variables_unit, artificial_variable{start, lower, upper, scale, final}, "
                      "budget{simulation_equivalents, wall_time_s (the limits, null: none), gradient_cost, gradient_cost_source, "
                      "spent, unit, max_iterations, max_iterations_counts}, settings, optimizer, gradient, formulation, epsilon, status, "
                      "message, design (SI), responses, response_units, constraints[{name, unit, value, bound | equals, excess, tolerance, met}] "
                      "(each constraint judged at the final design in its own units: angles in degrees; the "
                      "tolerance is its own or 1e-4 |bound|, at least 1e-6 in SI units), feasible (all met), initial_cost, cost (b_{k+1}), cost_functional{name, "
                      "unit, start, final} (the cost sensor's own functional), reported_iterate{iteration, point (final, "
                      "cheapest_feasible or least_infeasible), rule, cheapest_feasible_cost, cheapest_feasible_iteration} "
                      "(the history's record of the reported design and why it is reported), bound_worth[{name, kind, "
                      "parameter, bound, unit, equality, d_cost_d_bound, relaxing_lowers_cost_by, relaxed_by, "
                      "cost_unit_per_unit, tolerance}] (what relaxing each active bound is worth at a converged "
                      "optimum, from the multipliers), kkt_residual, tolerance_worth, max_violation, iterations, simulations, "
                      "gradient_evaluations, simulation_equivalents (the budget's count), thread_time_simulations (the "
                      "evaluations' thread time, each one's wall time times the threads it held, over one simulation's, "
                      "simulation_s), simulations_ahead "
                      "(run on a spare core for the point SDCC would try after a rejection) and "
                      "simulations_ahead_used (those among the simulations), "
                      "wall_time_s, history[{iteration, cost (b_{k+1}), max_violation, step, cost_functional (the cost's own, "
                      "in cost_functional.name's unit), simulations, gradient_evaluations, simulation_equivalents, design "
                      "(SI; null, as cost_functional, where the optimizer does not say which point it is)}]");
  command
      ->add_option("--accuracy", options->accuracy,
                   "Optimize to this discretisation accuracy (the cost's functional and each transcribed constraint "
                   "that can be active, in their own units): the time step is chosen at the start from the values on "
                   "2h, h and h/2 (h the scene's step), graded at the times a curve slider passes a jump of its "
                   "track's curvature (one short step across each: order 2 again), and kept fixed while the "
                   "optimizer runs (the objective stays smooth in the design); at the optimum the error is estimated "
                   "again and, where it exceeds TOL, the grid is graded again at the optimum's break times or "
                   "refined, and the optimizer goes on from the optimum (at most 4 grids). A problem's own "
                   "positive_part or squared_positive_part transcription becomes grid_max unless --formulation says "
                   "(the integrals are met only to the optimizer's feasibility tolerance). The summary gives the cost "
                   "as value +- error; the JSON a `discretisation` record. Exit status 2 when the accuracy is not met")
      ->check(positiveNumber());
  command->add_option("--out", options->out,
                      "Directory (created if missing) for result.json and two gnuplot figures like the paper's 6-8: "
                      "history.png (the distance of the cost's own functional to the best on a logarithmic axis, the max violation and the design variables against iterations, the reported point ringed) and response.png "
                      "(the cost's sensor over time at the start and at the final design)");
  command->callback([options] { locatingRunFailures(options->problem, [&] { optimize(*options); }); });
}

}  // namespace mbsopt
