// Plots drawn by gnuplot (docs/design.md §6: a real plotting tool): the data and the script are written
// beside the PNG, so that a figure can be redrawn or restyled without rerunning anything.
#pragma once

#include <limits>
#include <string>
#include <vector>

namespace mbsopt {

/// One curve: a title and its points (x, y).
struct PlotSeries {
  std::string title;  ///< empty: not in the key
  std::vector<std::pair<double, double>> points;
  /// Large marks alone, no line (a run's reported point on its curve).
  bool marks_only = false;
  /// The line type (colour) of series n of a panel is n + 1 unless given here (a series drawn in
  /// another's colour).
  int line_type = 0;
};

struct PlotPanel {
  std::string xlabel{}, ylabel{};
  bool log_y = false;
  std::vector<PlotSeries> series{};
  bool markers = true;  ///< a marker at each point (iterations); plain lines for dense series
  std::string title{};  ///< above the panel; may be empty
  double y_max = std::numeric_limits<double>::quiet_NaN();  ///< the top of the y axis; NaN: gnuplot's choice
  double y_min = std::numeric_limits<double>::quiet_NaN();  ///< the bottom of the y axis; NaN: gnuplot's choice
  bool log_x = false;
};

/// Writes STEM.dat (one block per series of each panel), STEM.gp and, when gnuplot is installed,
/// STEM.png with the panels row by row, `columns` to a row (with one column each panel's key is
/// outside on the right, with more inside it). The n-th series of every panel gets the same colour.
/// Returns false (and says why on stderr) when gnuplot is missing or fails; the data and the script
/// are written regardless.
bool plotPanels(const std::string& stem, const std::string& title, const std::vector<PlotPanel>& panels,
                int columns = 1);

}  // namespace mbsopt
