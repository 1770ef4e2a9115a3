#include "mbsopt/design/constraint_verdicts.hpp"

#include <algorithm>
#include <cmath>

#include "mbsopt/sensitivity/design_evaluation.hpp"
#include "mbsopt/sensitivity/time_functional.hpp"

namespace mbsopt {

namespace {


const char* measureName(ResponseMeasure of) {
  switch (of) {
    case ResponseMeasure::MaxAbs: return "max_abs";
    case ResponseMeasure::Max: return "max";
    case ResponseMeasure::Min: return "min";
    case ResponseMeasure::Integral: return "integral";
    case ResponseMeasure::FinalValue: return "final";
    case ResponseMeasure::Rms: return "rms";
  }
  return "";
}

/// The constraint's functional of y on the time grid.
double functionalValue(ResponseMeasure of, const Eigen::VectorXd& time, const Eigen::VectorXd& y) {
  switch (of) {
    case ResponseMeasure::MaxAbs: return y.cwiseAbs().maxCoeff();
    case ResponseMeasure::Max: return y.maxCoeff();
    case ResponseMeasure::Min: return y.minCoeff();
    case ResponseMeasure::Integral: return evaluateTimeFunctional(TimeMeasure::Integral, time, y).value;
    case ResponseMeasure::FinalValue: return y[y.size() - 1];
    case ResponseMeasure::Rms: return evaluateTimeFunctional(TimeMeasure::RootMeanSquare, time, y).value;
  }
  return 0.0;
}

}  // namespace

std::string measureUnit(const Model& model, const Sensor& sensor, ResponseMeasure of) {
  return sensorUnit(model, sensor) + (of == ResponseMeasure::Integral ? "·s" : "");
}

double constraintTolerance(const ResponseConstraint& constraint) {
  return constraint.tolerance.value_or(std::max(kRelativeTolerance * std::abs(constraint.bound), kAbsoluteTolerance));
}

std::string constraintName(const ResponseConstraint& constraint) { return constraint.sensor + "_" + measureName(constraint.of); }

std::vector<ConstraintVerdict> constraintVerdicts(const DesignProblem& problem, const DesignResponse& response) {
  if (response.made_of == ResponseParts::ExtrapolationRuns) {  // the verdicts of the combination the optimizer saw, not of one run
    const Eigen::VectorXd w = runWeights(problem, 1);
    std::vector<ConstraintVerdict> out;
    for (Eigen::Index i = 0; i < w.size(); ++i) {
      const int j = static_cast<int>(i) + 1;  // runs 2 … k
      const std::vector<ConstraintVerdict> run =
          constraintVerdicts(extrapolationRunProblem(problem, j + 1), extrapolationRunResponse(response, j + 1));
      if (out.empty()) {
        out = run;
        for (ConstraintVerdict& v : out) v.value *= w[i], v.excess *= w[i];
      } else {
        for (std::size_t c = 0; c < out.size(); ++c) out[c].value += w[i] * run[c].value, out[c].excess += w[i] * run[c].excess;
      }
    }
    for (ConstraintVerdict& v : out)  // |value − bound| is not linear in the runs' values
      if (v.equality) v.excess = std::abs(v.value - v.bound);
    return out;
  }
  const Model& model = problem.scene.model;
  const std::size_t cases = std::max<std::size_t>(problem.load_cases.size(), 1);
  std::vector<ConstraintVerdict> out;
  for (std::size_t k = 0; k < cases; ++k) {
    const Trajectory& trajectory = caseTrajectory(response, k);
    for (const ResponseConstraint& c : problem.design.constraints) {
      const int index = sensorIndex(model, c.sensor);
      const Sensor& sensor = model.sensors()[static_cast<std::size_t>(index)];
      const double unit = inUnits(sensor, 1.0);  // SI → the reported unit
      ConstraintVerdict v;
      v.name = constraintName(c) + (problem.load_cases.empty() ? "" : "_" + problem.load_cases[k].name);
      v.unit = measureUnit(model, sensor, c.of);
      const double value = functionalValue(c.of, trajectory.time, trajectory.sensors.col(index));
      const double excess = c.equality ? std::abs(value - c.bound)
                            : c.of == ResponseMeasure::Min ? c.bound - value
                                                            : value - c.bound;
      v.value = value * unit;
      v.bound = c.bound * unit;
      v.equality = c.equality;
      v.excess = excess * unit;
      v.tolerance = unit * constraintTolerance(c);
      out.push_back(v);
    }
  }
  return out;
}

double excessOverTolerance(const std::vector<ConstraintVerdict>& verdicts) {
  double worst = 0.0;
  for (const ConstraintVerdict& v : verdicts) worst = std::max(worst, v.excess / v.tolerance);
  return worst;
}

}  // namespace mbsopt
