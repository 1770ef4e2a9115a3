// The integrators by name (`--integrator`, one registry) and the one entry point that runs
// a scene with any of them: a fixed step, a fixed macro step with extrapolation, or a run driven by
// accuracy; with or without an estimate of its global error (docs/integrators.md).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mbsopt/integrators/accuracy_control.hpp"
#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/integrators/scene.hpp"

namespace mbsopt {

struct IntegratorInfo {
  std::string name;
  std::string description;  ///< one sentence, for --help
  /// Newmark runs per attempt at most when driven by accuracy (AccuracyGoal::max_runs): 2 for plain
  /// Newmark (a run at h/2 with the estimate from h), more for extrapolation.
  int max_runs = 2;
  /// Runs at H/1 … H/k combined (Aitken-Neville): an error estimate with every run, `runs` to choose.
  bool extrapolated = false;
  /// Steps chosen by each step's local error (a local tolerance; a design problem freezes the grid
  /// its initial design takes): the steps end at the output times.
  bool variable_steps = false;
};

/// newmark (the paper's; the default), extrapolation, adaptive.
const std::vector<IntegratorInfo>& integrators();
/// The registered integrator `name`; std::invalid_argument listing the names otherwise.
const IntegratorInfo& integratorInfo(const std::string& name);
/// The registered names in the registry's order: newmark, extrapolation, adaptive.
std::vector<std::string> integratorNames();
/// "newmark, extrapolation, adaptive".
std::string integratorNameList();

/// How to run a scene.
struct IntegrationRequest {
  /// The integrator by name, with the extrapolation's runs at a fixed macro step (H/1 … H/runs) and
  /// the adaptive integrator's local tolerance without `accuracy`.
  IntegratorChoice integrator;
  /// Steps (and runs) chosen to meet this (simulateToAccuracy); without it the scene's step is used:
  /// Newmark's step h, or the extrapolation's macro step H with the integrator's runs.
  std::optional<ErrorTolerance> accuracy;
  /// The result's time points are the multiples of uniformStep(output_step, end_time) [s], the last
  /// at the end time; 0: every step (Newmark) or every macro step (extrapolation, or a run driven by
  /// accuracy). At most the end time. A fixed step is then uniformStep(step, that output interval):
  /// at most the scene's, a whole number of them in each interval.
  double output_step = 0.0;
  /// A fixed-step Newmark run also estimates its global error (from a run at h/2: three times the work).
  bool estimate_error = false;
};

/// How `scene` runs unless told otherwise: its own integrator, with its runs and local tolerance; to
/// `accuracy`, the extrapolation unless `integrator` names another. `mbsopt simulate` and the Python
/// module's Scene.simulate both start from it.
IntegrationRequest sceneIntegration(const Scene& scene, const std::optional<std::string>& integrator = std::nullopt,
                                    const std::optional<ErrorTolerance>& accuracy = std::nullopt);

struct Integration {
  /// The result at its time points. q_error, v_error, sensor_error are empty when no estimate was
  /// asked for (a fixed-step Newmark run without estimate_error).
  EstimatedRun run;
  bool estimated = false;
  /// Driven by accuracy: the accepted macro step, the weighted estimate (≤ kAcceptedFraction) and the
  /// attempts rejected before it.
  std::optional<AccurateRun> control;
};

/// Runs the scene as `request` says. std::invalid_argument for an unknown integrator or an output step
/// that does not fit; SimulationError from a fixed-step run, AccuracyError when no attempt meets the
/// accuracy. `progress(t)` after each step of every run.
Integration integrate(const Model& model, const NewmarkSettings& settings, const Eigen::VectorXd& q0,
                      const Eigen::VectorXd& v0, const IntegrationRequest& request,
                      const std::function<void(double)>& progress = {});

}  // namespace mbsopt
