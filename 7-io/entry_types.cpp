#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

// Each in its own file of 7-io/cuts/, forces/ and sensors/.
SectionEntryType sphericalCut();
SectionEntryType revoluteCut();
SectionEntryType weldCut();
SectionEntryType curveSliderCut();
SectionEntryType jointSpringDamper();
SectionEntryType pointSpringDamper();
SectionEntryType jointActuation();
SectionEntryType trackGuidance();
SectionEntryType rotationalDamper();
SectionEntryType pointSensor();
SectionEntryType jointSensor();
SectionEntryType relativeAngleSensor();
SectionEntryType energySensor();
SectionEntryType cutForceSensor();

const std::vector<SectionEntryType>& cutTypes() {
  static const std::vector<SectionEntryType> registry{sphericalCut(), revoluteCut(), weldCut(), curveSliderCut()};
  return registry;
}

const std::vector<SectionEntryType>& forceTypes() {
  static const std::vector<SectionEntryType> registry{jointSpringDamper(), pointSpringDamper(), jointActuation(),
                                                      trackGuidance(), rotationalDamper()};
  return registry;
}

const std::vector<SectionEntryType>& sensorTypes() {
  static const std::vector<SectionEntryType> registry{pointSensor(), jointSensor(), relativeAngleSensor(),
                                                      energySensor(), cutForceSensor()};
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

Derivative readDerivative(const MapReader& map) {
  const std::string q = map.choice("quantity", {"position", "velocity", "acceleration"});
  return q == "position" ? Derivative::Position : q == "velocity" ? Derivative::Velocity : Derivative::Acceleration;
}

}  // namespace mbsopt
