// `cut_force`: a component of the force or torque a cut joint transmits, from its multipliers λ.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType cutForceSensor() {
  return {"cut_force",
          "the x, y or z `component` in frame_a's axes of the force (the default) or torque (`quantity`) that `cut` "
          "exerts on its frame_b, from its Lagrange multipliers",
          {"cut", "quantity", "component"}, [](SectionEntry& s) {
            const int c = s.cut("cut");
            const bool torque = s.map().choice("quantity", {"force", "torque"}, "force") == "torque";
            const std::string component = s.map().choice("component", {"x", "y", "z"});
            const ReactionQuantity q = torque ? ReactionQuantity::Torque : ReactionQuantity::Force;
            s.guarded([&] { s.model().addSensor(s.name(), CutReactionSensor{c, q, component[0] - 'x'}); });
          }};
}

}  // namespace mbsopt
