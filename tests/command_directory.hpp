// A fixture for tests that run the `mbsopt` program: a fresh directory per test (removed after it),
// the program run with stdout and stderr to files there, and those files read back.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

namespace mbsopt::test {

class CommandDirectory : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = std::filesystem::temp_directory_path() /
                 ("mbsopt_" + std::to_string(::getpid()) + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->test_suite_name() + "_" +
                  ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(directory_);
    std::filesystem::create_directories(directory_);
  }
  void TearDown() override { std::filesystem::remove_all(directory_); }

  std::string path(const std::string& name) const { return (directory_ / name).string(); }

  /// Runs `mbsopt ARGUMENTS` from the source directory, stdout and stderr to the files "stdout" and
  /// "stderr"; returns the exit status (-1 when it did not exit).
  int mbsopt(const std::string& arguments) const {
    const std::string command = "cd " + std::string(MBSOPT_SOURCE_DIR) + " && " + MBSOPT_EXECUTABLE + " " + arguments +
                                " > " + path("stdout") + " 2> " + path("stderr");
    const int status = std::system(command.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }

  std::string read(const std::string& name) const {
    std::ifstream in(path(name));
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
  }

  nlohmann::json json(const std::string& name) const { return nlohmann::json::parse(read(name)); }

  std::filesystem::path directory_;
};

}  // namespace mbsopt::test
