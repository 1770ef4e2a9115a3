// The units the reports give model parameters (2-model/units.hpp), by what each number is in the
// shipped scenes: a body's mass and inertia, an offset's translation, a joint spring on a revolute
// or a prismatic joint, a driven joint's polynomial, an actuation's harmonics, gravity.
#include <gtest/gtest.h>

#include <string>

#include "mbsopt/model/units.hpp"
#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

std::string unitOf(const std::string& scene, const std::string& parameter) {
  const Model& model = loadScene(readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/" + scene)).scene.model;
  return parameterUnit(model, model.parameterIndex(parameter));
}

TEST(ParameterUnit, NamesEachNumberByWhatItIs) {
  const std::string tramway = "problems/scenes/tramway.yaml";
  EXPECT_EQ(unitOf(tramway, "carbody1.mass"), "kg");
  EXPECT_EQ(unitOf(tramway, "carbody1.Izz"), "kg·m²");
  EXPECT_EQ(unitOf(tramway, "front_secondary.k"), "N·m/rad");  // a spring on a revolute joint
  EXPECT_EQ(unitOf(tramway, "front_secondary.c"), "N·m·s/rad");
  EXPECT_EQ(unitOf(tramway, "bogie1_guidance.k"), "N·m/rad");  // a track guidance's torsional spring
  EXPECT_EQ(unitOf(tramway, "bogie1_track.motion.polynomial.0"), "m");  // s(t) = s₀ + v t of a curve slider
  EXPECT_EQ(unitOf(tramway, "bogie1_track.motion.polynomial.1"), "m/s");
  EXPECT_EQ(unitOf(tramway, "gravity.y"), "m/s²");
  EXPECT_EQ(unitOf(tramway, "rail.segments.1.radius"), "");  // a track's numbers: no unit named
  const std::string absorber = "problems/suite/tuned_mass_damper.yaml";
  EXPECT_EQ(unitOf(absorber, "tmd.k"), "N/m");  // a spring on a prismatic joint
  EXPECT_EQ(unitOf(absorber, "tmd.c"), "N·s/m");
  EXPECT_EQ(unitOf(absorber, "tmd.rest"), "m");
  EXPECT_EQ(unitOf("problems/scenes/slider_crank.yaml", "conrod_end.translation.x"), "m");
  EXPECT_EQ(unitOf("problems/scenes/slider_crank.yaml", "crank.motion.polynomial.1"), "rad/s");
  const std::string drive = "problems/suite/rest_to_rest.yaml";  // a force on a prismatic cart
  EXPECT_EQ(unitOf(drive, "drive.value.harmonics.0.amplitude"), "N");
  EXPECT_EQ(unitOf(drive, "drive.value.harmonics.0.angular_frequency"), "rad/s");
}

}  // namespace
}  // namespace mbsopt
