// Every choice by name has one registry (integrators, gradient methods, optimizers, formulations),
// and everyone else asks it: no registered name is compared as a string anywhere in the sources
// outside the registry that defines it, so that adding an entry is one line there.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <regex>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "mbsopt/integrators/integration.hpp"
#include "mbsopt/sensitivity/formulation.hpp"
#include "mbsopt/sensitivity/gradient_method.hpp"
#include "mbsopt/optimizers/optimizer.hpp"

namespace mbsopt {
namespace {

struct Registry {
  std::string file;  ///< where the names are defined, relative to the source tree
  std::vector<std::string> names;
};

std::vector<Registry> registries() {
  return {{"4-integrators/integration.cpp", integratorNames()},
          {"5-sensitivity/gradient_method.cpp", gradientMethodChoices()},
          {"6-optimizers/optimizer.cpp", optimizerNames()},
          {"5-sensitivity/formulation.cpp", formulationNames()}};
}

std::string escaped(const std::string& name) { return std::regex_replace(name, std::regex(R"([-.])"), R"(\$&)"); }

TEST(Registries, NoRegisteredNameIsComparedAsAStringOutsideItsRegistry) {
  int files = 0;
  for (const Registry& registry : registries()) {
    ASSERT_FALSE(registry.names.empty()) << registry.file;
    for (const std::string& name : registry.names) {
      // `x == "name"`, `"name" == x`, `!=` likewise.
      const std::regex compared("(==|!=)\\s*\"" + escaped(name) + "\"|\"" + escaped(name) + "\"\\s*(==|!=)");
      for (const char* folder : {"1-linalg", "2-model", "3-algorithms", "4-integrators", "5-sensitivity", "6-optimizers",
                                 "7-io", "8-design", "app", "python", "bench"}) {
        for (const auto& entry : std::filesystem::recursive_directory_iterator(std::string(MBSOPT_SOURCE_DIR) + "/" + folder)) {
          const std::string extension = entry.path().extension().string();
          if (extension != ".hpp" && extension != ".cpp") continue;
          const std::string relative = std::filesystem::relative(entry.path(), MBSOPT_SOURCE_DIR).string();
          if (relative == registry.file) continue;
          ++files;
          std::ifstream in(entry.path());
          std::string line;
          for (int number = 1; std::getline(in, line); ++number)
            EXPECT_FALSE(std::regex_search(line, compared))
                << relative << ":" << number << ": '" << name << "' compared by name outside " << registry.file << ": "
                << line;
        }
      }
    }
  }
  EXPECT_GT(files, 100);  // the folders were found and read
}

// Each registry's names are unique and each entry says what it is (the --help texts are made of them).
TEST(Registries, EveryEntryHasAUniqueNameAndADescription) {
  std::set<std::string> seen;
  const auto check = [&](const std::string& kind, const std::string& name, const std::string& description) {
    EXPECT_TRUE(seen.insert(kind + ":" + name).second) << kind << " '" << name << "' is registered twice";
    EXPECT_GT(description.size(), 20u) << kind << " '" << name << "' has no description";
  };
  for (const IntegratorInfo& info : integrators()) check("integrator", info.name, info.description);
  for (const GradientMethodInfo& info : gradientMethods()) check("gradient method", info.name, info.description);
  for (const OptimizerInfo& info : optimizers()) check("optimizer", info.name, info.description);
  for (const FormulationInfo& info : formulations()) check("formulation", info.name, info.description);
}

// A lookup finds what was registered, an alias finds the entry it stands for, and an unknown name is
// refused with the names that exist.
TEST(Registries, LookupsFindTheirEntryAndRefuseAnUnknownNameListingTheKnownOnes) {
  EXPECT_EQ(gradientMethod("fd").name, "fd_central");
  EXPECT_EQ(gradientMethod("fd_central").simulations_per_variable, 2);
  EXPECT_EQ(gradientMethod("fd_forward").simulations_per_variable, 1);
  EXPECT_EQ(gradientMethod("adjoint").simulations_per_variable, 0);
  EXPECT_EQ(formulation("grid_max").measure, TimeMeasure::GridMax);
  EXPECT_EQ(formulationOf(TimeMeasure::PositivePart).name, "positive_part");
  EXPECT_THROW(formulationOf(TimeMeasure::Integral), std::invalid_argument);
  for (const auto& [lookup, known] : std::vector<std::pair<std::function<void()>, std::string>>{
           {[] { integratorInfo("rk4"); }, "newmark"},
           {[] { gradientMethod("complex_step"); }, "adjoint"},
           {[] { optimizerInfo("bfgs"); }, "slsqp"},
           {[] { formulation("max"); }, "grid_max"}}) {
    try {
      lookup();
      ADD_FAILURE() << "an unknown name was accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(known), std::string::npos) << e.what();
    }
  }
}

// compare and benchmark run, without --optimizers, the five whose results the suite publishes; an
// optimizer registered beside them runs when it is named.
TEST(Registries, TheDefaultComparisonIsTheRegisteredSetMarkedForIt) {
  const std::vector<std::string> compared = defaultComparisonOptimizers();
  EXPECT_EQ(compared, (std::vector<std::string>{"sdcc", "slsqp", "mma", "ccsaq", "ipopt"}));
  EXPECT_EQ(optimizerNames().size(), compared.size() + 1);  // auglag_lbfgs, run when asked for
}

}  // namespace
}  // namespace mbsopt
