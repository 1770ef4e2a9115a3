// The data file of a gnuplot figure the program writes (7-io/gnuplot.hpp): blocks, each headed
// "# TITLE" ("# (marks)" for a run's ringed reported point), of "x y" lines.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

namespace mbsopt::test {

struct PlotBlock {
  std::string title;
  std::vector<std::pair<double, double>> points;
};

inline std::vector<PlotBlock> readPlotBlocks(const std::filesystem::path& path) {
  std::ifstream data(path);
  std::vector<PlotBlock> blocks;
  for (std::string line; std::getline(data, line);)
    if (line.starts_with("# ")) {
      blocks.push_back({line.substr(2), {}});
    } else if (!line.empty() && !blocks.empty()) {
      double x = 0.0, y = 0.0;
      std::istringstream(line) >> x >> y;
      blocks.back().points.emplace_back(x, y);
    }
  return blocks;
}

}  // namespace mbsopt::test
