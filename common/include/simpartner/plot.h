// Plots drawn with gnuplot, for the validation report and simpartner-query
// plot: series kept as data until drawn into a PNG (pngcairo) or, for a
// person at a display, into a window.
#pragma once

#include <string>
#include <vector>

namespace simpartner {

struct Series {
  std::string title;
  std::vector<double> x, y;
  // gnuplot style: "lines", "points", "linespoints", "boxes", "dashed"
  // (a dashed line, for analytic curves and targets), "mark" (a big point,
  // e.g. where a track starts). Each series of a
  // plot gets a colour and a dash pattern of its own, so that a line drawn
  // over another of the same values still shows.
  std::string style = "lines";
};

struct Plot {
  std::string file;            // PNG name inside the report directory, e.g. "free_fall.png"
  std::string title;
  std::string xlabel, ylabel;
  std::vector<Series> series;
  // Same scale on x and y (trajectories), in a window shaped to the data:
  // its sides at most kMaxEqualAxesAspect to one, each at least min_extent.
  bool equal_axes = false;
  double min_extent = 0;
  bool log_y = false;
  std::vector<std::string> xtics;  // labels for a bar chart (x = 0, 1, ...)
  bool y_from_zero = false;    // bars: the y axis starts at 0
  // One panel per series (same y range in each), for series that would
  // hide one another: two rows of panels side by side.
  bool panels = false;
};

inline constexpr double kMaxEqualAxesAspect = 3.0;

// The ranges of an equal_axes plot: around the data's middle, each side
// at least plot.min_extent (and a margin of 5 %), the shorter side widened
// to at least 1 / kMaxEqualAxesAspect of the longer.
struct AxisRanges {
  double x_min = 0, x_max = 0, y_min = 0, y_max = 0;
};
AxisRanges EqualAxesRanges(const Plot& plot);

// The gnuplot commands that draw `plot` from `data_file` (the series in
// its blocks, as DrawPlot writes them), without terminal and output.
std::string GnuplotScript(const Plot& plot, const std::string& data_file);

// Keeps at most max_points evenly spaced points of a series (always the
// first and the last) so that plot data stays small.
Series Thin(Series series, size_t max_points = 2000);

// Draws the plot into directory/plot.file with gnuplot (pngcairo, 900 x 540).
// Throws simpartner::Error naming the plot and gnuplot's output when
// gnuplot is missing or fails.
void DrawPlot(const Plot& plot, const std::string& directory);

// The same into the PNG file `png_path` (any directory, any name).
void DrawPlotPng(const Plot& plot, const std::string& png_path);

// The window terminals this gnuplot has, best first (qt, wxt, x11; none
// with Debian's gnuplot-nox).
std::vector<std::string> GnuplotWindowTerminals();

// Draws the plot in a window and returns when the person closes it. Throws
// Error when this gnuplot has no window terminal (gnuplot-nox), naming the
// packages that have one.
void ShowPlotWindow(const Plot& plot);

}  // namespace simpartner
