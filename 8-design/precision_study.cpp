#include "mbsopt/design/precision_study.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <numeric>
#include <stdexcept>

#include "mbsopt/algorithms/sensors.hpp"
#include "mbsopt/integrators/extrapolation.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/integrators/trajectory.hpp"
#include "mbsopt/io/scene_file.hpp"
#include "mbsopt/io/scene_text.hpp"

namespace mbsopt {

namespace {

/// The index k of t = k·h on the grid of step h (within round-off), or −1.
long gridIndex(double t, double step) {
  const double ratio = t / step;
  const double k = std::round(ratio);
  return std::abs(ratio - k) <= 1e-6 ? static_cast<long>(k) : -1;
}

/// The grid indices of `times` (ascending) for step h; they must be on the grid (requireOnGrids).
std::vector<long> gridIndices(const Eigen::VectorXd& times, double step) {
  std::vector<long> indices;
  for (const double t : times) indices.push_back(gridIndex(t, step));
  return indices;
}

/// A run of ⌈T/h⌉ steps that keeps q, q̇, q̈ only at the grid indices `at` (ascending): a reference
/// of millions of steps needs no memory, and the time measured is that of the integration alone.
struct SampledTrajectory {
  Trajectory samples;
  IntegratorStatistics statistics;
};

SampledTrajectory integrateSampled(const Scene& scene, const NewmarkSettings& settings, const std::vector<long>& at,
                            const std::function<void(double)>& progress = {}) {
  NewmarkIntegrator integrator(scene.model, settings);
  integrator.initialize(scene.q0, scene.v0, 0.0);
  const Eigen::Index n = scene.model.coordinateCount(), points = static_cast<Eigen::Index>(at.size());
  SampledTrajectory run;
  Trajectory& samples = run.samples;
  samples.time.resize(points);
  samples.q.resize(n, points);
  samples.v.resize(n, points);
  samples.a.resize(n, points);
  Eigen::Index next = 0;
  const auto keep = [&](long k) {
    for (; next < points && at[static_cast<std::size_t>(next)] == k; ++next) {
      samples.time[next] = integrator.time();
      samples.q.col(next) = integrator.q();
      samples.v.col(next) = integrator.v();
      samples.a.col(next) = integrator.a();
    }
  };
  keep(0);
  const long steps = stepsToCover(settings.end_time, settings.step);
  for (long k = 1; k <= steps; ++k) {
    integrator.step();
    keep(k);
    if (progress) progress(integrator.time());
  }
  run.statistics = integrator.statistics();
  return run;
}

/// The quantities at every sample: rows = samples, columns = quantities.
Eigen::MatrixXd quantityValues(const Model& model, const Trajectory& samples, const std::vector<Quantity>& quantities) {
  const bool any_sensor = std::any_of(quantities.begin(), quantities.end(), [](const Quantity& q) { return q.sensor; });
  const Eigen::MatrixXd sensors = any_sensor ? sensorHistory(model, samples) : Eigen::MatrixXd();
  Eigen::MatrixXd values(samples.time.size(), static_cast<Eigen::Index>(quantities.size()));
  for (std::size_t j = 0; j < quantities.size(); ++j) {
    const Eigen::Index column = static_cast<Eigen::Index>(j);
    values.col(column) = quantities[j].sensor ? Eigen::VectorXd(sensors.col(quantities[j].index))
                                              : Eigen::VectorXd(samples.q.row(quantities[j].index).transpose());
  }
  return values;
}

std::vector<Quantity> findQuantities(const Model& model, const std::vector<std::string>& names) {
  std::vector<Quantity> quantities;
  for (const std::string& name : names) quantities.push_back(findQuantity(model, name));
  return quantities;
}

/// Fields of one CSV line and the 1-based column where each starts.
std::vector<std::pair<std::string, int>> splitCsvLine(const std::string& line) {
  std::vector<std::pair<std::string, int>> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t comma = line.find(',', start);
    std::string field = line.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    const std::size_t first = field.find_first_not_of(" \t"), last = field.find_last_not_of(" \t\r");
    field = first == std::string::npos ? "" : field.substr(first, last - first + 1);
    fields.emplace_back(field, static_cast<int>(start + (first == std::string::npos ? 0 : first)) + 1);
    if (comma == std::string::npos) return fields;
    start = comma + 1;
  }
}

}  // namespace

Quantity findQuantity(const Model& model, const std::string& name) {
  std::vector<std::string> names;
  for (std::size_t i = 0; i < model.coordinates().size(); ++i) {
    if (model.coordinates()[i].name == name) return {name, false, static_cast<Eigen::Index>(i)};
    names.push_back(model.coordinates()[i].name);
  }
  for (std::size_t s = 0; s < model.sensors().size(); ++s) {
    if (model.sensors()[s].name == name) return {name, true, static_cast<Eigen::Index>(s)};
    names.push_back(model.sensors()[s].name);
  }
  throw std::invalid_argument(quoted(name) + " is neither a coordinate nor a sensor of the scene" +
                              suggestion(name, names) + " (they are: " + listed(names) + ")");
}

namespace {

/// A variant of the scheme: the integrator it runs and how it changes the scene's settings.
struct IntegratorVariant {
  std::string name;
  std::string integrator;  ///< a name of the integrators' registry (4-integrators/integration.cpp)
  NewmarkSettings (*settings)(NewmarkSettings settings, double alpha);
};

const std::vector<IntegratorVariant>& integratorVariants() {
  static const std::vector<IntegratorVariant> variants{
      {"newmark", "newmark", [](NewmarkSettings s, double) { return s; }},
      {"damped", "newmark",
       [](NewmarkSettings s, double alpha) {
         s.gamma = 0.5 + alpha;
         s.beta = 0.25 * (s.gamma + 0.5) * (s.gamma + 0.5);
         return s;
       }},
      {"fast-newton", "newmark",
       [](NewmarkSettings s, double) {
         s.accept_by_contraction_rate = true;
         return s;
       }},
      {"fast-steps", "newmark", [](NewmarkSettings s, double) { return withFastSteps(s); }},
      {"acceleration-closure", "newmark",
       [](NewmarkSettings s, double) {
         s.closure = ClosureLevel::Acceleration;
         return s;
       }},
      {"extrapolation", "extrapolation", [](NewmarkSettings s, double) { return s; }},
  };
  return variants;
}

const IntegratorVariant& integratorVariant(const std::string& name) {
  for (const IntegratorVariant& variant : integratorVariants())
    if (variant.name == name) return variant;
  throw std::invalid_argument("unknown variant " + quoted(name) + suggestion(name, integratorVariantNames()) +
                              " (the variants: " + listed(integratorVariantNames()) + ")");
}

}  // namespace

bool runsExtrapolation(const std::string& variant) {
  return integratorInfo(integratorVariant(variant).integrator).extrapolated;
}

const std::vector<std::string>& integratorVariantNames() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const IntegratorVariant& variant : integratorVariants()) out.push_back(variant.name);
    return out;
  }();
  return names;
}

NewmarkSettings variantSettings(NewmarkSettings settings, const std::string& variant, double alpha) {
  settings = integratorVariant(variant).settings(settings, alpha);
  if (runsExtrapolation(variant))
    if (const std::string defect = extrapolationDefect(settings); !defect.empty()) throw std::invalid_argument(defect);
  return settings;
}

Eigen::VectorXd commonGridTimes(const std::vector<double>& steps, double end_time) {
  const double largest = *std::max_element(steps.begin(), steps.end());
  std::vector<double> times;
  for (long k = 1; k * largest <= end_time * (1.0 + 1e-12); ++k) {
    const double t = static_cast<double>(k) * largest;
    if (std::all_of(steps.begin(), steps.end(), [t](double h) { return gridIndex(t, h) >= 0; })) times.push_back(t);
  }
  if (times.empty())
    throw std::invalid_argument("the steps have no common time point in (0, " + formatNumber(end_time) +
                                "] s: choose steps that are whole multiples of one another (a factor-2 ladder), "
                                "with a reference step that divides them all");
  return Eigen::Map<const Eigen::VectorXd>(times.data(), static_cast<Eigen::Index>(times.size()));
}

void requireOnGrids(const Eigen::VectorXd& times, const std::vector<double>& steps, double end_time) {
  for (const double t : times)
    for (const double h : steps) {
      const long k = gridIndex(t, h);
      if (k < 0)
        throw std::invalid_argument("the reference time t = " + formatNumber(t) + " s is not on the grid of the step " +
                                    formatNumber(h) + " s (t/h = " + formatNumber(t / h) +
                                    "): give reference rows at multiples of every swept step");
      if (k > stepsToCover(end_time, h))
        throw std::invalid_argument("the reference time t = " + formatNumber(t) +
                                    " s lies after the end of the runs (" + formatNumber(end_time) + " s)");
    }
}

ReferenceSolution readReferenceCsv(const std::string& path, const Model& model,
                                   const std::vector<std::string>& quantities) {
  std::ifstream in(path);
  if (!in) throw SceneError(path, 0, 0, "cannot open the reference file");
  std::string line;
  if (!std::getline(in, line))
    throw SceneError(path, 0, 0, "the reference file is empty: expected a header t,<name>,... (each name may carry its unit, t [s])");
  auto header = splitCsvLine(line);
  for (auto& [name, column] : header)  // "name [unit]", as mbsopt simulate writes its headers: the name
    if (const std::size_t unit = name.find(" ["); unit != std::string::npos && name.back() == ']') name.resize(unit);
  if (header[0].first != "t")
    throw SceneError(path, 1, header[0].second,
                     "the first column must be the time 't', not " + quoted(header[0].first));
  std::vector<Quantity> columns;  // the file's columns after t
  std::vector<std::string> names;
  for (std::size_t c = 1; c < header.size(); ++c) {
    const auto& [name, column] = header[c];
    try {
      columns.push_back(findQuantity(model, name));
    } catch (const std::invalid_argument& e) {
      throw SceneError(path, 1, column, "column " + std::string(e.what()));
    }
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw SceneError(path, 1, column, "column " + quoted(name) + " appears twice");
    names.push_back(name);
  }
  if (columns.empty()) throw SceneError(path, 1, 0, "the header has no column after 't': nothing to compare");

  std::vector<std::vector<double>> rows;
  for (int number = 2; std::getline(in, line); ++number) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    const auto fields = splitCsvLine(line);
    if (fields.size() != header.size())
      throw SceneError(path, number, 0, std::to_string(fields.size()) + " fields, but the header has " +
                                            std::to_string(header.size()));
    std::vector<double> row;
    for (const auto& [text, column] : fields) {
      char* end = nullptr;
      const double value = std::strtod(text.c_str(), &end);
      if (text.empty() || *end != '\0' || !std::isfinite(value))
        throw SceneError(path, number, column, quoted(text) + " is not a finite number");
      row.push_back(value);
    }
    if (row[0] < 0.0) throw SceneError(path, number, fields[0].second, "a negative time");
    rows.push_back(std::move(row));
  }
  if (rows.empty()) throw SceneError(path, 0, 0, "the reference file has a header but no rows");
  std::stable_sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a[0] < b[0]; });

  // The compared columns: those asked for, else the sensors, else all.
  std::vector<std::size_t> chosen;
  for (const std::string& name : quantities) {
    const auto at = std::find(names.begin(), names.end(), name);
    if (at == names.end())
      throw SceneError(path, 1, 0, "--quantities: " + quoted(name) + " is not a column of the file (its columns: " +
                                       listed(names) + ")");
    chosen.push_back(static_cast<std::size_t>(at - names.begin()));
  }
  if (chosen.empty())
    for (std::size_t c = 0; c < columns.size(); ++c)
      if (columns[c].sensor) chosen.push_back(c);
  if (chosen.empty()) {
    chosen.resize(columns.size());
    std::iota(chosen.begin(), chosen.end(), 0);
  }

  ReferenceSolution reference;
  reference.file = path;
  reference.times.resize(static_cast<Eigen::Index>(rows.size()));
  reference.values.resize(static_cast<Eigen::Index>(rows.size()), static_cast<Eigen::Index>(chosen.size()));
  for (std::size_t j = 0; j < chosen.size(); ++j) reference.quantities.push_back(columns[chosen[j]]);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const Eigen::Index r = static_cast<Eigen::Index>(i);
    reference.times[r] = rows[i][0];
    for (std::size_t j = 0; j < chosen.size(); ++j)
      reference.values(r, static_cast<Eigen::Index>(j)) = rows[i][chosen[j] + 1];
  }
  return reference;
}

namespace {

/// The extrapolation of `runs` runs at the macro step `settings.step`, kept at the time points `at` (their
/// indices on its grid), with the largest error it estimates for each compared quantity there.
SampledTrajectory extrapolatedSamples(const Scene& scene, const NewmarkSettings& settings, int runs,
                                      const std::vector<long>& at, const std::vector<Quantity>& quantities,
                                      double& estimate) {
  const EstimatedRun run = extrapolatedNewmark(scene.model, settings, runs, scene.q0, scene.v0);
  const std::vector<Eigen::Index> points(at.begin(), at.end());
  SampledTrajectory kept;
  kept.samples.time = run.trajectory.time(points);
  kept.samples.q = run.trajectory.q(Eigen::all, points);
  kept.samples.v = run.trajectory.v(Eigen::all, points);
  kept.samples.a = run.trajectory.a(Eigen::all, points);
  kept.samples.lambda = run.trajectory.lambda(Eigen::all, points);
  kept.statistics = run.trajectory.statistics;
  estimate = 0.0;
  for (const Quantity& quantity : quantities)
    for (const Eigen::Index k : points)
      estimate = std::max(estimate, std::abs(quantity.sensor ? run.sensor_error(k, quantity.index)
                                                             : run.q_error(quantity.index, k)));
  return kept;
}

}  // namespace

ReferenceSolution referenceRun(const Scene& scene, double step, int runs, const Eigen::VectorXd& times,
                               const std::vector<std::string>& quantities,
                               const std::function<void(double)>& progress) {
  std::vector<std::string> names = quantities;
  if (names.empty())
    for (const Coordinate& c : scene.model.coordinates()) names.push_back(c.name);
  ReferenceSolution reference;
  reference.step = step;
  try {
    reference.quantities = findQuantities(scene.model, names);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("--quantities: " + std::string(e.what()));
  }
  reference.times = times;
  NewmarkSettings settings = scene.settings;
  settings.step = step;
  const auto start = std::chrono::steady_clock::now();
  double estimate = 0.0;
  const SampledTrajectory run =
      runs > 1 ? extrapolatedSamples(scene, settings, runs, gridIndices(times, step), reference.quantities, estimate)
               : integrateSampled(scene, settings, gridIndices(times, step), progress);
  reference.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  reference.values = quantityValues(scene.model, run.samples, reference.quantities);
  return reference;
}

PrecisionRun measureIntegratorRun(const Scene& scene, const std::string& variant, double step, double alpha, int runs,
                                  const ReferenceSolution& reference, int repeat) {
  PrecisionRun result;
  result.variant = variant;
  result.step = step;
  SampledTrajectory run;
  try {
    NewmarkSettings settings = variantSettings(scene.settings, variant, alpha);
    settings.step = step;
    const std::vector<long> at = gridIndices(reference.times, step);
    if (runsExtrapolation(variant)) {
      double estimate = 0.0;
      timeMedian(repeat, [&] { run = extrapolatedSamples(scene, settings, runs, at, reference.quantities, estimate); },
                 result.seconds);
      result.estimated_error = estimate;
    } else {
      timeMedian(repeat, [&] { run = integrateSampled(scene, settings, at); }, result.seconds);
    }
  } catch (const SimulationError& e) {
    return failedRun(result, e);
  } catch (const std::invalid_argument& e) {  // settings the integrator refuses (say, too many steps)
    return failedRun(result, e);
  }
  result.steps = run.statistics.steps;
  result.newton_iterations = run.statistics.newton_iterations;
  const Eigen::MatrixXd values = quantityValues(scene.model, run.samples, reference.quantities);
  result.error = 0.0;
  for (std::size_t j = 0; j < reference.quantities.size(); ++j) {
    const Eigen::Index column = static_cast<Eigen::Index>(j);
    const std::string& name = reference.quantities[j].name;
    if (!values.col(column).allFinite()) {
      Eigen::Index k = 0;
      while (std::isfinite(values(k, column))) ++k;
      result.failed = true;
      result.message = quoted(name) + " is not finite at t = " + formatNumber(reference.times[k]) + " s";
      result.error = std::numeric_limits<double>::quiet_NaN();
      return result;
    }
    const double error = (values.col(column) - reference.values.col(column)).cwiseAbs().maxCoeff();
    result.errors.emplace_back(name, error);
    result.error = std::max(result.error, error);
  }
  return result;
}

}  // namespace mbsopt
