// `mbsopt gradcheck` end to end: its JSON carries every functional's value and gradient by each
// method under the documented keys, and the methods agree as the exact-gradient tests require.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <unistd.h>

#include "mbsopt/io/scene_file.hpp"
#include "tests/sensitivity_scenes.hpp"

namespace mbsopt {
namespace {

double relativeGap(const std::vector<double>& a, const std::vector<double>& b) {
  double gap = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    gap = std::max(gap, std::abs(a[i] - b[i]));
    scale = std::max(scale, std::abs(b[i]));
  }
  return gap / std::max(scale, 1e-300);
}

TEST(GradcheckCommand, WritesEveryMethodUnderTheDocumentedKeys) {
  const std::filesystem::path directory =
      std::filesystem::temp_directory_path() / ("mbsopt_gradcheck_" + std::to_string(::getpid()));
  std::filesystem::create_directories(directory);
  const std::filesystem::path scene = directory / "chain.yaml", json = directory / "chain.json";
  std::ofstream(scene) << test::kOpenChainProblem;
  const std::string command = std::string(MBSOPT_EXECUTABLE) + " gradcheck " + scene.string() + " --json " +
                              json.string() + " > " + (directory / "stdout").string();
  ASSERT_EQ(std::system(command.c_str()), 0);
  nlohmann::json document;
  std::ifstream(json) >> document;
  ASSERT_EQ(document["functionals"].size(), 5u);  // the cost and 2 × 2 constraints
  for (const auto& f : document["functionals"]) {
    ASSERT_TRUE(f.contains("name") && f.contains("value"));
    const auto& g = f["gradients"];
    const auto adjoint = g["adjoint"].get<std::vector<double>>();
    ASSERT_EQ(adjoint.size(), 4u);  // three design variables and b_{k+1}
    EXPECT_LE(relativeGap(g["direct"].get<std::vector<double>>(), adjoint), 1e-9) << f["name"];
    EXPECT_LE(relativeGap(g["fd_central"].get<std::vector<double>>(), adjoint), 1e-6) << f["name"];
    EXPECT_TRUE(g.contains("fd_forward"));
    // A discretisation error of O(h²) (2.8e-3 measured at this h; its order in test_continuous_adjoint).
    EXPECT_LE(relativeGap(g["continuous-adjoint"].get<std::vector<double>>(), adjoint), 1e-2) << f["name"];
    EXPECT_EQ(f["fd_sweep"].size(), 8u);  // relative steps 1e-2 … 1e-9
    EXPECT_EQ(f["fd_sweep"][0]["relative_step"].get<double>(), 1e-2);
  }
  // The columns are named: the problem's variables with their scales, then b_{k+1}; the cost is
  // b_{k+1} = x·scale, so its derivative in the last column is that scale, zero in the others.
  const DesignProblem problem = loadDesignProblem({"chain.yaml", test::kOpenChainProblem});
  ASSERT_EQ(document["variables"].size(), problem.design.variables.size() + 1);
  for (std::size_t i = 0; i < problem.design.variables.size(); ++i) {
    EXPECT_EQ(document["variables"][i]["name"], problem.design.variables[i].parameter);
    EXPECT_EQ(document["variables"][i]["scale"].get<double>(), problem.design.variables[i].scale);
  }
  EXPECT_EQ(document["variables"].back()["name"], "b_{k+1}");
  const auto cost = document["functionals"][0]["gradients"]["adjoint"].get<std::vector<double>>();
  EXPECT_EQ(cost.back(), document["variables"].back()["scale"].get<double>());
  EXPECT_EQ(cost.front(), 0.0);
  for (const char* key : {"simulation", "adjoint", "continuous-adjoint", "direct", "fd_forward", "fd_central"})
    EXPECT_GT(document["timings_s"][key].get<double>(), 0.0) << key;
  std::filesystem::remove_all(directory);
}

}  // namespace
}  // namespace mbsopt
