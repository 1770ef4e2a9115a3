#include "mbsopt/io/scene_file.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>

#include "mbsopt/algorithms/assembly.hpp"
#include "mbsopt/integrators/adaptive_newmark.hpp"
#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/io/design_file.hpp"
#include "mbsopt/io/element_type.hpp"
#include "mbsopt/io/model_file.hpp"
#include "mbsopt/io/scene_parameters.hpp"
#include "mbsopt/io/scene_text.hpp"
#include "mbsopt/io/yaml_reader.hpp"

namespace mbsopt {

namespace {

std::string location(const std::string& path, int line, int column) {
  std::string text = path;
  if (line > 0) text += ':' + std::to_string(line);
  if (line > 0 && column > 0) text += ':' + std::to_string(column);
  return text;
}

/// "bob: mass must be positive" from the model builder → "mass must be positive".
std::string withoutOwner(const std::string& message, const std::string& owner) {
  const std::string prefix = owner + ": ";
  return message.starts_with(prefix) ? message.substr(prefix.size()) : message;
}

TimeFunction readTimeFunction(const YamlContext& context, const YamlNode& node, const std::string& what) {
  if (node.isScalar()) return TimeFunction::constant(readNumber(context, node, what));
  const MapReader map(context, node, what);
  map.allowKeys({"polynomial", "harmonics"});
  std::vector<double> coefficients;
  for (const YamlNode& c : readList(context, map.node()["polynomial"], what + ".polynomial"))
    coefficients.push_back(readNumber(context, c, what + ".polynomial"));
  std::vector<TimeFunction::Harmonic> harmonics;
  for (const YamlNode& h : readList(context, map.node()["harmonics"], what + ".harmonics")) {
    const MapReader harmonic(context, h, what + " harmonic");
    harmonic.allowKeys({"amplitude", "angular_frequency", "phase"});
    harmonics.push_back({harmonic.number("amplitude"), harmonic.number("angular_frequency"),
                         harmonic.number("phase", 0.0)});
  }
  return {std::move(coefficients), std::move(harmonics)};
}

/// Builds the model of a parsed scene file section by section (problems/scenes/README.md).
class SceneBuilder {
 public:
  SceneBuilder(const YamlContext& context, const YamlNode& root, std::vector<ParameterOverride> model_file_overrides = {})
      : context_(context), root_(context, root, "scene"), model_file_overrides_(std::move(model_file_overrides)) {
    root_.allowKeys({"settings", "model", "gravity", "tracks", "elements", "bodies", "forces", "cuts", "sensors", "design"});
    if (!root_.has("model")) {  // a model file brings its own elements and bodies
      root_.required("elements");
      root_.required("bodies");
    }
  }

  LoadedScene build() {
    readSettings();
    readModelFile();
    if (root_.has("gravity")) model().setGravity(root_.vector("gravity"));
    readTracks();
    readElements();
    for (const YamlNode& node : list("bodies")) readBody(node);
    for (const YamlNode& node : list("cuts")) readCut(node);
    for (const YamlNode& node : list("forces")) readEntry(node, forceTypes(), "force");
    for (const YamlNode& node : list("sensors")) readEntry(node, sensorTypes(), "sensor");
    checkTrajectorySize();
    if (root_.has("design")) result_.design = readDesign(MapReader(context_, root_.node()["design"], "design"), model());
    recordLocations();
    assembleInitialState();
    if (result_.design)
      checkDesignAgainstScene(MapReader(context_, root_.node()["design"], "design"), *result_.design, result_.scene);
    checkFirstEvaluation();
    return std::move(result_);
  }

 private:
  struct InitialValue {
    std::string coordinate;
    double q0, v0;
  };
  struct PendingElement {
    MapReader entry;
    std::string name, type, parent;
    enum class State { Waiting, Placing, Placed } state = State::Waiting;
  };

  Model& model() { return result_.scene.model; }

  std::vector<std::reference_wrapper<const YamlNode>> list(const std::string& section) const {
    auto entries = readList(context_, root_.node()[section], section);
    if (entries.size() > kSceneLimits.entries_per_section)
      context_.fail(entries[kSceneLimits.entries_per_section].get(),
                    section + ": more than " + std::to_string(kSceneLimits.entries_per_section) +
                        " entries, the limit of a section");
    return entries;
  }

  /// The model's size against kSceneLimits, at the entry (element or cut) that exceeds it.
  void checkModelSize(const MapReader& entry) const {
    const Model& m = result_.scene.model;
    if (m.coordinateCount() > kSceneLimits.coordinates)
      context_.fail(entry.node(), entry.what() + ": the model has more than " +
                                      std::to_string(kSceneLimits.coordinates) + " joint coordinates, the limit");
    if (m.constraintCount() > kSceneLimits.closure_equations)
      context_.fail(entry.node(), entry.what() + ": the model has more than " +
                                      std::to_string(kSceneLimits.closure_equations) +
                                      " loop-closure equations, the limit");
  }

  /// An entry of a named section: a map with a unique `name` and a `type` among `types`.
  MapReader entry(const YamlNode& node, const std::string& kind, std::string& name) {
    const MapReader map(context_, node, kind);
    name = map.name("name");
    if (name == "ground") map.fail("name", "'ground' is the name of the fixed frame");
    if (name == "t") map.fail("name", "'t' is the time column of the CSV output");
    if (const auto used = names_.find(name); used != names_.end())
      map.fail("name", "the name '" + name + "' is already used at line " + std::to_string(used->second.line + 1));
    names_.emplace(name, map.node()["name"].mark());
    return MapReader(context_, node, kind + " '" + name + "'");
  }

  /// A name an entry adds to the model beside its own (ElementEntry::claimName): unique among the
  /// file's names, and located at the entry's name.
  void claimName(const MapReader& entry, const std::string& added) { claimName(entry, "name", added); }
  void claimName(const MapReader& entry, const std::string& key, const std::string& added) {
    if (const auto used = names_.find(added); used != names_.end())
      entry.fail(key, "it adds '" + added + "', a name already used at line " + std::to_string(used->second.line + 1));
    names_.emplace(added, entry.markOf(key));
  }

  /// Runs a model-builder call; its std::invalid_argument becomes an error at `entry`.
  template <class Call>
  void guarded(const MapReader& entry, const std::string& name, Call&& call) {
    try {
      call();
    } catch (const std::invalid_argument& e) {
      context_.fail(entry.node(), entry.what() + ": " + withoutOwner(e.what(), name));
    }
  }

  /// Where the file declares each named entry, for errors found later (LoadedScene::locations).
  void recordLocations() {
    for (const auto& [name, mark] : names_) result_.locations[name] = {mark.line + 1, mark.column + 1};
  }

  FrameIndex frame(const MapReader& entry, const std::string& key) {
    const std::string name = entry.name(key);
    std::vector<std::string> names;
    for (const Frame& f : model().frames()) {
      if (f.name == name) return static_cast<FrameIndex>(names.size());
      names.push_back(f.name);
    }
    entry.fail(key, key + ": frame '" + name + "' does not exist" + suggestion(name, names) +
                        " (frames are 'ground' and the elements)");
  }

  std::string joint(const MapReader& entry, const std::string& key) {
    const std::string name = entry.name(key);
    std::vector<std::string> names;
    for (const Coordinate& c : model().coordinates()) {
      if (c.name == name) return name;
      names.push_back(c.name);
    }
    for (const Frame& f : model().frames())
      if (f.name == name)
        entry.fail(key, key + ": '" + name + "' is " + (f.element < 0 ? "the ground" : "an offset") +
                            ", not a joint: it has no coordinate");
    entry.fail(key, key + ": joint '" + name + "' does not exist" + suggestion(name, names) +
                        " (joints are revolute, prismatic and curve-slider elements and curve-slider cuts)");
  }

  /// The model index of the cut named under `key` (a curve-slider cut's equations are its "_closure").
  int cut(const MapReader& entry, const std::string& key) {
    const std::string name = entry.name(key);
    std::vector<std::string> names;
    const std::string closure = "_closure";
    for (std::size_t c = 0; c < model().cuts().size(); ++c) {
      const std::string& cut_name = model().cuts()[c].name;
      const bool generated = !names_.contains(cut_name);  // the weld or sphere of a curve-slider cut
      const std::string declared = generated ? cut_name.substr(0, cut_name.size() - closure.size()) : cut_name;
      if (declared == name) return static_cast<int>(c);
      names.push_back(declared);
    }
    entry.fail(key, "cut joint '" + name + "' does not exist" + suggestion(name, names) +
                          (names.empty() ? " (the scene has no cuts)" : ""));
  }

  TrackIndex track(const MapReader& entry, const std::string& key = "track") const {
    const std::string name = entry.name(key);
    const auto found = tracks_.find(name);
    if (found == tracks_.end()) {
      std::vector<std::string> names;
      for (const auto& [track_name, track] : tracks_) names.push_back(track_name);
      entry.fail(key, "track '" + name + "' does not exist" + suggestion(name, names));
    }
    return found->second;
  }

  /// q0 and v0 of a joint; `deg` (deg/s for v0) only on a revolute joint's angle.
  void initialValues(const MapReader& entry, const std::string& coordinate, bool angular) {
    if (!angular)
      for (const char* key : {"q0", "v0"})
        if (entry.inDegrees(key))
          entry.fail(key, std::string(key) + " in deg on a joint that translates (its coordinate is in m): deg is for "
                                             "a revolute joint's angle");
    initial_.push_back({coordinate, entry.number("q0", 0.0), entry.number("v0", 0.0)});
  }

  /// The stored trajectory must fit kMaxTrajectoryBytes (problems/scenes/README.md, "Limits").
  void checkTrajectorySize() {
    const NewmarkSettings& s = result_.scene.settings;
    const double bytes = trajectoryBytes(model(), s);
    if (bytes <= kMaxTrajectoryBytes) return;
    const YamlNode& settings = root_.node()["settings"];
    const std::string what = "a run of " + formatNumber(static_cast<double>(stepsToCover(s.end_time, s.step))) + " steps of this model stores " +
                             formatNumber(std::round(bytes / (1 << 20))) +
                             " MiB of trajectory, more than the limit of 4 GiB: shorten end_time or enlarge step";
    if (settings["end_time"].isDefined()) context_.fail(settings["end_time"], "settings: end_time: " + what);
    context_.fail(settings.isDefined() ? settings : root_.node(), "settings: " + what);
  }

  /// `integrator` (a name of the registry), `extrapolation_runs` (2 … 8) and `local_tolerance`.
  void readIntegrator(const MapReader& settings) {
    IntegratorChoice& choice = result_.scene.integrator;
    if (settings.has("integrator")) {
      choice.name = settings.name("integrator");
      try {
        integratorInfo(choice.name);
      } catch (const std::invalid_argument& e) {
        settings.fail("integrator", std::string("integrator: ") + e.what());
      }
    }
    choice.extrapolation_runs = settings.positiveInteger("extrapolation_runs", choice.extrapolation_runs);
    if (choice.extrapolation_runs < 2 || choice.extrapolation_runs > kMaxExtrapolationRuns)
      settings.fail("extrapolation_runs", "extrapolation_runs: " + std::to_string(choice.extrapolation_runs) +
                                              " runs; between 2 and " + std::to_string(kMaxExtrapolationRuns));
    choice.local_tolerance = settings.number("local_tolerance", choice.local_tolerance);
    if (!(choice.local_tolerance > 0.0 && std::isfinite(choice.local_tolerance)))
      settings.fail("local_tolerance", "local_tolerance: must be positive and finite");
    if (choice.extrapolated() || choice.adaptive())
      if (const std::string defect = extrapolationDefect(
              result_.scene.settings, choice.adaptive() ? "the adaptive integrator's error estimate" : "extrapolation");
          !defect.empty())
        settings.fail("integrator", "integrator: " + defect);
  }

  void readSettings() {
    NewmarkSettings& s = result_.scene.settings;
    if (!root_.has("settings")) return;
    const MapReader settings(context_, root_.node()["settings"], "settings");
    settings.allowKeys({"step", "end_time", "beta", "gamma", "newton_tolerance", "max_newton_iterations",
                        "svd_threshold", "closure", "closure_tolerance", "energy_tolerance", "integrator",
                        "extrapolation_runs", "local_tolerance"});
    s.step = settings.number("step", s.step);
    s.end_time = settings.number("end_time", s.end_time);
    s.beta = settings.number("beta", s.beta);
    s.gamma = settings.number("gamma", s.gamma);
    s.newton_tolerance = settings.number("newton_tolerance", s.newton_tolerance);
    s.max_newton_iterations = settings.positiveInteger("max_newton_iterations", s.max_newton_iterations);
    s.svd_threshold = settings.number("svd_threshold", s.svd_threshold);
    s.closure_tolerance = settings.number("closure_tolerance", s.closure_tolerance);
    s.energy_tolerance = settings.number("energy_tolerance", s.energy_tolerance);
    s.closure = settings.choice("closure", {"position", "acceleration"}, "position") == "acceleration"
                    ? ClosureLevel::Acceleration
                    : ClosureLevel::Position;
    if (const SettingsDefect defect = settingsDefect(s); !defect.field.empty())
      settings.fail(settings.has(defect.field) ? defect.field : "step", defect.field + ": " + defect.message);
    readIntegrator(settings);
    // The Newmark family is unconditionally stable for linear problems iff 2β ≥ γ ≥ ½ (Hughes, The
    // Finite Element Method, 2000, §9.1.2); outside, a small enough step is needed.
    if (!(s.gamma >= 0.5 && 2.0 * s.beta >= s.gamma))
      result_.warnings.push_back(location(context_.path(), settings.markOf("gamma").line + 1, 0) +
                                 ": warning: beta = " + formatNumber(s.beta) + ", gamma = " + formatNumber(s.gamma) +
                                 " are not unconditionally stable (that needs 2 beta >= gamma >= 1/2)");
  }

  /// `model: {file, ignore}`: the mechanism of an MJCF or URDF file (model_file.hpp), its path relative
  /// to the scene file's folder; its names are the file's and are located at `model`.
  void readModelFile() {
    if (!root_.has("model")) return;
    const MapReader entry(context_, root_.node()["model"], "model");
    entry.allowKeys({"file", "ignore", "q0", "v0"});
    const YamlNode& file = entry.required("file");
    if (!file.isScalar() || file.text().empty()) entry.fail("file", "file: expected the path of an MJCF (.xml) or URDF (.urdf) file");
    std::vector<std::string> ignore;  // a list, or one word of names and commas (`--set model.ignore=a,b`)
    const YamlNode& ignored = entry.node()["ignore"];
    if (ignored.isScalar()) {
      std::istringstream words(ignored.text());
      for (std::string word; std::getline(words, word, ',');)
        if (!word.empty()) ignore.push_back(word);
    } else {
      for (const YamlNode& feature : readList(context_, ignored, "model.ignore")) {
        if (!feature.isScalar()) context_.fail(feature, "model.ignore: expected a feature's name");
        ignore.push_back(feature.text());
      }
    }
    const std::filesystem::path folder = std::filesystem::path(context_.path()).parent_path();
    const std::filesystem::path path = std::filesystem::path(file.text()).is_absolute() ? std::filesystem::path(file.text())
                                                                                        : folder / file.text();
    if (!std::filesystem::exists(path)) entry.fail("file", "file: no such file " + quoted(path.string()));
    ModelFileContents contents;
    try {
      contents = addModelFile(model(), path.string(), ignore);
    } catch (const SceneError& e) {
      if (!e.reason().starts_with("ignore:")) throw;  // the model file's error, at its line where it has one
      entry.fail("ignore", e.reason());
    }
    for (const std::string& name : contents.names) claimName(entry, "file", name);
    for (const ModelFileContents::Start& s : contents.starts) initial_.push_back({s.coordinate, s.q0, s.v0});
    readModelFileStarts(entry);
    applyModelFileOverrides(contents);
    for (const Frame& f : model().frames()) model_file_frames_.insert(f.name);
    for (const std::string& left_out : contents.left_out)
      result_.warnings.push_back(context_.path() + ": warning: left out of " +
                                 path.filename().string() + ": " + left_out);
    result_.left_out = contents.left_out;
  }

  /// `model: {q0: {JOINT: value}, v0: {…}}`: starts of the file's joints other than the file's, in SI
  /// units (rad or m, rad/s or m/s), from the joint's reference.
  void readModelFileStarts(const MapReader& entry) {
    for (const char* key : {"q0", "v0"}) {
      if (!entry.has(key)) continue;
      const YamlNode& starts = entry.node()[key];
      if (!starts.isMap()) entry.fail(key, std::string(key) + ": expected a map of joint names to numbers");
      const MapReader map(context_, starts, std::string("model.") + key);
      for (std::size_t i = 0; i < starts.size(); ++i) {
        const std::string joint = starts.key(i).text();
        const auto start = std::find_if(initial_.begin(), initial_.end(), [&](const InitialValue& v) { return v.coordinate == joint; });
        if (start == initial_.end()) {
          std::vector<std::string> names;
          for (const InitialValue& v : initial_) names.push_back(v.coordinate);
          map.fail(joint, "model." + std::string(key) + ": the model file has no joint coordinate '" + joint + "'" +
                              suggestion(joint, names));
        }
        (std::string(key) == "q0" ? start->q0 : start->v0) = map.number(joint);
      }
    }
  }

  /// `--set` of a model file's numbers: its parameters (MODEL.mass, J_spring.c, …) and its joints'
  /// starts (J.q0, J.v0, in SI units).
  void applyModelFileOverrides(const ModelFileContents& contents) {
    std::vector<std::string> names = model().parameterNames();
    for (const ModelFileContents::Start& s : contents.starts)
      for (const char* key : {".q0", ".v0"}) names.push_back(s.coordinate + key);
    for (const ParameterOverride& o : model_file_overrides_) {
      const auto start = std::find_if(initial_.begin(), initial_.end(), [&](const InitialValue& v) {
        return o.name == v.coordinate + ".q0" || o.name == v.coordinate + ".v0";
      });
      if (start != initial_.end()) {
        (o.name.ends_with(".q0") ? start->q0 : start->v0) = o.value;
        continue;
      }
      if (std::find(names.begin(), names.end(), o.name) == names.end()) throw unknownOverride(context_, o, names);
      try {
        model().setParameter(o.name, o.value);
      } catch (const std::invalid_argument& e) {
        throw SceneError(context_.path(), 0, 0, describe(o) + ": " + e.what());
      }
    }
  }

  void readTracks() {
    for (const YamlNode& node : list("tracks")) {
      std::string name;
      const MapReader t = entry(node, "track", name);
      t.allowKeys({"name", "origin", "heading", "segments"});
      Track track(t.vector("origin", Eigen::Vector3d::Zero()), t.number("heading", 0.0));
      const auto segments = readList(context_, t.required("segments"), t.what() + ".segments");
      if (segments.empty()) t.fail("segments", "a track needs at least one segment");
      for (const YamlNode& s : segments) {
        const MapReader segment(context_, s, t.what() + " segment");
        const std::string type = segment.choice("type", {"straight", "arc", "clothoid"});
        if (type == "straight") {
          segment.allowKeys({"type", "length"});
          track.straight(segment.positive("length"));
        } else if (type == "arc") {
          segment.allowKeys({"type", "radius", "angle"});
          const double radius = segment.positive("radius");
          const double angle = segment.number("angle");
          if (angle == 0.0) segment.fail("angle", "an arc must turn (angle ≠ 0)");
          track.arc(radius, angle);
        } else {
          segment.allowKeys({"type", "length", "end_curvature"});
          const double length = segment.positive("length");
          track.clothoid(length, segment.number("end_curvature"));
        }
      }
      guarded(t, name, [&] { tracks_.emplace(name, model().addTrack(name, track)); });
    }
  }

  void readElements() {
    std::vector<PendingElement> pending;
    std::map<std::string, std::size_t> index;
    for (const YamlNode& node : list("elements")) {
      std::string name;
      MapReader e = entry(node, "element", name);
      const std::string type = e.choice("type", entryTypeNames(elementTypes()));
      std::vector<std::string> keys{"name", "type", "parent"};
      for (const std::string& key : entryType(elementTypes(), type, "element").keys) keys.push_back(key);
      e.allowKeys(keys);
      const std::string parent = e.name("parent");
      index.emplace(name, pending.size());
      pending.push_back({std::move(e), name, type, parent});
    }
    // From each element up to the ground or a placed ancestor, then placed downwards: parents
    // first, file order otherwise. A loop, not a recursion: a chain as long as the file allows
    // must not exhaust the stack.
    for (std::size_t start = 0; start < pending.size(); ++start) {
      std::vector<std::size_t> chain;  // start, its parent, ... (unplaced)
      for (std::size_t i = start; pending[i].state != PendingElement::State::Placed;) {
        PendingElement& p = pending[i];
        if (p.state == PendingElement::State::Placing) {
          std::string cycle;
          for (auto it = std::find(chain.begin(), chain.end(), i); it != chain.end(); ++it)
            cycle += pending[*it].name + " → ";
          p.entry.fail("parent", "the elements " + cycle + p.name + " form a cycle: every chain must start at the ground");
        }
        p.state = PendingElement::State::Placing;
        chain.push_back(i);
        if (p.parent == "ground" || model_file_frames_.contains(p.parent)) break;
        const auto parent = index.find(p.parent);
        if (parent == index.end()) {
          std::vector<std::string> names{"ground"};
          for (const PendingElement& other : pending) names.push_back(other.name);
          p.entry.fail("parent", "parent '" + p.parent + "' does not exist" + suggestion(p.parent, names) +
                                     " (it must be 'ground' or an element)");
        }
        i = parent->second;
      }
      for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
        PendingElement& p = pending[*it];
        addElement(p.entry, p.name, p.type, p.parent);
        checkModelSize(p.entry);
        p.state = PendingElement::State::Placed;
      }
    }
  }

  /// One entry of a named section as its type's reader sees it (entry_type.hpp); `Interface` is
  /// SectionEntry, or ElementEntry for the elements.
  template <class Interface>
  class EntryOf : public Interface {
   public:
    EntryOf(SceneBuilder& builder, const MapReader& map, const std::string& name)
        : builder_(builder), map_(map), name_(name) {}
    const MapReader& map() const override { return map_; }
    const std::string& name() const override { return name_; }
    Model& model() override { return builder_.model(); }
    FrameIndex frame(const std::string& key) const override { return builder_.frame(map_, key); }
    std::string joint(const std::string& key) const override { return builder_.joint(map_, key); }
    int cut(const std::string& key) const override { return builder_.cut(map_, key); }
    TrackIndex track(const std::string& key) const override { return builder_.track(map_, key); }
    TimeFunction timeFunction(const std::string& key) const override {
      return readTimeFunction(builder_.context_, map_.node()[key], map_.what() + "." + key);
    }
    void guarded(const std::function<void()>& call) const override { builder_.guarded(map_, name_, call); }
    void initialValues(const std::string& coordinate, bool angular) override {
      builder_.initialValues(map_, coordinate, angular);
    }

   protected:
    SceneBuilder& builder_;
    const MapReader& map_;
    const std::string& name_;
  };

  class ElementEntryOf final : public EntryOf<ElementEntry> {
   public:
    ElementEntryOf(SceneBuilder& builder, const MapReader& map, const std::string& name, FrameIndex parent)
        : EntryOf(builder, map, name), parent_(parent) {}
    using EntryOf::initialValues;
    FrameIndex parent() const override { return parent_; }
    void motionOrInitialValues(const std::string& coordinate, bool angular) override {
      if (!map_.has("motion")) {
        initialValues(coordinate, angular);
        return;
      }
      for (const char* key : {"q0", "v0"})
        if (map_.has(key))
          map_.fail(key, std::string(key) + " conflicts with 'motion': a driven joint starts where its motion says");
      const TimeFunction motion = timeFunction("motion");
      guarded([&] { model().drive(coordinate, motion); });
    }
    void initialValues(const std::string& coordinate, double q0, double v0) override {
      builder_.initial_.push_back({coordinate, q0, v0});
    }
    void claimName(const std::string& added) override { builder_.claimName(map_, added); }

   private:
    FrameIndex parent_;
  };

  void addElement(const MapReader& e, const std::string& name, const std::string& type,
                  const std::string& parent_name) {
    ElementEntryOf entry(*this, e, name, parent_name == "ground" ? Model::ground : model().frame(parent_name));
    entryType(elementTypes(), type, "element").add(entry);
  }

  void readBody(const YamlNode& node) {
    std::string name;
    const MapReader b = entry(node, "body", name);
    b.allowKeys({"name", "frame", "mass", "com", "Ixx", "Iyy", "Izz", "Ixy", "Ixz", "Iyz"});
    const FrameIndex f = frame(b, "frame");
    const double mass = b.positive("mass");
    const Eigen::Vector3d com = b.vector("com", Eigen::Vector3d::Zero());
    Eigen::Matrix3d inertia;
    inertia(0, 0) = b.number("Ixx");
    inertia(1, 1) = b.number("Iyy");
    inertia(2, 2) = b.number("Izz");
    inertia(0, 1) = inertia(1, 0) = b.number("Ixy", 0.0);
    inertia(0, 2) = inertia(2, 0) = b.number("Ixz", 0.0);
    inertia(1, 2) = inertia(2, 1) = b.number("Iyz", 0.0);
    guarded(b, name, [&] { model().addBody(name, f, mass, com, inertia); });
  }

  /// An entry of `cuts:`, `forces:` or `sensors:` (`kind`: "cut", "force", "sensor"), read by its
  /// registered type (entry_type.hpp); `added` sees the entry once its type has added it.
  void readEntry(const YamlNode& node, const std::vector<SectionEntryType>& types, const std::string& kind,
                 const std::function<void(const MapReader&)>& added = {}) {
    std::string name;
    const MapReader map = entry(node, kind, name);
    const SectionEntryType& type = entryType(types, map.choice("type", entryTypeNames(types)), kind);
    std::vector<std::string> keys{"name", "type"};
    keys.insert(keys.end(), type.keys.begin(), type.keys.end());
    map.allowKeys(keys);
    EntryOf<SectionEntry> reader(*this, map, name);
    type.add(reader);
    if (added) added(map);
  }

  /// A cut's closure equations are located at its entry, and they count towards the model's size.
  void readCut(const YamlNode& node) {
    readEntry(node, cutTypes(), "cut", [&](const MapReader& map) {
      cut_marks_.resize(model().cuts().size(), map.node().mark());
      checkModelSize(map);
    });
  }

  /// q₀ and q̇₀ from the joints' q0 and v0, moved onto the loop closure when they miss it.
  void assembleInitialState() {
    Scene& scene = result_.scene;
    const Eigen::Index n = model().coordinateCount();
    scene.q0 = Eigen::VectorXd::Zero(n);
    scene.v0 = Eigen::VectorXd::Zero(n);
    for (const InitialValue& value : initial_) {
      const int i = model().coordinate(value.coordinate);
      scene.q0[i] = value.q0;
      scene.v0[i] = value.v0;
    }
    const Eigen::VectorXd q_given = scene.q0, v_given = scene.v0;
    try {
      assemble(model(), scene.q0, scene.v0, 0.0, 1e-12, scene.settings.svd_threshold);
    } catch (const AssemblyError& e) {
      if (e.openCuts().empty() || cut_marks_.empty()) throw SceneError(context_.path(), 0, 0, e.what());
      const auto cut = static_cast<std::size_t>(e.openCuts().front());
      context_.fail(cut_marks_.at(cut), "cut '" + model().cuts()[cut].name + "': " + e.what());
    } catch (const std::exception& e) {  // a flipped weld, a non-finite driver at t = 0
      throw SceneError(context_.path(), 0, 0, std::string("the initial state: ") + e.what());
    }
    warnIfMoved(scene.q0 - q_given, "coordinates", "m or rad");
    warnIfMoved(scene.v0 - v_given, "rates", "m/s or rad/s");
  }

  /// Computes the initial accelerations, so that a scene whose dynamics are undefined from the start
  /// (a joint with nothing to move, a point spring of zero length) is an error at its entry.
  void checkFirstEvaluation() {
    const Scene& scene = result_.scene;
    try {
      NewmarkIntegrator(scene.model, scene.settings).initialize(scene.q0, scene.v0, 0.0);
    } catch (const SimulationError& e) {
      const auto entry = names_.find(e.element);
      if (entry == names_.end()) throw SceneError(context_.path(), 0, 0, "at t = 0: " + e.reason);
      context_.fail(entry->second, "at t = 0: " + e.reason);
    } catch (const std::exception& e) {
      throw SceneError(context_.path(), 0, 0, std::string("at t = 0: ") + e.what());
    }
  }

  void warnIfMoved(const Eigen::VectorXd& change, const std::string& what, const std::string& unit) {
    Eigen::VectorXd free_change = change;
    for (const int d : model().drivenCoordinates()) free_change[d] = 0.0;  // a driver sets them exactly
    if (free_change.size() == 0) return;
    Eigen::Index worst = 0;
    const double largest = free_change.cwiseAbs().maxCoeff(&worst);
    if (!(largest > 1e-10)) return;
    result_.warnings.push_back(context_.path() + ": warning: the initial " + what +
                               " do not close the loops; moved them onto the closure by up to " +
                               formatNumber(largest) + " " + unit + ", at '" +
                               model().coordinates()[static_cast<std::size_t>(worst)].name + "'");
  }

  const YamlContext& context_;
  MapReader root_;
  LoadedScene result_;
  std::map<std::string, YamlMark> names_;
  std::map<std::string, TrackIndex> tracks_;
  std::vector<InitialValue> initial_;
  std::vector<YamlMark> cut_marks_;  ///< per cut of the model: where the file declares it
  std::set<std::string> model_file_frames_;  ///< the frames a model file added (elements may start there)
  std::vector<ParameterOverride> model_file_overrides_;  ///< of the model file's numbers (applyOverrides)
};

/// The 1-based number of the last line of `text` that holds something, at least 1.
int lastContentLine(const std::string& text) {
  int line = 1, last = 1;
  for (char c : text) {
    if (c == '\n') ++line;
    else if (!std::isspace(static_cast<unsigned char>(c))) last = line;
  }
  return last;
}

/// Line `number` (1-based) of `text`.
std::string lineOf(const std::string& text, int number) {
  std::istringstream in(text);
  std::string line;
  for (int i = 0; i < number && std::getline(in, line); ++i) {
  }
  return line;
}

YamlNode parse(const SceneSource& source) {
  YamlNode root;
  try {
    root = parseYamlDocument(source.text);
  } catch (const YamlSyntaxError& e) {
    if (e.mark().isNull()) throw SceneError(source.path, 0, 0, e.what());
    // An unclosed bracket is found at the end of the input: name the last line instead.
    const int line = std::min(e.mark().line + 1, lastContentLine(source.text));
    const int column = line == e.mark().line + 1 ? e.mark().column + 1 : 1;
    std::string hint;
    const YamlMark& opened = e.contextMark();
    if (!e.context().empty())
      hint = " (" + e.context() +
             (opened.line == e.mark().line && opened.column == e.mark().column
                  ? ""
                  : " at line " + std::to_string(opened.line + 1) + ", column " + std::to_string(opened.column + 1)) +
             ")";
    for (int l : {line, line - 1})
      if (l > 0 && lineOf(source.text, l).find('\t') != std::string::npos) {
        hint += " (line " + std::to_string(l) + " has a tab: YAML indents with spaces only)";
        break;
      }
    throw SceneError(source.path, line, column, e.what() + hint);
  }
  if (!root.isDefined() || root.isNull()) throw SceneError(source.path, 0, 0, "the scene is empty");
  return root;
}

}  // namespace

SceneError::SceneError(const std::string& path, int line, int column, const std::string& what)
    : std::runtime_error(location(path, line, column) + ": error: " + what),
      path_(path),
      reason_(what),
      line_(line),
      column_(column) {}

SceneSource readSceneFile(const std::string& path) {
  if (std::filesystem::is_directory(path)) throw SceneError(path, 0, 0, "is a directory, not a scene file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path, 0, 0, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw SceneError(path, 0, 0, "cannot read the scene file");
  if (text.str().find('\0') != std::string::npos)
    throw SceneError(path, 0, 0, "the file holds NUL bytes: it is not a text (YAML) file");
  return {path, text.str()};
}

LoadedScene loadScene(const SceneSource& source, const std::vector<ParameterOverride>& overrides) {
  YamlContext context(source.path);
  YamlNode root = parse(source);
  std::vector<ParameterOverride> model_file_overrides = applyOverrides(context, root, overrides);
  return SceneBuilder(context, root, std::move(model_file_overrides)).build();
}

namespace {

/// A scene run by the adaptive integrator, as a design problem: on the steps it takes at the initial
/// design, frozen, so that the values are smooth in the design and the exact gradients those of the steps.
void freezeAdaptiveSteps(const SceneSource& source, Scene& scene) {
  if (!scene.integrator.adaptive()) return;
  LocalErrorControl control;
  control.tolerance = {scene.integrator.local_tolerance, 0.0};
  try {
    const AdaptiveRun run = adaptiveNewmarkRun(scene.model, scene.settings, scene.q0, scene.v0, control);
    scene.settings.time_grid = timeGrid(run.trajectory.time);
  } catch (const SimulationError& e) {
    throw SceneError(source.path, 0, 0, std::string("the adaptive run that chooses the steps failed: ") + e.what());
  }
}

/// Each design variable's bounds are values the scene itself accepts for its parameter (a stiffness's
/// lower bound is not negative): the scene loaded with each bound as its value, an error at the bound
/// where the scene refuses that value. (A loop that cannot be assembled at a bound is not such an
/// error: the design simply cannot go there, which its evaluation says.)
void checkVariableBounds(const SceneSource& source, const std::vector<ParameterOverride>& overrides,
                         const DesignDescription& design) {
  for (std::size_t i = 0; i < design.variables.size(); ++i) {
    const DesignVariable& v = design.variables[i];
    for (const char* side : {"lower", "upper"}) {
      std::vector<ParameterOverride> at_bound = overrides;
      at_bound.emplace_back(v.parameter, side[0] == 'l' ? v.lower : v.upper);
      at_bound.back().origin = "design.variables." + std::to_string(i) + "." + side;
      try {
        loadScene(source, at_bound);
      } catch (const SceneError& e) {
        if (e.reason().find("(value from " + at_bound.back().origin) == std::string::npos) continue;
        const YamlMark mark = parse(source)["design"]["variables"][i][side].mark();
        throw SceneError(source.path, mark.line + 1, mark.column + 1,
                         std::string("design variable ") + quoted(v.parameter) + ": its " + side + " bound " +
                             formatNumber(side[0] == 'l' ? v.lower : v.upper) + " is a value the scene refuses: " +
                             e.reason());
      }
    }
  }
}

}  // namespace

SceneError failureAt(const SceneSource& source, const std::vector<ParameterOverride>& overrides,
                     const std::string& element, const std::string& what) {
  if (!element.empty()) {
    try {
      const LoadedScene loaded = loadScene(source, overrides);
      if (const auto where = loaded.locations.find(element); where != loaded.locations.end())
        return SceneError(source.path, where->second.line, where->second.column, what);
    } catch (const SceneError&) {  // located at the file, then
    }
  }
  return SceneError(source.path, 0, 0, what);
}

DesignProblem loadDesignProblem(const SceneSource& source, const std::vector<ParameterOverride>& overrides) {
  LoadedScene loaded = loadScene(source, overrides);
  if (!loaded.design) throw SceneError(source.path, 0, 0, "the scene has no 'design:' section");
  checkVariableBounds(source, overrides, *loaded.design);
  DesignProblem problem{std::move(loaded.scene), std::move(*loaded.design), {}};
  // Each load case: the scene again with the command line's overrides, then the case's own.
  for (std::size_t c = 0; c < problem.design.load_cases.size(); ++c) {
    const LoadCaseDescription& description = problem.design.load_cases[c];
    std::vector<ParameterOverride> own = overrides;
    for (const auto& [name, value] : description.set) own.emplace_back(name, value);
    try {
      problem.load_cases.push_back({description.name, loadScene(source, own).scene});
      freezeAdaptiveSteps(source, problem.load_cases.back().scene);
    } catch (const SceneError& e) {  // at the case's entry, whose number it is
      const YamlMark mark = parse(source)["design"]["load_cases"][c].mark();
      throw SceneError(source.path, mark.line + 1, mark.column + 1, "load case '" + description.name + "': " + e.reason());
    }
  }
  freezeAdaptiveSteps(source, problem.scene);
  return problem;
}

std::vector<std::pair<std::string, double>> sceneParameters(const SceneSource& source) {
  YamlContext context(source.path);
  const YamlNode root = parse(source);
  std::vector<std::pair<std::string, double>> parameters;
  forEachNumber(root, [&](const std::string& name, const YamlNode& node) {
    parameters.emplace_back(name, readNumber(context, node, name));
  });
  // The defaults the file does not write, which --set can still address.
  const Scene scene = SceneBuilder(context, root).build().scene;
  const NewmarkSettings& s = scene.settings;
  std::vector<std::pair<std::string, double>> defaults{
      {"settings.step", s.step},
      {"settings.end_time", s.end_time},
      {"settings.beta", s.beta},
      {"settings.gamma", s.gamma},
      {"settings.newton_tolerance", s.newton_tolerance},
      {"settings.max_newton_iterations", s.max_newton_iterations},
      {"settings.svd_threshold", s.svd_threshold},
      {"settings.closure_tolerance", s.closure_tolerance},
      {"settings.energy_tolerance", s.energy_tolerance},
      {"settings.extrapolation_runs", scene.integrator.extrapolation_runs},
      {"settings.local_tolerance", scene.integrator.local_tolerance}};
  for (const std::string& name : scene.model.parameterNames()) defaults.emplace_back(name, scene.model.parameter(name));
  const bool from_model_file = root["model"].isDefined();  // which starts where the file places its bodies
  for (const int i : scene.model.freeCoordinates()) {
    const std::string& name = scene.model.coordinates()[static_cast<std::size_t>(i)].name;
    if (scene.model.coordinateOwner(i) != name) continue;  // a coordinate the file does not name
    defaults.emplace_back(name + ".q0", from_model_file ? scene.q0[i] : 0.0);
    defaults.emplace_back(name + ".v0", from_model_file ? scene.v0[i] : 0.0);
  }
  for (const auto& entry : defaults)
    if (std::none_of(parameters.begin(), parameters.end(), [&](const auto& p) { return p.first == entry.first; }))
      parameters.push_back(entry);
  return parameters;
}

}  // namespace mbsopt
