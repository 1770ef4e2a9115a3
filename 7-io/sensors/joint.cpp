// `joint`: a joint coordinate, its rate or its acceleration.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType jointSensor() {
  return {"joint", "the coordinate of `joint`, its rate or its acceleration (`quantity`)", {"joint", "quantity"},
          [](SectionEntry& s) {
            const int coordinate = s.model().coordinate(s.joint("joint"));
            const Derivative d = readDerivative(s.map());
            s.guarded([&] { s.model().addSensor(s.name(), JointSensor{coordinate, d}); });
          }};
}

}  // namespace mbsopt
