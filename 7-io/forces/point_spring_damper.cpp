// `point_spring_damper`: a spring and damper along the line between two points of two frames.
#include "mbsopt/io/entry_type.hpp"

namespace mbsopt {

SectionEntryType pointSpringDamper() {
  return {"point_spring_damper",
          "a spring and damper between point_a of frame_a and point_b of frame_b (the frames' origins by default), "
          "F = −k (ℓ − rest_length) − c ℓ̇ along the line between them",
          {"frame_a", "point_a", "frame_b", "point_b", "k", "c", "rest_length"}, [](SectionEntry& f) {
            const FrameIndex a = f.frame("frame_a"), b = f.frame("frame_b");
            const Eigen::Vector3d pa = f.map().vector("point_a", Eigen::Vector3d::Zero());
            const Eigen::Vector3d pb = f.map().vector("point_b", Eigen::Vector3d::Zero());
            const double k = f.map().nonNegative("k", 0.0), c = f.map().nonNegative("c", 0.0);
            const double rest = f.map().nonNegative("rest_length", 0.0);
            f.guarded([&] { f.model().addPointSpringDamper(f.name(), a, pa, b, pb, k, c, rest); });
          }};
}

}  // namespace mbsopt
