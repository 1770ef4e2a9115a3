#include "mbsopt/design/benchmark_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "mbsopt/io/atomic_file.hpp"
#include "mbsopt/io/gnuplot.hpp"
#include "mbsopt/design/optimization_plots.hpp"

namespace mbsopt {

namespace fs = std::filesystem;

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// One run's record (null when its file is missing).
struct Record {
  const BenchmarkRun* run;
  nlohmann::json json;
};

std::string number(double value, const char* format = "%.6g") {
  if (!std::isfinite(value)) return "–";
  char text[64];
  std::snprintf(text, sizeof text, format, value);
  return text;
}

double finalCost(const nlohmann::json& record) {
  if (!record.contains("cost_functional")) return kInfinity;
  const nlohmann::json& value = record["cost_functional"]["final"];
  return value.is_number() ? value.get<double>() : kInfinity;
}

bool feasibleRun(const nlohmann::json& record) { return record.value("feasible", false); }

/// The reference's optimum of the cost's functional, from NAME.reference.json beside the problem's file.
std::optional<double> referenceOptimum(const BenchmarkProblem& p, const std::string& cost_key) {
  const fs::path reference = fs::path(p.path).replace_extension(".reference.json");
  std::ifstream in(reference);
  if (!in) return std::nullopt;
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, false);
  if (!json.is_object() || !json.contains("optimum")) return std::nullopt;
  const nlohmann::json& responses = json["optimum"]["responses"];
  if (!responses.is_object() || !responses.contains(cost_key)) return std::nullopt;
  return responses[cost_key].get<double>();
}

/// The simulation-equivalents at which the run solved its instance to τ (the header's test), +∞ if never.
double solvedAt(const nlohmann::json& record, double best, double tau) {
  if (!feasibleRun(record) || !record.contains("history")) return kInfinity;
  const double feasibility = OptimizerOptions{}.feasibility_tolerance;
  for (const nlohmann::json& h : record["history"]) {
    if (!h["cost_functional"].is_number() || h["max_violation"].get<double>() > feasibility) continue;
    if (h["cost_functional"].get<double>() <= best + tau * std::abs(best)) return h["simulation_equivalents"].get<double>();
  }
  return kInfinity;
}

double median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

/// A step function through the fractions of `values` ≤ x, from x = `from` to `to`.
PlotSeries profile(const std::string& title, std::vector<double> values, std::size_t instances, double from, double to) {
  std::sort(values.begin(), values.end());
  PlotSeries series{title, {}};
  std::size_t below = 0;
  while (below < values.size() && values[below] <= from) ++below;
  series.points.emplace_back(from, static_cast<double>(below) / static_cast<double>(instances));
  for (std::size_t k = below; k < values.size() && std::isfinite(values[k]); ++k) {
    const double before = static_cast<double>(k) / static_cast<double>(instances);
    series.points.emplace_back(values[k], before);
    series.points.emplace_back(values[k], static_cast<double>(k + 1) / static_cast<double>(instances));
  }
  series.points.emplace_back(to, series.points.back().second);
  return series;
}

}  // namespace

std::string writeBenchmarkReport(const BenchmarkOptions& options, const BenchmarkPlan& plan) {
  std::vector<Record> records;
  std::size_t missing = 0;
  for (const BenchmarkRun& run : plan.runs) {
    Record r{&run, nullptr};
    if (std::ifstream in(options.out + "/" + run.file); in) r.json = nlohmann::json::parse(in, nullptr, false);
    if (!r.json.is_object()) {
      r.json = nullptr;
      ++missing;
    }
    records.push_back(std::move(r));
  }
  // The solvers in the plan's order, and each problem's best known optimum.
  std::vector<std::string> solvers;
  for (const BenchmarkRun& run : plan.runs)
    if (std::find(solvers.begin(), solvers.end(), run.solver) == solvers.end()) solvers.push_back(run.solver);
  std::vector<double> best(plan.problems.size(), kInfinity);
  std::vector<std::string> best_source(plan.problems.size(), "no feasible run");
  std::vector<std::string> cost_key(plan.problems.size());
  for (const Record& r : records)
    if (!r.json.is_null() && r.json.contains("cost_functional")) cost_key[r.run->problem] = r.json["cost_functional"]["name"];
  for (std::size_t p = 0; p < plan.problems.size(); ++p) {
    if (const auto reference = referenceOptimum(plan.problems[p], cost_key[p])) {
      best[p] = *reference;
      best_source[p] = "the reference";
    }
    if (std::isfinite(best[p])) continue;  // a run may end below the reference by what the tolerances allow
    for (const Record& r : records)
      if (r.run->problem == p && !r.json.is_null() && feasibleRun(r.json) && finalCost(r.json) < best[p]) {
        best[p] = finalCost(r.json);
        best_source[p] = "the best feasible run";
      }
  }
  // t[τ][instance][solver]: the simulation-equivalents to solve, +∞ when not solved.
  const std::size_t instances = plan.problems.size() * static_cast<std::size_t>(options.starts);
  const auto instanceOf = [&](const BenchmarkRun& run) {
    return run.problem * static_cast<std::size_t>(options.starts) + static_cast<std::size_t>(run.start);
  };
  const auto solverOf = [&](const BenchmarkRun& run) {
    return static_cast<std::size_t>(std::find(solvers.begin(), solvers.end(), run.solver) - solvers.begin());
  };
  std::vector<std::vector<std::vector<double>>> t(
      std::size(kProfileTolerances), std::vector<std::vector<double>>(instances, std::vector<double>(solvers.size(), kInfinity)));
  for (const Record& r : records)
    if (!r.json.is_null())
      for (std::size_t k = 0; k < std::size(kProfileTolerances); ++k)
        t[k][instanceOf(*r.run)][solverOf(*r.run)] = solvedAt(r.json, best[r.run->problem], kProfileTolerances[k]);

  std::ostringstream md, csv;
  md << "# Benchmark: " << plan.problems.size() << " problems × " << options.starts << " starts × " << solvers.size()
     << " solvers\n\n";
  if (missing > 0) md << "**" << missing << " of " << records.size() << " runs have no file yet** (the sweep is unfinished).\n\n";
  md << "A run *solves* an instance (problem, start) to τ once an iterate is feasible with the cost's own functional "
        "f ≤ f_L + τ|f_L| and the run ends feasible in the problem's own units; f_L is the best known optimum. "
        "Start 0 is each problem's own, the others a Latin hypercube in the bounds (seed "
     << options.seed << ").\n\n";
  // Over all instances.
  md << "## All problems\n\n| solver | runs | converged | feasible | unsupported | solved τ=1e-1 | τ=1e-3 | τ=1e-5 | "
        "median sim.-eq. to τ=1e-3 |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t s = 0; s < solvers.size(); ++s) {
    std::size_t runs = 0, converged = 0, feasible = 0, unsupported = 0, solved[3] = {0, 0, 0};
    std::vector<double> cost_to_solve;
    for (const Record& r : records) {
      if (r.json.is_null() || solverOf(*r.run) != s) continue;
      ++runs;
      converged += r.json["status"] == "converged";
      unsupported += r.json["status"] == "unsupported";
      feasible += feasibleRun(r.json);
      for (std::size_t k = 0; k < 3; ++k) solved[k] += std::isfinite(t[k][instanceOf(*r.run)][s]);
      if (std::isfinite(t[1][instanceOf(*r.run)][s])) cost_to_solve.push_back(t[1][instanceOf(*r.run)][s]);
    }
    md << "| " << solvers[s] << " | " << runs << " | " << converged << " | " << feasible << " | " << unsupported << " | "
       << solved[0] << " | "
       << solved[1] << " | " << solved[2] << " | " << number(median(cost_to_solve), "%.0f") << " |\n";
  }
  std::size_t converged_infeasible = 0;
  for (const Record& r : records)
    if (!r.json.is_null() && r.json["status"] == "converged" && !feasibleRun(r.json)) ++converged_infeasible;
  md << "\nConverged runs that are not feasible in their problem's own units: " << converged_infeasible << ".\n\n";
  md << "![profiles](profiles.png)\n\n";
  // Per problem.
  // Each run's reported point (its result.json's cost_functional.final, in cost_unit), at full precision.
  csv << "problem,start,optimizer,gradient,formulation,status,reported_point,reported_iteration,feasible,"
         "cost_functional,best_known,cost_unit,relative_gap,simulation_equivalents,wall_time_s,solved_1e-1,"
         "solved_1e-3,solved_1e-5\n";
  for (std::size_t p = 0; p < plan.problems.size(); ++p) {
    const BenchmarkProblem& problem = plan.problems[p];
    md << "## " << problem.name << "\n\n" << cost_key[p] << ": best known " << number(best[p], "%.8g") << " ("
       << best_source[p] << ")\n\n| solver | formulation | converged | feasible | best | median (feasible) | "
                            "median sim.-eq. | solved τ=1e-3 |\n|---|---|---|---|---|---|---|---|\n";
    std::vector<std::string> reasons;
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      std::size_t converged = 0, feasible = 0, solved = 0, runs = 0;
      std::vector<double> costs, spent;
      double lowest = kInfinity;
      std::string formulation;
      for (const Record& r : records) {
        if (r.run->problem != p || solverOf(*r.run) != s || r.json.is_null()) continue;
        ++runs;
        formulation = formulationLabel(r.run->choice);
        const nlohmann::json& j = r.json;
        const std::string status = j["status"];
        converged += status == "converged";
        feasible += feasibleRun(j);
        solved += std::isfinite(t[1][instanceOf(*r.run)][s]);
        if (feasibleRun(j)) {
          costs.push_back(finalCost(j));
          lowest = std::min(lowest, finalCost(j));
        }
        if (j.contains("simulation_equivalents")) spent.push_back(j["simulation_equivalents"].get<double>());
        if (status != "converged")
          reasons.push_back("- " + solvers[s] + ", start " + std::to_string(r.run->start) + ": " + status + " — " +
                            j["message"].get<std::string>());
        const double cost = finalCost(j);
        const nlohmann::json reported = j.value("reported_iterate", nlohmann::json::object());
        const nlohmann::json reported_iteration = reported.value("iteration", nlohmann::json(nullptr));
        csv << problem.name << ',' << r.run->start << ',' << r.run->choice.optimizer << ',' << r.run->choice.gradient << ','
            << r.run->choice.formulation << ',' << status << ',' << reported.value("point", std::string()) << ','
            << (reported_iteration.is_number() ? std::to_string(reported_iteration.get<int>()) : "") << ','
            << (feasibleRun(j) ? "yes" : "no") << ',' << number(cost, "%.17g") << ',' << number(best[p], "%.17g") << ','
            << j.value("cost_functional", nlohmann::json::object()).value("unit", std::string()) << ','
            << number((cost - best[p]) / std::abs(best[p]), "%.3e") << ','
            << (j.contains("simulation_equivalents") ? number(j["simulation_equivalents"].get<double>(), "%.2f") : "")
            << ',' << (j.contains("wall_time_s") ? number(j["wall_time_s"].get<double>(), "%.3f") : "");
        for (std::size_t k = 0; k < 3; ++k) csv << ',' << number(t[k][instanceOf(*r.run)][s], "%.2f");
        csv << '\n';
      }
      if (runs == 0) continue;
      md << "| " << solvers[s] << " | " << formulation << " | " << converged << "/" << runs << " | " << feasible << "/" << runs << " | "
         << number(lowest, "%.8g") << " | " << number(median(costs), "%.8g") << " | " << number(median(spent), "%.0f")
         << " | " << solved << "/" << runs << " |\n";
    }
    md << "\n![convergence](convergence/" << problem.name << ".png)\n\n";
    if (!reasons.empty()) {
      md << "Runs that did not converge, and why:\n\n";
      for (const std::string& reason : reasons) md << reason << '\n';
      md << '\n';
    }
  }
  // Profiles: a row per τ, the performance profile (ratio to the best solver of each instance) beside
  // the data profile (simulation-equivalents).
  std::vector<PlotPanel> panels;
  for (std::size_t k = 0; k < std::size(kProfileTolerances); ++k) {
    char tau[32];
    std::snprintf(tau, sizeof tau, "τ = %g", kProfileTolerances[k]);
    PlotPanel performance{.xlabel = "α: within α times the best solver's cost", .ylabel = "fraction of instances",
                          .markers = false, .title = std::string("performance profile, ") + tau, .log_x = true};
    PlotPanel data{.xlabel = "simulation-equivalents", .ylabel = "fraction of instances", .markers = false,
                   .title = std::string("data profile, ") + tau, .log_x = true};
    double widest = 2.0, most = 1.0;
    std::vector<std::vector<double>> ratios(solvers.size()), spent(solvers.size());
    for (std::size_t i = 0; i < instances; ++i) {
      const double fastest = *std::min_element(t[k][i].begin(), t[k][i].end());
      for (std::size_t s = 0; s < solvers.size(); ++s) {
        const double ratio = std::isfinite(fastest) ? t[k][i][s] / fastest : kInfinity;
        ratios[s].push_back(ratio);
        spent[s].push_back(t[k][i][s]);
        if (std::isfinite(ratio)) widest = std::max(widest, 2.0 * ratio);
        if (std::isfinite(t[k][i][s])) most = std::max(most, 2.0 * t[k][i][s]);
      }
    }
    for (std::size_t s = 0; s < solvers.size(); ++s) {
      performance.series.push_back(profile(solvers[s], ratios[s], instances, 1.0, widest));
      data.series.push_back(profile(solvers[s], spent[s], instances, 1.0, most));
    }
    for (PlotPanel* panel : {&performance, &data}) {
      panel->y_min = 0.0;
      panel->y_max = 1.02;
      panels.push_back(*panel);
    }
  }
  plotPanels(options.out + "/profiles", "Dolan–Moré performance and Moré–Wild data profiles", panels, 2);
  // Convergence: per problem, a row per start, the cost's functional and the violation against
  // simulation-equivalents, a curve per solver.
  fs::create_directories(options.out + "/convergence");
  for (std::size_t p = 0; p < plan.problems.size(); ++p) {
    std::vector<PlotPanel> rows;
    for (int start = 0; start < options.starts; ++start) {
      char title[200];
      std::snprintf(title, sizeof title, "start %d: best %.8g (%s; 0 drawn at %.0e of it)", start, best[p],
                    best_source[p].c_str(), kDistanceFloor);
      PlotPanel cost{.xlabel = "simulation-equivalents", .ylabel = "|" + cost_key[p] + " - best|", .log_y = true,
                     .title = title};
      PlotPanel violation{.xlabel = "simulation-equivalents", .ylabel = "max violation (0 drawn at 1e-12)", .log_y = true,
                          .title = "start " + std::to_string(start)};
      std::vector<PlotSeries> reported_costs, reported_violations;  // each run's reported point, ringed
      for (std::size_t s = 0; s < solvers.size(); ++s) {
        PlotSeries c{solvers[s], {}}, v{solvers[s], {}};
        PlotSeries reported_c{"", {}, true, static_cast<int>(s) + 1}, reported_v = reported_c;
        for (const Record& r : records) {
          if (r.run->problem != p || r.run->start != start || solverOf(*r.run) != s || r.json.is_null() ||
              !r.json.contains("history"))
            continue;
          const nlohmann::json reported =
              r.json.value("reported_iterate", nlohmann::json::object()).value("iteration", nlohmann::json(nullptr));
          for (const nlohmann::json& h : r.json["history"]) {
            const double at = h["simulation_equivalents"].get<double>();
            const double violation_at = std::max(h["max_violation"].get<double>(), 1e-12);
            v.points.emplace_back(at, violation_at);
            if (!h["cost_functional"].is_number()) continue;
            c.points.emplace_back(at, distanceToBest(h["cost_functional"].get<double>(), best[p]));
            if (h["iteration"] == reported) {
              reported_c.points = {c.points.back()};
              reported_v.points = {{at, violation_at}};
            }
          }
        }
        cost.series.push_back(c);
        violation.series.push_back(v);
        reported_costs.push_back(reported_c);
        reported_violations.push_back(reported_v);
      }
      cost.series.insert(cost.series.end(), reported_costs.begin(), reported_costs.end());
      violation.series.insert(violation.series.end(), reported_violations.begin(), reported_violations.end());
      rows.push_back(cost);
      rows.push_back(violation);
    }
    plotPanels(options.out + "/convergence/" + plan.problems[p].name, "convergence on " + plan.problems[p].name, rows, 2);
  }
  const std::string report = md.str();
  writeAtomically(options.out + "/report.md", [&](std::ostream& out) { out << report; });
  writeAtomically(options.out + "/summary.csv", [&](std::ostream& out) { out << csv.str(); });
  return report;
}

}  // namespace mbsopt
