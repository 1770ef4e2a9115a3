// Plots drawn by gnuplot (DESIGN.md §6: a real plotting tool): the data and the script are written
// beside the PNG, so that a figure can be redrawn or restyled without rerunning anything.
#pragma once

#include <string>
#include <vector>

namespace mbsopt {

/// One curve: a title and its points (x, y).
struct PlotSeries {
  std::string title;
  std::vector<std::pair<double, double>> points;
};

struct PlotPanel {
  std::string xlabel, ylabel;
  bool log_y = false;
  std::vector<PlotSeries> series;
  bool markers = true;  ///< a marker at each point (iterations); plain lines for dense series
};

/// Writes STEM.dat (one block per series of each panel), STEM.gp and, when gnuplot is installed,
/// STEM.png with the panels stacked vertically. Returns false (and says why on stderr) when gnuplot
/// is missing or fails; the data and the script are written regardless.
bool plotPanels(const std::string& stem, const std::string& title, const std::vector<PlotPanel>& panels);

}  // namespace mbsopt
