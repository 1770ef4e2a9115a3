// `rotational_damper`: a torque against the rotation of one frame relative to another.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType rotationalDamper() {
  return {"rotational_damper",
          "a damper against the rotation of frame_b relative to frame_a: the torque −c (ω_b − ω_a) on frame_b, its "
          "opposite on frame_a (across a ball joint, MuJoCo's damping of the ball) [c in N·m·s/rad]",
          {"frame_a", "frame_b", "c"}, [](SectionEntry& f) {
            const FrameIndex a = f.frame("frame_a"), b = f.frame("frame_b");
            const double c = f.map().nonNegative("c", 0.0);
            f.guarded([&] { f.model().addRotationalDamper(f.name(), a, b, c); });
          }};
}

}  // namespace mbsopt
