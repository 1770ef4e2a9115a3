// `--set` for the setting whose value is a word, settings.closure (problems/scenes/README.md,
// "Dotted parameter names"): through the loader and through the command line.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <unistd.h>

#include "mbsopt/io/scene_file.hpp"

namespace mbsopt {
namespace {

SceneSource shipped(const std::string& name) {
  return readSceneFile(std::string(MBSOPT_SOURCE_DIR) + "/problems/scenes/" + name + ".yaml");
}

ParameterOverride closure(const std::string& word) { return ParameterOverride::ofWord("settings.closure", word); }

TEST(WordSettings, ClosureIsAWordSetting) {
  EXPECT_TRUE(isWordSetting("settings.closure"));
  EXPECT_FALSE(isWordSetting("settings.step"));
  EXPECT_FALSE(isWordSetting("closure"));
}

// four_bar.yaml writes no closure (the default, position): the override writes it in.
TEST(WordSettings, OverrideSetsAClosureTheFileLeavesAtItsDefault) {
  EXPECT_EQ(loadScene(shipped("four_bar")).scene.settings.closure, ClosureLevel::Position);
  EXPECT_EQ(loadScene(shipped("four_bar"), {closure("acceleration")}).scene.settings.closure,
            ClosureLevel::Acceleration);
  EXPECT_EQ(loadScene(shipped("four_bar"), {closure("position")}).scene.settings.closure, ClosureLevel::Position);
}

// A file that writes the closure: the override replaces it; a bad word is an error at that line,
// naming the override.
TEST(WordSettings, OverrideReplacesTheFilesClosureAndABadWordNamesTheOverride) {
  const SceneSource source{"written.yaml",
                           "settings:\n"                                                                  // 1
                           "  end_time: 0.01\n"                                                           // 2
                           "  closure: position\n"                                                        // 3
                           "elements:\n"                                                                  // 4
                           "  - {name: slide, type: prismatic, parent: ground, axis: [1, 0, 0]}\n"        // 5
                           "bodies:\n"                                                                    // 6
                           "  - {name: block, frame: slide, mass: 1, Ixx: 0.1, Iyy: 0.1, Izz: 0.1}\n"};  // 7
  EXPECT_EQ(loadScene(source, {closure("acceleration")}).scene.settings.closure, ClosureLevel::Acceleration);
  try {
    loadScene(source, {closure("sideways")});
    FAIL() << "settings.closure=sideways was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(e.line(), 3) << e.what();
    EXPECT_NE(e.reason().find("expected one of position, acceleration, got 'sideways'"), std::string::npos) << e.what();
    EXPECT_NE(e.reason().find("(value from --set settings.closure=sideways)"), std::string::npos) << e.what();
  }
}

struct CommandResult {
  int status;
  std::string out, err;
};

CommandResult mbsopt(const std::string& arguments) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("mbsopt_word_settings_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path out = directory / "stdout", err = directory / "stderr";
  const int status = std::system(
      (std::string(MBSOPT_EXECUTABLE) + " " + arguments + " > " + out.string() + " 2> " + err.string()).c_str());
  const auto read = [](const std::filesystem::path& path) {
    std::ifstream in(path);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  };
  CommandResult result{status, read(out), read(err)};
  std::filesystem::remove_all(directory);
  return result;
}

double maxClosureError(const std::string& summary) {
  std::smatch match;
  if (!std::regex_search(summary, match, std::regex("max closure error ([^,]+),"))) return -1.0;
  return std::stod(match[1]);
}

// The paper's acceleration-level closure (38) lets the positions drift off the loop, which the
// default position-level closure holds to round-off: the override reaches the integrator.
TEST(WordSettings, CommandLineRunsTheAccelerationClosure) {
  const CommandResult position = mbsopt("simulate four_bar --t-end 0.5");
  const CommandResult acceleration = mbsopt("simulate four_bar --t-end 0.5 --set settings.closure=acceleration");
  ASSERT_EQ(position.status, 0) << position.err;
  ASSERT_EQ(acceleration.status, 0) << acceleration.err;
  const double held = maxClosureError(position.out), drifted = maxClosureError(acceleration.out);
  ASSERT_GE(held, 0.0) << position.out;
  ASSERT_GE(drifted, 0.0) << acceleration.out;
  EXPECT_LT(held, 1e-12);
  EXPECT_GT(drifted, 100.0 * held);
}

TEST(WordSettings, CommandLineRefusesABadWord) {
  const CommandResult run = mbsopt("simulate four_bar --t-end 0.01 --set settings.closure=sideways");
  EXPECT_NE(run.status, 0);
  EXPECT_NE(run.err.find("error: settings: closure: expected one of position, acceleration, got 'sideways' "
                         "(value from --set settings.closure=sideways)"),
            std::string::npos)
      << run.err;
}

}  // namespace
}  // namespace mbsopt
