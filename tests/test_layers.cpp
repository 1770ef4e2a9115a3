// The layers point one way (README, "Folders"): app → bench, problems → optimizers | sensitivity →
// dynamics. Every project include of every source file is read and checked against the folders
// its own folder may use; an include upwards or sideways fails with the file and the include, and so
// does a layer of the libraries included without the "mbsopt/" prefix the installed package needs.
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
  // A layer of the libraries is included as "mbsopt/LAYER/…", the path consumers of the installed
  // package use; app/ and tests/ are the project's own.
  const std::regex project_include(R"(^\s*#\s*include\s+"(mbsopt/)?([a-z_]+)/)");
  const std::set<std::string> layers{"dynamics", "sensitivity", "optimizers", "problems"};
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
          const std::string included = match[2].str();
          EXPECT_TRUE(allowed.count(included))
              << entry.path().string() << ":" << number << ": " << folder << "/ includes " << included << "/";
          EXPECT_EQ(match[1].matched, layers.count(included) == 1)
              << entry.path().string() << ":" << number << ": " << included << "/ is included as "
              << (match[1].matched ? "\"mbsopt/" + included + "/…\"" : "\"" + included + "/…\", not \"mbsopt/" + included + "/…\"");
        }
      }
    }
  }
  EXPECT_GT(files, 100);  // the folders were found and read
}

}  // namespace
}  // namespace mbsopt
