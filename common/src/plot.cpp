#include "simpartner/plot.h"

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

#include "simpartner/child_process.h"
#include "simpartner/diagnostic.h"
#include "simpartner/programs.h"

namespace simpartner {
namespace {

namespace fs = std::filesystem;

// gnuplot's string syntax: single quotes, a quote written twice.
std::string Quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else out += c;
  }
  return out + "'";
}

// Okabe and Ito's colours (told apart by the colour-blind too), and
// gnuplot's dash patterns: solid, dashed, dash-dot, dash-dot-dot, dotted.
constexpr const char* kColours[] = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                    "#E69F00", "#56B4E9", "#000000", "#F0E442"};
constexpr int kDashes[] = {1, 2, 4, 5, 3};
constexpr int kPointTypes[] = {7, 5, 9, 11, 13};

// The style of the index-th series: its own colour and, for lines, its own
// dash pattern and a width that narrows from the first, so that a line
// drawn over another with the same values leaves the one below visible.
std::string StyleOf(const Series& s, size_t index) {
  const std::string colour = std::string(" lc rgb '") + kColours[index % std::size(kColours)] + "'";
  const std::string point = " pt " + std::to_string(kPointTypes[index % std::size(kPointTypes)]);
  if (s.style == "dashed") return "lines dt 2 lw 2" + colour;
  if (s.style == "points") return "points" + point + " ps 0.6" + colour;
  if (s.style == "mark") return "points" + point + " ps 1.6" + colour;
  if (s.style == "linespoints") return "linespoints" + point + " ps 0.8 lw 2" + colour;
  if (s.style == "boxes") return "boxes fs solid 0.6" + colour;
  const double width = 3.0 - 0.5 * static_cast<double>(std::min<size_t>(index, 3));
  std::ostringstream style;
  style << "lines dt " << kDashes[index % std::size(kDashes)] << " lw " << width << colour;
  return style.str();
}

// posix_spawn needs a path: the first gnuplot on PATH, else the bare name,
// which then cannot start (RunGnuplot says what to install).
std::string GnuplotProgram() {
  const std::string found = ProgramOnPath("gnuplot");
  return found.empty() ? "gnuplot" : found;
}

// A scratch directory for gnuplot's data, script and log, removed at the end.
class Scratch {
 public:
  explicit Scratch(const std::string& what) {
    char dir_template[] = "/tmp/simpartner-plot-XXXXXX";
    const char* made = mkdtemp(dir_template);
    if (made == nullptr) throw Error(what + ": cannot create a temporary directory");
    path_ = made;
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

// Runs gnuplot on `script`; throws Error naming `what` and gnuplot's output
// when it cannot start or fails.
void RunGnuplot(const fs::path& script, const fs::path& log, const std::string& what,
                std::chrono::milliseconds timeout) {
  int status = -1;
  try {
    ChildProcess gnuplot({GnuplotProgram(), script.string()}, log.string());
    status = gnuplot.Wait(timeout).value_or(-1);
  } catch (const std::exception& e) {
    throw Error(what + ": cannot run gnuplot (install gnuplot-x11, or gnuplot-nox for PNGs only): " +
                e.what());
  }
  if (status != 0) {
    std::ifstream in(log);
    std::ostringstream message;
    message << in.rdbuf();
    throw Error(what + ": gnuplot failed (status " + std::to_string(status) + "): " + message.str());
  }
}

// The series' points (thinned), one gnuplot data block each.
void WriteData(const Plot& plot, const fs::path& data) {
  std::ofstream out(data);
  out.precision(12);
  for (const Series& s : plot.series) {
    const Series thin = Thin(s);
    for (size_t i = 0; i < thin.x.size(); ++i) {
      if (std::isfinite(thin.x[i]) && std::isfinite(thin.y[i]))
        out << thin.x[i] << ' ' << thin.y[i] << '\n';
    }
    out << "\n\n";  // next gnuplot index
  }
}

// The smallest and largest finite y of all series (0, 0 with none).
std::pair<double, double> YBounds(const Plot& plot) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Series& s : plot.series)
    for (size_t i = 0; i < s.y.size() && i < s.x.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        lo = std::min(lo, s.y[i]);
        hi = std::max(hi, s.y[i]);
      }
  return lo <= hi ? std::make_pair(lo, hi) : std::make_pair(0.0, 0.0);
}

size_t PanelRows(const Plot& plot) { return (plot.series.size() + 1) / 2; }

// 900 x 540 pixels, taller for more than two rows of panels.
std::string CanvasSize(const Plot& plot) {
  const size_t rows = plot.panels ? PanelRows(plot) : 1;
  return "900," + std::to_string(std::max<size_t>(540, 270 * rows));
}

void WriteAxes(const Plot& plot, std::ostream& out) {
  if (plot.equal_axes) {
    const AxisRanges r = EqualAxesRanges(plot);
    out << "set size ratio -1\nset xrange [" << r.x_min << ":" << r.x_max << "]\nset yrange ["
        << r.y_min << ":" << r.y_max << "]\n";
  }
  if (plot.y_from_zero) out << "set yrange [0:*]\n";
  if (plot.log_y) out << "set logscale y\nset format y '10^{%T}'\n";
  if (!plot.xtics.empty()) {
    out << "set boxwidth 0.25\nset xtics (";
    for (size_t i = 0; i < plot.xtics.size(); ++i)
      out << (i ? ", " : "") << Quote(plot.xtics[i]) << " " << i;
    out << ")\nset xrange [-0.6:" << plot.xtics.size() - 0.4 << "]\n";
  }
}

// One series as a plot element: "'data' index i using 1:2 with ... title ...".
std::string Element(const Plot& plot, size_t i, const std::string& data_file, bool titled) {
  return Quote(data_file) + " index " + std::to_string(i) + " using 1:2 with " +
         StyleOf(plot.series[i], i) + (titled ? " title " + Quote(plot.series[i].title) : " notitle");
}

// Two panels a row, each titled by its series, all with the y range of all.
void WritePanels(const Plot& plot, const std::string& data_file, std::ostream& out) {
  auto [lo, hi] = YBounds(plot);
  const double margin = hi > lo ? 0.05 * (hi - lo) : 1.0;
  out << "set yrange [" << lo - margin << ":" << hi + margin << "]\n"
      << "set multiplot layout " << PanelRows(plot) << "," << (plot.series.size() > 1 ? 2 : 1)
      << " title " << Quote(plot.title) << " noenhanced\n";
  for (size_t i = 0; i < plot.series.size(); ++i)
    out << "set title " << Quote(plot.series[i].title) << " noenhanced\nplot "
        << (plot.series[i].x.empty() ? "NaN notitle" : Element(plot, i, data_file, false)) << "\n";
  out << "unset multiplot\n";
}

// The data file and the script after the terminal lines, `pause` at the end.
void WritePlotFiles(const Plot& plot, const fs::path& data, const fs::path& script,
                    const std::string& terminal, const std::string& pause) {
  WriteData(plot, data);
  std::ofstream(script) << terminal << GnuplotScript(plot, data.string()) << pause;
}

}  // namespace

AxisRanges EqualAxesRanges(const Plot& plot) {
  double x_lo = std::numeric_limits<double>::infinity(), x_hi = -x_lo, y_lo = x_lo, y_hi = -x_lo;
  for (const Series& s : plot.series)
    for (size_t i = 0; i < s.x.size() && i < s.y.size(); ++i)
      if (std::isfinite(s.x[i]) && std::isfinite(s.y[i])) {
        x_lo = std::min(x_lo, s.x[i]);
        x_hi = std::max(x_hi, s.x[i]);
        y_lo = std::min(y_lo, s.y[i]);
        y_hi = std::max(y_hi, s.y[i]);
      }
  if (x_lo > x_hi) x_lo = x_hi = y_lo = y_hi = 0;  // nothing to draw
  double dx = std::max(1.1 * (x_hi - x_lo), plot.min_extent);
  double dy = std::max(1.1 * (y_hi - y_lo), plot.min_extent);
  if (dx <= 0 && dy <= 0) dx = dy = 1;  // one point
  dx = std::max(dx, dy / kMaxEqualAxesAspect);
  dy = std::max(dy, dx / kMaxEqualAxesAspect);
  const double cx = 0.5 * (x_lo + x_hi), cy = 0.5 * (y_lo + y_hi);
  return {cx - 0.5 * dx, cx + 0.5 * dx, cy - 0.5 * dy, cy + 0.5 * dy};
}

std::string GnuplotScript(const Plot& plot, const std::string& data_file) {
  std::ostringstream out;
  out.precision(12);
  if (!plot.panels) out << "set title " << Quote(plot.title) << " noenhanced\n";
  out << "set xlabel " << Quote(plot.xlabel) << " noenhanced\n"
      << "set ylabel " << Quote(plot.ylabel) << " noenhanced\n"
      << "set grid\nset key outside bottom center horizontal noenhanced\n"
      << "set datafile missing 'nan'\n";
  WriteAxes(plot, out);
  if (plot.panels) {
    WritePanels(plot, data_file, out);
    return out.str();
  }
  out << "plot ";
  bool first = true;
  for (size_t i = 0; i < plot.series.size(); ++i) {
    if (plot.series[i].x.empty()) continue;
    out << (first ? "" : ", \\\n     ") << Element(plot, i, data_file, true);
    first = false;
  }
  out << "\n";
  return out.str();
}

Series Thin(Series series, size_t max_points) {
  const size_t n = series.x.size();
  if (n <= max_points || max_points < 2) return series;
  Series out;
  out.title = series.title;
  out.style = series.style;
  for (size_t k = 0; k < max_points; ++k) {
    const size_t i = (k * (n - 1)) / (max_points - 1);
    out.x.push_back(series.x[i]);
    out.y.push_back(series.y[i]);
  }
  return out;
}

void DrawPlot(const Plot& plot, const std::string& directory) {
  const fs::path png = fs::absolute(fs::path(directory) / plot.file);
  const Scratch scratch("plot " + plot.file);
  WritePlotFiles(plot, scratch.path() / "data.txt", scratch.path() / "plot.gp",
                 "set terminal pngcairo size " + CanvasSize(plot) + " enhanced font 'DejaVu Sans,11'\n"
                 "set output " + Quote(png.string()) + "\n",
                 "");
  RunGnuplot(scratch.path() / "plot.gp", scratch.path() / "gnuplot.log", "plot " + plot.file,
             std::chrono::seconds(60));
}

void DrawPlotPng(const Plot& plot, const std::string& png_path) {
  const fs::path path(png_path);
  Plot named = plot;
  named.file = path.filename().string();
  DrawPlot(named, path.has_parent_path() ? path.parent_path().string() : ".");
}

std::vector<std::string> GnuplotWindowTerminals() {
  const Scratch scratch("gnuplot terminals");
  const fs::path script = scratch.path() / "terminals.gp";
  const fs::path log = scratch.path() / "gnuplot.log";
  std::ofstream(script) << "print GPVAL_TERMINALS\n";
  RunGnuplot(script, log, "gnuplot terminals", std::chrono::seconds(20));
  std::ifstream in(log);
  std::vector<std::string> available, out;
  std::string word;
  while (in >> word) available.push_back(word);
  for (const char* wanted : {"qt", "wxt", "x11"}) {
    for (const std::string& a : available)
      if (a == wanted) out.push_back(a);
  }
  return out;
}

void ShowPlotWindow(const Plot& plot) {
  const std::vector<std::string> terminals = GnuplotWindowTerminals();
  if (terminals.empty())
    throw Error("plot '" + plot.title +
                "': this gnuplot has no window terminal (Debian's gnuplot-nox draws files only); "
                "install gnuplot-x11 or gnuplot-qt for a window, or write a PNG with -o FILE.png");
  const Scratch scratch("plot " + plot.title);
  // The window is titled like the plot, so that it can be told apart (and
  // found by a test). `pause mouse close` keeps gnuplot, and with it the
  // zoom and the mouse readout, until the window is closed.
  WritePlotFiles(plot, scratch.path() / "data.txt", scratch.path() / "plot.gp",
                 "set terminal " + terminals.front() + " size " + CanvasSize(plot) +
                     " enhanced title " + Quote(plot.title) + "\n",
                 "pause mouse close\n");
  try {
    RunGnuplot(scratch.path() / "plot.gp", scratch.path() / "gnuplot.log", "plot " + plot.title,
               std::chrono::hours(24 * 365));
  } catch (const Error& e) {
    const char* display = std::getenv("DISPLAY");
    std::string message = e.what();
    while (!message.empty() && std::isspace(static_cast<unsigned char>(message.back()))) message.pop_back();
    throw Error(message + "\n(no window could be opened on DISPLAY=" + (display != nullptr ? display : "") +
                "; write a PNG with -o FILE.png instead)");
  }
}

}  // namespace simpartner
