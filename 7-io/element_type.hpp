// The kinematic element types of a scene file's `elements:` section, one registry: each type's name,
// what it is, the keys its entry takes besides name, type and parent, and how it adds itself to the
// model. A type is one file of 7-io/elements/ and one line of element_type.cpp's table.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <string>
#include <vector>

#include "mbsopt/model/model.hpp"
#include "mbsopt/io/yaml_reader.hpp"

namespace mbsopt {

/// What an element type's reader is given: its entry in the file and the scene being built, with
/// the readings every type shares. Every error is reported at the entry's line in the file.
class ElementEntry {
 public:
  virtual ~ElementEntry() = default;
  /// The entry's map, for its own numbers and for errors at one of its keys (MapReader::fail).
  virtual const MapReader& map() const = 0;
  virtual const std::string& name() const = 0;
  /// The frame the element starts from (its `parent`: the ground or an element placed before).
  virtual FrameIndex parent() const = 0;
  virtual Model& model() = 0;
  /// The track named under `key` (the scene's `tracks:` section).
  virtual TrackIndex track(const std::string& key) const = 0;
  /// Runs a model-builder call; its std::invalid_argument becomes an error at the entry.
  virtual void guarded(const std::function<void()>& call) const = 0;
  /// The start of the joint coordinate `coordinate`: the entry's `motion` (a driven joint) or its
  /// q0 and v0 (both 0 by default; in deg only where `angular`).
  virtual void motionOrInitialValues(const std::string& coordinate, bool angular) = 0;
  /// The start of the joint coordinate `coordinate` given as numbers (SI units).
  virtual void initialValues(const std::string& coordinate, double q0, double v0) = 0;
  /// A further name the entry adds to the model (an intermediate frame and its coordinate): refused
  /// where another entry of the file has it, and located at this entry in later errors.
  virtual void claimName(const std::string& added) = 0;
};

/// A non-zero vector under `key` of `map` (a joint's or a turn's axis; any length, the model
/// normalises it); an error at the key otherwise.
Eigen::Vector3d readAxis(const MapReader& map, const std::string& key);
/// A curve slider's `orientation` (follow_track, the default, or translate), of an element or a cut.
SliderOrientation readSliderOrientation(const MapReader& map);

struct ElementType {
  std::string name;
  std::string description;        ///< one sentence, for the scene files' documentation and errors
  std::vector<std::string> keys;  ///< the entry's keys besides name, type and parent
  std::function<void(ElementEntry&)> add;
};

/// offset, revolute, prismatic, curve_slider, spherical.
const std::vector<ElementType>& elementTypes();
/// The registered type `name`; std::invalid_argument listing the names otherwise.
const ElementType& elementType(const std::string& name);
/// The registered names, in the registry's order.
std::vector<std::string> elementTypeNames();

}  // namespace mbsopt
