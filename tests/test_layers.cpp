// The layers point one way (README, "Folders"): app → bench, problems → optimizers | sensitivity →
// dynamics. Every project include of every source file is read and checked against the folders
// its own folder may use; an include upwards or sideways fails with the file and the include.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <string>

namespace mbsopt {
namespace {

const std::map<std::string, std::set<std::string>>& allowedFolders() {
  static const std::map<std::string, std::set<std::string>> allowed{
      {"dynamics", {"dynamics"}},
      {"sensitivity", {"sensitivity", "dynamics"}},
      {"optimizers", {"optimizers"}},
      {"problems", {"problems", "optimizers", "sensitivity", "dynamics"}},
      {"app", {"app", "problems", "optimizers", "sensitivity", "dynamics"}},
  };
  return allowed;
}

TEST(Layers, EveryIncludePointsDownwards) {
  const std::regex project_include(R"(^\s*#\s*include\s+"([a-z_]+)/)");
  int files = 0;
  for (const auto& [folder, allowed] : allowedFolders()) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(MBSOPT_SOURCE_DIR) + "/" + folder)) {
      const std::string extension = entry.path().extension().string();
      if (extension != ".hpp" && extension != ".cpp" && extension != ".in") continue;
      ++files;
      std::ifstream in(entry.path());
      std::string line;
      for (int number = 1; std::getline(in, line); ++number) {
        std::smatch match;
        if (std::regex_search(line, match, project_include)) {
          EXPECT_TRUE(allowed.count(match[1].str()))
              << entry.path().string() << ":" << number << ": " << folder << "/ includes " << match[1].str() << "/";
        }
      }
    }
  }
  EXPECT_GT(files, 100);  // the folders were found and read
}

}  // namespace
}  // namespace mbsopt
