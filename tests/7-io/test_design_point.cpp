// A design point a user gives (`gradcheck --design`, Problem.evaluate(design)) is checked as the scene
// file checks the same numbers: within the design's bounds unless that is asked for, and then each
// value as `--set` would set it, so that a negative stiffness is refused with the scene's own words
// instead of being simulated (an RMS of 1e135). The design's bounds are such values too.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "mbsopt/io/design_point.hpp"
#include "tests/command_directory.hpp"

namespace mbsopt {
namespace {

const std::string kTunedMassDamper = std::string(MBSOPT_SOURCE_DIR) + "/problems/suite/tuned_mass_damper.yaml";

/// The message of the std::invalid_argument that `call` throws ("" when it throws none).
template <class Call>
std::string refusal(Call&& call) {
  try {
    call();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(DesignPoint, IsRefusedOutsideItsBoundsUnlessAskedFor) {
  const SceneSource source = readSceneFile(kTunedMassDamper);
  const DesignProblem problem = loadDesignProblem(source);
  const std::string outside = refusal([&] { checkedDesignPoint(source, {}, problem, {{1200, 5}, {}, false}); });
  EXPECT_NE(outside.find("tmd.k = 1200 lies outside its bounds [100, 1000]"), std::string::npos) << outside;
  const Eigen::VectorXd x = checkedDesignPoint(source, {}, problem, {{1200, 5}, {}, true});
  EXPECT_EQ(x[0], 12.0);  // scale 100
  ASSERT_EQ(outsideBounds(problem, x).size(), 1u);
  EXPECT_EQ(outsideBounds(problem, x)[0], "tmd.k = 1200 above its upper bound 1000");
}

// b_{k+1} as the design variables: within its bounds [0, 1] m unless asked for, and never beyond what
// x = b / scale can hold (scale 0.01: 1e308 would make x, and the cost x · scale, infinite).
TEST(DesignPoint, TheArtificialVariableIsCheckedAsTheDesignVariablesAre) {
  const SceneSource source = readSceneFile(kTunedMassDamper);
  const DesignProblem problem = loadDesignProblem(source);
  const std::string above = refusal([&] { checkedDesignPoint(source, {}, problem, {{}, 2.0, false}); });
  EXPECT_NE(above.find("b_{k+1} = 2 lies outside its bounds [0, 1]"), std::string::npos) << above;
  const Eigen::VectorXd x = checkedDesignPoint(source, {}, problem, {{}, 2.0, true});
  EXPECT_EQ(x[2], 200.0);
  ASSERT_EQ(outsideBounds(problem, x).size(), 1u);
  EXPECT_EQ(outsideBounds(problem, x)[0], "b_{k+1} = 2 above its upper bound 1");
  const std::string huge = refusal([&] { checkedDesignPoint(source, {}, problem, {{}, 1e308, true}); });
  EXPECT_NE(huge.find("beyond the range of its scale"), std::string::npos) << huge;
}

TEST(DesignPoint, ANegativeStiffnessIsRefusedAsTheSceneRefusesIt) {
  const SceneSource source = readSceneFile(kTunedMassDamper);
  const DesignProblem problem = loadDesignProblem(source);
  for (const bool outside_bounds : {false, true}) {
    const std::string why = refusal([&] { checkedDesignPoint(source, {}, problem, {{-400, 5}, {}, outside_bounds}); });
    EXPECT_FALSE(why.empty());
    if (outside_bounds) {  // past the bounds, the scene's own check of k, at its line
      EXPECT_NE(why.find("tuned_mass_damper.yaml:30:"), std::string::npos) << why;
    }
    EXPECT_NE(why.find(outside_bounds ? "k must not be negative, got -400" : "outside its bounds"), std::string::npos) << why;
  }
  EXPECT_NE(refusal([&] { checkedDesignPoint(source, {}, problem, {{464.85, NAN}, {}, false}); }).find("not a finite number"),
            std::string::npos);
  EXPECT_NE(refusal([&] { checkedDesignPoint(source, {}, problem, {{464.85}, {}, false}); }).find("1 values for 2"),
            std::string::npos);
}

TEST(DesignPoint, ABoundTheSceneRefusesIsAnErrorAtTheBound) {
  SceneSource source = readSceneFile(kTunedMassDamper);
  const std::string from = "{parameter: tmd.k, lower: 100,";
  const std::size_t at = source.text.find(from);
  ASSERT_NE(at, std::string::npos);
  source.text.replace(at, from.size(), "{parameter: tmd.k, lower: -100,");
  try {
    loadDesignProblem(source);
    FAIL() << "a negative stiffness as a lower bound was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 37);
    EXPECT_NE(e.reason().find("its lower bound -100 is a value the scene refuses"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("k must not be negative"), std::string::npos) << e.what();
  }
}

class GradcheckDesign : public test::CommandDirectory {};

TEST_F(GradcheckDesign, RefusesWhatTheSceneRefusesAndNamesWhatLiesOutsideTheBounds) {
  EXPECT_EQ(mbsopt("gradcheck problems/suite/tuned_mass_damper.yaml --design -400,5"), 1);
  EXPECT_NE(read("stderr").find("outside its bounds"), std::string::npos) << read("stderr");
  EXPECT_EQ(mbsopt("gradcheck problems/suite/tuned_mass_damper.yaml --design -400,5 --outside-bounds"), 1);
  EXPECT_NE(read("stderr").find("k must not be negative"), std::string::npos) << read("stderr");
  ASSERT_EQ(mbsopt("gradcheck problems/suite/tuned_mass_damper.yaml --design 1200,5 --outside-bounds --json " +
                   path("g.json")),
            0)
      << read("stderr");
  EXPECT_NE(read("stdout").find("OUTSIDE THE DESIGN'S BOUNDS (--outside-bounds): tmd.k = 1200"), std::string::npos);
  EXPECT_EQ(json("g.json")["outside_bounds"][0], "tmd.k = 1200 above its upper bound 1000");
}

}  // namespace
}  // namespace mbsopt
