// `joint_spring_damper`: Q = −k (q − rest(t)) − c (q̇ − rest'(t)) on one joint coordinate.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType jointSpringDamper() {
  return {"joint_spring_damper",
          "a spring and damper on `joint`: Q = −k (q − rest(t)) − c (q̇ − rest'(t)); rest a number or a time function",
          {"joint", "k", "c", "rest"}, [](SectionEntry& f) {
            const std::string j = f.joint("joint");
            const double k = f.map().nonNegative("k", 0.0), c = f.map().nonNegative("c", 0.0);
            const TimeFunction rest = f.map().has("rest") ? f.timeFunction("rest") : TimeFunction::constant(0.0);
            f.guarded([&] { f.model().addGuidanceSpring(f.name(), j, k, c, rest); });
          }};
}

}  // namespace mbsopt
