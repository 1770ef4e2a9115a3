// `energy`: the scene's kinetic, potential or total mechanical energy (3-algorithms/energy.hpp).
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType energySensor() {
  return {"energy", "the scene's kinetic, potential or total (the default) mechanical energy [J] (`part`)", {"part"},
          [](SectionEntry& s) {
            const std::string part = s.map().choice("part", {"kinetic", "potential", "total"}, "total");
            const EnergyPart p = part == "kinetic"     ? EnergyPart::Kinetic
                                 : part == "potential" ? EnergyPart::Potential
                                                       : EnergyPart::Total;
            s.guarded([&] { s.model().addSensor(s.name(), EnergySensor{p}); });
          }};
}

}  // namespace mbsopt
