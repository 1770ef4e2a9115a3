#include "mbsopt/io/element_type.hpp"

#include <stdexcept>

namespace mbsopt {

// Each in its own file of 7-io/elements/.
ElementType offsetElement();
ElementType revoluteElement();
ElementType prismaticElement();
ElementType curveSliderElement();
ElementType sphericalElement();

const std::vector<ElementType>& elementTypes() {
  static const std::vector<ElementType> registry{
      offsetElement(), revoluteElement(), prismaticElement(), curveSliderElement(), sphericalElement(),
  };
  return registry;
}

Eigen::Vector3d readAxis(const MapReader& map, const std::string& key) {
  const Eigen::Vector3d axis = map.vector(key);
  if (!(axis.norm() > 1e-12)) map.fail(key, key + " must be a non-zero vector");
  return axis;
}

SliderOrientation readSliderOrientation(const MapReader& map) {
  return map.choice("orientation", {"follow_track", "translate"}, "follow_track") == "translate"
             ? SliderOrientation::Translate
             : SliderOrientation::FollowTrack;
}

std::vector<std::string> elementTypeNames() {
  std::vector<std::string> names;
  for (const ElementType& type : elementTypes()) names.push_back(type.name);
  return names;
}

const ElementType& elementType(const std::string& name) {
  for (const ElementType& type : elementTypes())
    if (type.name == name) return type;
  std::string known;
  for (const std::string& type_name : elementTypeNames()) known += (known.empty() ? "" : ", ") + type_name;
  throw std::invalid_argument("unknown element type '" + name + "' (known: " + known + ")");
}

}  // namespace mbsopt
