#include "mbsopt/io/gnuplot.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "mbsopt/io/atomic_file.hpp"

namespace mbsopt {

namespace {

/// The series' line types: Okabe and Ito's colour-blind-safe palette without its yellow, which reads
/// badly on white (black, then orange, sky blue, bluish green, blue, vermillion, reddish purple,
/// grey), solid for the first eight series and dashed for the next eight.
constexpr const char* kLineTypes =
    "set linetype 1 lc rgb '#000000' lw 1.5\nset linetype 2 lc rgb '#E69F00' lw 1.5\n"
    "set linetype 3 lc rgb '#56B4E9' lw 1.5\nset linetype 4 lc rgb '#009E73' lw 1.5\n"
    "set linetype 5 lc rgb '#0072B2' lw 1.5\nset linetype 6 lc rgb '#D55E00' lw 1.5\n"
    "set linetype 7 lc rgb '#CC79A7' lw 1.5\nset linetype 8 lc rgb '#999999' lw 1.5\n"
    "set linetype 9 lc rgb '#000000' lw 1.5 dt 2\nset linetype 10 lc rgb '#E69F00' lw 1.5 dt 2\n"
    "set linetype 11 lc rgb '#56B4E9' lw 1.5 dt 2\nset linetype 12 lc rgb '#009E73' lw 1.5 dt 2\n"
    "set linetype 13 lc rgb '#0072B2' lw 1.5 dt 2\nset linetype 14 lc rgb '#D55E00' lw 1.5 dt 2\n"
    "set linetype 15 lc rgb '#CC79A7' lw 1.5 dt 2\nset linetype 16 lc rgb '#999999' lw 1.5 dt 2\n"
    "set linetype cycle 16\n";

/// gnuplot's own quoting: single quotes, with ' doubled.
std::string quoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

/// The shell's quoting: single quotes, with ' as '\''.
std::string shellQuoted(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

}  // namespace

bool plotPanels(const std::string& stem, const std::string& title, const std::vector<PlotPanel>& panels, int columns) {
  const std::size_t width = static_cast<std::size_t>(columns), rows = (panels.size() + width - 1) / width;
  const std::string data = stem + ".dat", script = stem + ".gp", image = stem + ".png";
  // Data: every series a block of "x y" lines, blocks separated by two blank lines (gnuplot's index).
  writeAtomically(data, [&](std::ostream& out) {
    out.precision(17);
    for (const PlotPanel& panel : panels)
      for (const PlotSeries& series : panel.series) {
        out << "# " << (series.title.empty() && series.marks_only ? "(marks)" : series.title) << '\n';
        for (const auto& [x, y] : series.points) out << x << ' ' << y << '\n';
        if (series.points.empty()) out << "NaN NaN\n";  // a block all the same: gnuplot's index counts only blocks with lines
        out << "\n\n";
      }
  });
  writeAtomically(script, [&](std::ostream& out) {
    out << "set terminal pngcairo noenhanced size " << (width == 1 ? 1000 : 650 * width) << "," << 380 * rows
        << " font ',10'\n"
        << "set output " << quoted(std::filesystem::path(image).filename().string()) << '\n'
        << "set multiplot layout " << rows << "," << width << " rowsfirst title " << quoted(title) << '\n'
        << (width == 1 ? "set key outside right\n" : "set key top right font ',8'\n") << "set grid\n"
        << kLineTypes;
    int block = 0;
    for (const PlotPanel& panel : panels) {
      out << "set title " << quoted(panel.title) << "\nset xlabel " << quoted(panel.xlabel) << "\nset ylabel "
          << quoted(panel.ylabel) << '\n'
          << (panel.log_y ? "set logscale y\nset format y \"%.0e\"\n" : "unset logscale y\nset format y\n")
          << (panel.log_x ? "set logscale x\nset format x \"%.0e\"\n" : "unset logscale x\nset format x\n");
      out << "set yrange [";
      if (std::isnan(panel.y_min)) out << '*';
      else out << panel.y_min;
      out << ':';
      if (std::isnan(panel.y_max)) out << '*';
      else out << panel.y_max;
      out << "]\n";
      // An empty series is left out of the plot, and each series keeps its line type: the n-th of
      // every panel has the same colour whichever are empty.
      std::string plots;
      for (std::size_t s = 0; s < panel.series.size(); ++s, ++block) {
        const PlotSeries& series = panel.series[s];
        if (series.points.empty()) continue;
        const char* style = series.marks_only ? " with points pt 6 ps 2" : panel.markers ? " with linespoints" : " with lines";
        plots += (plots.empty() ? "" : ", ") + quoted(std::filesystem::path(data).filename().string()) + " index " +
                 std::to_string(block) + style + " lt " +
                 std::to_string(series.line_type > 0 ? series.line_type : static_cast<int>(s) + 1) +
                 (series.title.empty() ? std::string(" notitle") : " title " + quoted(series.title));
      }
      if (plots.empty()) out << "set label 1 'no data' at graph 0.5, 0.5 center\nplot [0:1] NaN notitle\nunset label 1\n";
      else out << "plot " << plots << '\n';
    }
    out << "unset multiplot\n";
  });
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0) {
    std::cerr << "mbsopt: warning: gnuplot is not installed; wrote " << data << " and " << script << " only\n";
    return false;
  }
  const std::filesystem::path directory = std::filesystem::path(script).parent_path();
  const std::string command = "cd " + shellQuoted(directory.empty() ? "." : directory.string()) + " && gnuplot " +
                              shellQuoted(std::filesystem::path(script).filename().string());
  if (std::system(command.c_str()) != 0) {
    std::cerr << "mbsopt: warning: gnuplot failed on " << script << '\n';
    return false;
  }
  return true;
}

}  // namespace mbsopt
