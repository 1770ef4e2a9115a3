// The types of the entries of a scene file's named sections (`elements:`, `cuts:`, `forces:`,
// `sensors:`), one registry per section: each type's name, what it is, the keys its entry takes
// besides name and type, and how it adds itself to the model. A type is one file of the section's
// folder (7-io/elements/, cuts/, forces/, sensors/) and one line of its table (element_type.cpp,
// entry_types.cpp).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/model/time_function.hpp"
#include "mbsopt/io/yaml_reader.hpp"

namespace mbsopt {

/// What a type's reader is given: its entry in the file and the scene being built, with the
/// readings every type shares. Every error is reported at the entry's line in the file.
class SectionEntry {
 public:
  virtual ~SectionEntry() = default;
  /// The entry's map, for its own numbers and for errors at one of its keys (MapReader::fail).
  virtual const MapReader& map() const = 0;
  virtual const std::string& name() const = 0;
  virtual Model& model() = 0;
  /// The frame named under `key`: the ground or an element placed before.
  virtual FrameIndex frame(const std::string& key) const = 0;
  /// The joint coordinate named under `key` (a revolute, prismatic or curve-slider element, or a
  /// curve-slider cut).
  virtual std::string joint(const std::string& key) const = 0;
  /// The model index of the cut joint named under `key`.
  virtual int cut(const std::string& key) const = 0;
  /// The track named under `key` (the scene's `tracks:` section).
  virtual TrackIndex track(const std::string& key) const = 0;
  /// The function of time under `key` (time_function.hpp's forms).
  virtual TimeFunction timeFunction(const std::string& key) const = 0;
  /// Runs a model-builder call; its std::invalid_argument becomes an error at the entry.
  virtual void guarded(const std::function<void()>& call) const = 0;
  /// The start of the joint coordinate `coordinate` from the entry's q0 and v0 (both 0 by default;
  /// in deg only where `angular`).
  virtual void initialValues(const std::string& coordinate, bool angular) = 0;
};

template <class Entry>
struct EntryType {
  std::string name;
  std::string description;        ///< one sentence, for the scene files' documentation and errors
  std::vector<std::string> keys;  ///< the entry's keys besides name and type (and an element's parent)
  std::function<void(Entry&)> add;
};

/// The registered names, in the registry's order.
template <class Entry>
std::vector<std::string> entryTypeNames(const std::vector<EntryType<Entry>>& registry) {
  std::vector<std::string> names;
  for (const EntryType<Entry>& type : registry) names.push_back(type.name);
  return names;
}

/// The registered type `name`; std::invalid_argument naming the section (`what`: "element", "cut",
/// "force", "sensor") and listing the names otherwise.
template <class Entry>
const EntryType<Entry>& entryType(const std::vector<EntryType<Entry>>& registry, const std::string& name,
                                  const std::string& what) {
  for (const EntryType<Entry>& type : registry)
    if (type.name == name) return type;
  std::string known;
  for (const std::string& type_name : entryTypeNames(registry)) known += (known.empty() ? "" : ", ") + type_name;
  throw std::invalid_argument("unknown " + what + " type '" + name + "' (known: " + known + ")");
}

using SectionEntryType = EntryType<SectionEntry>;

/// spherical, revolute, weld, curve_slider (7-io/cuts/).
const std::vector<SectionEntryType>& cutTypes();
/// joint_spring_damper, point_spring_damper, joint_actuation, track_guidance (7-io/forces/).
const std::vector<SectionEntryType>& forceTypes();
/// point, joint, relative_angle, energy, cut_force (7-io/sensors/).
const std::vector<SectionEntryType>& sensorTypes();

/// A non-zero vector under `key` of `map` (a joint's or a turn's axis; any length, the model
/// normalises it); an error at the key otherwise.
Eigen::Vector3d readAxis(const MapReader& map, const std::string& key);
/// A curve slider's `orientation` (follow_track, the default, or translate), of an element or a cut.
SliderOrientation readSliderOrientation(const MapReader& map);
/// A sensor's `quantity`: position, velocity or acceleration.
Derivative readDerivative(const MapReader& map);

}  // namespace mbsopt
