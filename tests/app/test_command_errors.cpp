// What the command line says of bad input: exit status 1 (the documented status of an error), one
// short line in the program's own words on stderr, and nothing done before it: an output path that
// cannot be written is refused before the first simulation, not after an optimisation of minutes.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "mbsopt/optimizers/optimizer.hpp"
#include "tests/command_directory.hpp"

namespace mbsopt {
namespace {

class CommandErrors : public test::CommandDirectory {
 protected:
  /// Runs `arguments`, expects exit status 1 and one line on stderr holding `says`, and nothing on stdout.
  void expectRefused(const std::string& arguments, const std::string& says) {
    SCOPED_TRACE(arguments);
    EXPECT_EQ(mbsopt(arguments), 1);
    const std::string error = read("stderr");
    EXPECT_NE(error.find(says), std::string::npos) << error;
    EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << error;
    EXPECT_LT(error.size(), 120u + arguments.size()) << error;  // no 310-digit range
    EXPECT_EQ(read("stdout"), "") << "work was done before the refusal";
  }
};

TEST_F(CommandErrors, BadNumbersExitOneWithTheOptionAndTheValue) {
  expectRefused("simulate pendulum --every 0", "--every: must be a positive integer, got 0");
  expectRefused("simulate pendulum --every 1.5", "--every: must be a positive integer, got 1.5");
  expectRefused("optimize tramway --accuracy 0", "--accuracy: must be a positive number, got 0");
  expectRefused("optimize tramway --budget 0", "--budget: must be a positive number, got 0");
  expectRefused("optimize tramway --epsilon -1", "--epsilon: must be a number of at least 0, got -1");
  expectRefused("optimize tramway --max-iter 0", "--max-iter: must be a positive integer, got 0");
  expectRefused("precision pendulum --repeat 0", "--repeat: must be a whole number from 1 to 1000, got 0");
  expectRefused("simulate pendulum --nope", "simulate has no option --nope");
  expectRefused("compare tramway --every 0", "compare has no option --every");  // not CLI11's "0 --every"
  expectRefused("optimize tramway extra", "optimize takes no argument 'extra'");
  std::string registered;  // the registry's names, as CLI11 lists them
  for (const std::string& name : optimizerNames()) registered += (registered.empty() ? "" : ",") + name;
  expectRefused("optimize tramway --optimizer foo", "foo not in {" + registered + "}");
}

TEST_F(CommandErrors, AnOutputThatCannotBeWrittenIsRefusedBeforeTheWork) {
  expectRefused("optimize tramway --out /proc/mbsopt-optimum", "--out /proc/mbsopt-optimum: cannot be created");
  expectRefused("optimize tramway --json /proc/mbsopt.json", "--json /proc/mbsopt.json: its directory cannot be written");
  expectRefused("compare tramway --out /proc/mbsopt-comparison", "--out /proc/mbsopt-comparison: cannot be created");
  expectRefused("gradcheck tramway --json " + path("missing/g.json"), "does not exist");
  expectRefused("simulate pendulum --json " + path("missing/s.json"), "does not exist");
  expectRefused("simulate pendulum --out " + directory_.string(), "is not a regular file");
  expectRefused("precision pendulum --out /proc/mbsopt-precision", "cannot be created");
  expectRefused("benchmark tramway --out /proc/mbsopt-benchmark", "cannot be created");
}

// A loop that cannot close during a run (test_integrator_errors.cpp has its time) is the scene's
// error at the cut joint's line, from simulate as from the design commands.
TEST_F(CommandErrors, ALoopThatCannotCloseIsLocatedAtItsCut) {
  const std::string short_rod = " --set conrod_end.translation.x=0.12 --set rail.translation.y=0.05";
  EXPECT_EQ(mbsopt("simulate slider_crank" + short_rod), 1);
  EXPECT_NE(read("stderr").find("slider_crank.yaml:38:12: error: the loop closed by wrist_pin cannot be closed"),
            std::string::npos)
      << read("stderr");
  std::ifstream in(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/slider_crank.yaml");
  std::stringstream scene;
  scene << in.rdbuf() << "design:\n  variables: [{parameter: block.mass, lower: 0.1, upper: 2}]\n"
        << "  cost: {sensor: slider_a, of: max_abs}\n  artificial: {initial: 100, lower: 0, upper: 1000, scale: 10}\n";
  std::ofstream(path("design.yaml")) << scene.str();
  for (const std::string command : {"gradcheck", "optimize"}) {
    EXPECT_EQ(mbsopt(command + " " + path("design.yaml") + short_rod), 1) << command;
    EXPECT_NE(read("stderr").find("design.yaml:38:12: error: the loop closed by wrist_pin cannot be closed"),
              std::string::npos)
        << command << ": " << read("stderr");
  }
}

TEST_F(CommandErrors, HelpAndVersionStillExitZero) {
  EXPECT_EQ(mbsopt("--version"), 0);
  EXPECT_EQ(mbsopt("gradcheck --help"), 0);
  EXPECT_NE(read("stdout").find("--outside-bounds"), std::string::npos);
}

}  // namespace
}  // namespace mbsopt
