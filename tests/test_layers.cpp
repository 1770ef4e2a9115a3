// The layers point one way (README, "Folders"): each of the library's layers, 1-linalg … 8-design,
// includes only itself and the layers before it; the front ends (app/, python/) and bench/ include
// the library, and python/ and bench/ nothing of app/. Every project include of every source file is
// read and checked against what its folder may use; an include upwards or sideways fails with the
// file and the include, and so does a layer included without the "mbsopt/" prefix the installed
// package needs.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace mbsopt {
namespace {

/// The library's layers in pipeline order: (folder, include prefix after "mbsopt/").
const std::vector<std::pair<std::string, std::string>>& layers() {
  static const std::vector<std::pair<std::string, std::string>> ordered{
      {"1-linalg", "linalg"},         {"2-model", "model"},   {"3-algorithms", "algorithms"},
      {"4-integrators", "integrators"}, {"5-sensitivity", "sensitivity"}, {"6-optimizers", "optimizers"},
      {"7-io", "io"},                 {"8-design", "design"}};
  return ordered;
}

/// What each folder may include: a layer, itself and the layers before it; a front end, every layer
/// (each its own files too).
std::map<std::string, std::set<std::string>> allowedIncludes() {
  std::map<std::string, std::set<std::string>> allowed;
  std::set<std::string> below;
  for (const auto& [folder, layer] : layers()) {
    below.insert(layer);
    allowed[folder] = below;
  }
  allowed["app"] = below;
  allowed["app"].insert("app");
  allowed["python"] = below;
  allowed["python"].insert("python");
  allowed["bench"] = below;
  allowed["bench"].insert("bench");
  return allowed;
}

TEST(Layers, EveryIncludePointsDownwards) {
  const std::regex project_include(R"(^\s*#\s*include\s+"(mbsopt/)?([a-z_]+)/)");
  std::set<std::string> library;
  for (const auto& [folder, layer] : layers()) library.insert(layer);
  int files = 0;
  for (const auto& [folder, allowed] : allowedIncludes()) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(MBSOPT_SOURCE_DIR) + "/" + folder)) {
      const std::string extension = entry.path().extension().string();
      if (extension != ".hpp" && extension != ".cpp" && extension != ".in") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        std::smatch match;
        if (!std::regex_search(line, match, project_include)) continue;
        const std::string included = match[2].str();
        EXPECT_TRUE(allowed.count(included))
            << entry.path().string() << ":" << number << ": " << folder << "/ includes " << included << "/";
        EXPECT_EQ(match[1].matched, library.count(included) == 1)
            << entry.path().string() << ":" << number << ": " << included << "/ is included as "
            << (match[1].matched ? "\"mbsopt/" + included + "/…\"" : "\"" + included + "/…\", not \"mbsopt/" + included + "/…\"");
      }
    }
  }
  EXPECT_GT(files, 200);  // the folders were found and read
}

// The top-level CMakeLists.txt adds the layers in the order above, before the front ends.
TEST(Layers, TheBuildAddsTheLayersInPipelineOrder) {
  std::ifstream in(std::string(MBSOPT_SOURCE_DIR) + "/CMakeLists.txt");
  const std::regex added(R"(^\s*add_subdirectory\(([\w-]+)\))");
  std::vector<std::string> subdirectories;
  std::string line;
  while (std::getline(in, line)) {
    std::smatch match;
    if (std::regex_search(line, match, added)) subdirectories.push_back(match[1].str());
  }
  std::vector<std::string> expected;
  for (const auto& [folder, layer] : layers()) expected.push_back(folder);
  ASSERT_GE(subdirectories.size(), expected.size());
  EXPECT_EQ(std::vector<std::string>(subdirectories.begin(), subdirectories.begin() + static_cast<long>(expected.size())), expected);
}

}  // namespace
}  // namespace mbsopt
