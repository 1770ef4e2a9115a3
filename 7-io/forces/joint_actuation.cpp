// `joint_actuation`: a generalized force Q = value(t) on one joint coordinate.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType jointActuation() {
  return {"joint_actuation", "a generalized force Q = value(t) on `joint` [N or N·m], value a time function",
          {"joint", "value"}, [](SectionEntry& f) {
            const std::string j = f.joint("joint");
            f.map().required("value");
            const TimeFunction value = f.timeFunction("value");
            f.guarded([&] { f.model().addJointActuation(f.name(), j, value); });
          }};
}

}  // namespace mbsopt
