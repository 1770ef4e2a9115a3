// The report of `mbsopt benchmark`, from the run files alone (a sweep spread over MPI ranks, or
// resumed, reports as one that ran here at once): per problem a table of every solver (optimizer,
// gradient method, formulation) over the starts and the reasons of every run that did not converge;
// the convergence of the cost's own functional and of the violation against simulation-equivalents;
// Dolan–Moré performance profiles and Moré–Wild data profiles.
//
// A run solves an instance (problem, start) to τ once a recorded iterate is feasible in the
// optimizer's terms (max violation ≤ the optimizers' feasibility tolerance) with the cost's own
// functional f ≤ f_L + τ |f_L|, and the run ends feasible in the problem's own units; its cost is
// the simulation-equivalents spent by then. f_L is the best known optimum: the problem's reference
// (NAME.reference.json beside its file), or where there is none the best feasible final cost of any
// run (docs/benchmarking.md). Moré and Wild (2009) measure f(x₀) − f ≤ (1 − τ)(f(x₀) − f_L) instead; with
// constraints the start may be infeasible and its cost below f_L, which that test cannot take.
#pragma once

#include "mbsopt/design/benchmark_plan.hpp"

namespace mbsopt {

/// The tolerances τ of the profiles.
inline constexpr double kProfileTolerances[] = {1e-1, 1e-3, 1e-5};

/// Writes OUT/report.md, OUT/summary.csv, OUT/profiles.png and OUT/convergence/NAME.png (each
/// figure with its .dat and .gp) from the plan's run files; returns the report's text. Runs whose
/// file is missing are counted as such.
std::string writeBenchmarkReport(const BenchmarkOptions& options, const BenchmarkPlan& plan);

}  // namespace mbsopt
