#include "simpartner/plot.h"

#include <unistd.h>

#include <chrono>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "simpartner/child_process.h"
#include "simpartner/diagnostic.h"

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

std::string StyleOf(const Series& s, size_t index) {
  const std::string colour = " lc " + std::to_string(index + 1);
  if (s.style == "dashed") return "lines dt 2 lw 2" + colour;
  if (s.style == "points") return "points pt 7 ps 0.6" + colour;
  if (s.style == "linespoints") return "linespoints pt 7 ps 0.8 lw 2" + colour;
  if (s.style == "boxes") return "boxes fs solid 0.6" + colour;
  return "lines lw 2" + colour;
}

// posix_spawn needs a path: the first gnuplot on PATH.
std::string FindProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path != nullptr ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / name;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return name;
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
    ChildProcess gnuplot({FindProgram("gnuplot"), script.string()}, log.string());
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

// The data file and the script after the terminal lines, `pause` at the end.
void WritePlotFiles(const Plot& plot, const fs::path& data, const fs::path& script,
                    const std::string& terminal, const std::string& pause) {
  {
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
  std::ofstream out(script);
  out << terminal << "set title " << Quote(plot.title) << " noenhanced\n"
      << "set xlabel " << Quote(plot.xlabel) << " noenhanced\n"
      << "set ylabel " << Quote(plot.ylabel) << " noenhanced\n"
      << "set grid\nset key outside bottom center horizontal noenhanced\n"
      << "set datafile missing 'nan'\n";
  if (plot.equal_axes) out << "set size ratio -1\n";
  if (plot.y_from_zero) out << "set yrange [0:*]\n";
  if (plot.log_y) out << "set logscale y\nset format y '10^{%T}'\n";
  if (!plot.xtics.empty()) {
    out << "set boxwidth 0.25\nset xtics (";
    for (size_t i = 0; i < plot.xtics.size(); ++i)
      out << (i ? ", " : "") << Quote(plot.xtics[i]) << " " << i;
    out << ")\nset xrange [-0.6:" << plot.xtics.size() - 0.4 << "]\n";
  }
  out << "plot ";
  bool first = true;
  for (size_t i = 0; i < plot.series.size(); ++i) {
    if (plot.series[i].x.empty()) continue;
    out << (first ? "" : ", \\\n     ") << Quote(data.string()) << " index " << i
        << " using 1:2 with " << StyleOf(plot.series[i], i) << " title "
        << Quote(plot.series[i].title);
    first = false;
  }
  out << "\n" << pause;
}

}  // namespace

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
                 "set terminal pngcairo size 900,540 enhanced font 'DejaVu Sans,11'\n"
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
                 "set terminal " + terminals.front() + " size 900,540 enhanced title " +
                     Quote(plot.title) + "\n",
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
