#include "mbsopt/io/design_file.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "mbsopt/model/units.hpp"
#include "mbsopt/sensitivity/formulation.hpp"
#include "mbsopt/io/scene_text.hpp"

namespace mbsopt {

namespace {

/// `of:` among `choices` (max_abs, max, integral, rms, and for constraints min, final).
ResponseMeasure readMeasure(const MapReader& entry, const std::vector<std::string>& choices) {
  const std::string of = entry.choice("of", choices, "max_abs");
  return of == "max"        ? ResponseMeasure::Max
         : of == "min"      ? ResponseMeasure::Min
         : of == "integral" ? ResponseMeasure::Integral
         : of == "final"    ? ResponseMeasure::FinalValue
         : of == "rms"      ? ResponseMeasure::Rms
                            : ResponseMeasure::MaxAbs;
}

std::string readSensor(const MapReader& entry, const Model& model) {
  const std::string name = entry.name("sensor");
  std::vector<std::string> names;
  for (const Sensor& s : model.sensors()) {
    if (s.name == name) {
      if (const std::string defect = designSensorDefect(s); !defect.empty()) entry.fail("sensor", defect);
      return name;
    }
    names.push_back(s.name);
  }
  entry.fail("sensor", "sensor '" + name + "' does not exist" + suggestion(name, names));
}

/// lower ≤ upper, scale > 0; `value` (the starting point) inside the bounds.
void readRange(const MapReader& entry, double value, double& lower, double& upper, double& scale) {
  lower = entry.number("lower");
  upper = entry.number("upper");
  if (!(lower <= upper)) entry.fail("upper", "upper must not be below lower");
  scale = entry.has("scale") ? entry.positive("scale") : 1.0;
  if (value < lower || value > upper)
    entry.fail("lower", "the starting value " + formatNumber(value) + " lies outside [lower, upper]");
}

}  // namespace

DesignDescription readDesign(const MapReader& design, const Model& model) {
  const YamlContext& context = design.context();
  design.allowKeys({"variables", "cost", "artificial", "constraints", "transcription", "load_cases"});
  DesignDescription out;
  const std::vector<std::string> parameters = model.parameterNames();
  for (const YamlNode& node : readList(context, design.required("variables"), "design.variables")) {
    const MapReader v(context, node, "design variable");
    v.allowKeys({"parameter", "lower", "upper", "scale"});
    const YamlNode& name = v.required("parameter");
    const std::string parameter = name.isScalar() ? name.text() : "";
    if (std::find(parameters.begin(), parameters.end(), parameter) == parameters.end())
      v.fail("parameter", "parameter " + quoted(parameter) + " is not a model parameter" +
                              suggestion(parameter, parameters) + " ('mbsopt parameters' lists them)");
    DesignVariable variable = designVariable(model, parameter, 0.0, 0.0, 1.0);
    readRange(v, model.value(variable.index), variable.lower, variable.upper, variable.scale);
    out.variables.push_back(std::move(variable));
  }
  if (out.variables.empty()) design.fail("variables", "a design problem needs at least one variable");

  const MapReader cost(context, design.required("cost"), "design.cost");
  cost.allowKeys({"sensor", "of"});
  out.cost = {readSensor(cost, model), readMeasure(cost, {"max_abs", "max", "integral", "rms"})};

  const MapReader artificial(context, design.required("artificial"), "design.artificial");
  artificial.allowKeys({"initial", "lower", "upper", "scale"});
  out.artificial.initial = artificial.number("initial");
  readRange(artificial, out.artificial.initial, out.artificial.lower, out.artificial.upper, out.artificial.scale);

  for (const YamlNode& node : readList(context, design.node()["constraints"], "design.constraints")) {
    const MapReader c(context, node, "design constraint");
    c.allowKeys({"sensor", "of", "bound", "equals", "tolerance"});
    ResponseConstraint constraint;
    constraint.sensor = readSensor(c, model);
    constraint.of = readMeasure(c, {"max_abs", "max", "min", "integral", "final", "rms"});
    constraint.equality = c.has("equals");
    if (constraint.equality && c.has("bound")) c.fail("equals", "a constraint has a bound or 'equals', not both");
    if (!constraint.equality && !c.has("bound")) c.fail("sensor", "a constraint needs a bound (or 'equals')");
    if (constraint.equality && constraint.of != ResponseMeasure::Integral && constraint.of != ResponseMeasure::FinalValue)
      c.fail("equals", "an equality needs an exact functional: of: integral or of: final");
    const std::string bound_key = constraint.equality ? "equals" : "bound";
    constraint.bound = c.number(bound_key);
    if (c.has("tolerance")) constraint.tolerance = c.positive("tolerance");
    // `deg` converts to rad: only where the sensor measures an angle (in rad, a relative angle or a
    // revolute joint's position; `of: integral` of one is in rad·s).
    const Sensor& sensor = model.sensors()[static_cast<std::size_t>(model.sensor(constraint.sensor))];
    for (const std::string& key : {bound_key, std::string("tolerance")})
      if (c.inDegrees(key) && !measuresAngle(model, sensor))
        c.fail(key, key + " in deg on sensor '" + constraint.sensor + "', which measures " + sensorSiUnit(model, sensor) +
                        ": deg is for angles (a relative angle, a revolute joint's position)");
    out.constraints.push_back(constraint);
  }

  for (const YamlNode& node : readList(context, design.node()["load_cases"], "design.load_cases")) {
    const MapReader c(context, node, "design load case");
    c.allowKeys({"name", "set"});
    LoadCaseDescription load_case{c.name("name"), {}};
    for (const LoadCaseDescription& other : out.load_cases)
      if (other.name == load_case.name) c.fail("name", "a load case named '" + load_case.name + "' comes earlier");
    if (c.has("set")) {
      const YamlNode& set = c.required("set");
      if (!set.isMap()) c.fail("set", "'set' is a map of the scene's numbers by their dotted names");
      const MapReader values(context, set, "load case '" + load_case.name + "'.set");
      for (std::size_t i = 0; i < set.size(); ++i) {
        const std::string& name = set.key(i).text();
        if (name.rfind("design.", 0) == 0)
          values.fail(name, "a load case sets the scene's numbers, not the design's ('" + name + "')");
        for (const DesignVariable& v : out.variables)
          if (v.parameter == name)
            values.fail(name, "'" + name + "' is a design variable: every load case takes the design's value");
        load_case.set.emplace_back(name, values.number(name));
      }
    }
    out.load_cases.push_back(std::move(load_case));
  }

  if (design.has("transcription")) {
    const MapReader t(context, design.node()["transcription"], "design.transcription");
    t.allowKeys({"measure", "tolerance", "rho", "windows"});
    out.transcription.measure = formulation(t.choice("measure", formulationNames(), "grid_max")).measure;
    out.transcription.tolerance = t.nonNegative("tolerance", 0.0);
    if (t.has("rho")) out.transcription.rho = t.positive("rho");
    out.transcription.windows = t.positiveInteger("windows", 1);
  }
  return out;
}

void checkDesignAgainstScene(const MapReader& design, const DesignDescription& described, const Scene& scene) {
  std::vector<MapReader> entries{MapReader(design.context(), design.required("cost"), "design.cost")};
  for (const YamlNode& node : readList(design.context(), design.node()["constraints"], "design.constraints"))
    entries.emplace_back(design.context(), node, "design constraint");
  for (const MapReader& entry : entries) {
    const Sensor& sensor = scene.model.sensors()[static_cast<std::size_t>(scene.model.sensor(entry.name("sensor")))];
    if (const std::string defect = reactionDeterminacyDefect(scene, sensor); !defect.empty()) entry.fail("sensor", defect);
  }
  const int windows = described.transcription.windows;
  if (windows == 1) return;
  const MapReader t(design.context(), design.node()["transcription"], "design.transcription");
  const NewmarkSettings& s = scene.settings;
  const long steps = stepsToCover(s.end_time, s.step);  // as the integrator takes them
  if (2 * windows > steps + 1)
    t.fail("windows", std::to_string(windows) + " windows of the run's " + std::to_string(steps + 1) +
                          " time points leave some window fewer than two");
}

}  // namespace mbsopt
