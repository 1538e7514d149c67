// The gnuplot scripts of plots: every series in a style of its own (so that
// lines with the same values still show), panels with one y range, and the
// window of an equal-axes plot (equal scale, shaped to the data, at least
// its minimum extent).
#include "simpartner/plot.h"

#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <set>
#include <string>
#include <vector>

namespace simpartner {
namespace {

// The tests read the scripts with plain string search, not std::regex:
// GCC 12 warns inside <regex> under the sanitizers, and warnings are
// errors (tests/models/broken_files_test.cpp says the same).

// Every text between `prefix` and the next `end`, in order.
std::vector<std::string> Between(const std::string& text, const std::string& prefix,
                                 const std::string& end) {
  std::vector<std::string> found;
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    const size_t begin = at + prefix.size();
    const size_t stop = text.find(end, begin);
    if (stop != std::string::npos) found.push_back(text.substr(begin, stop - begin));
  }
  return found;
}

// Every run of `allowed` characters right after `prefix` ("dt " and digits).
std::vector<std::string> After(const std::string& text, const std::string& prefix,
                               const std::string& allowed) {
  std::vector<std::string> found;
  for (size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at + 1)) {
    const size_t begin = at + prefix.size();
    const size_t stop = text.find_first_not_of(allowed, begin);
    found.push_back(text.substr(begin, (stop == std::string::npos ? text.size() : stop) - begin));
  }
  return found;
}

constexpr const char* kDigits = "0123456789";

// The style ("lines dt 2 lw 2.5 lc rgb '#...'") of each plot element: what
// stands between " with " and its title (or notitle).
std::vector<std::string> Styles(const std::string& script) {
  std::vector<std::string> styles;
  for (size_t at = script.find(" with "); at != std::string::npos;
       at = script.find(" with ", at + 1)) {
    const size_t begin = at + 6;
    const size_t stop = std::min(script.find(" title '", begin), script.find(" notitle", begin));
    if (stop != std::string::npos) styles.push_back(script.substr(begin, stop - begin));
  }
  return styles;
}

// n series of the same values: drawn over one another.
Plot SameLines(size_t n) {
  Plot plot;
  for (size_t i = 0; i < n; ++i)
    plot.series.push_back(
        Series{"wheel " + std::to_string(i), {0, 1, 2}, {650, 650, 650}, "lines"});
  return plot;
}

TEST(GnuplotScript, EverySeriesHasAStyleOfItsOwn) {
  for (size_t n : {2u, 4u, 8u, 12u}) {
    const std::vector<std::string> styles = Styles(GnuplotScript(SameLines(n), "data.txt"));
    ASSERT_EQ(styles.size(), n);
    EXPECT_EQ(std::set<std::string>(styles.begin(), styles.end()).size(), n) << n << " series";
  }
  // Up to five lines differ in their dash pattern as well as their
  // colour, and the first is the widest: one drawn over it leaves it seen.
  const std::string four = GnuplotScript(SameLines(4), "data.txt");
  const std::vector<std::string> dashes = After(four, "dt ", kDigits);
  const std::vector<std::string> colours = Between(four, "lc rgb '", "'");
  EXPECT_EQ(std::set<std::string>(dashes.begin(), dashes.end()).size(), 4u) << four;
  EXPECT_EQ(std::set<std::string>(colours.begin(), colours.end()).size(), 4u) << four;
  const std::vector<std::string> widths = After(four, "lw ", "0123456789.");
  ASSERT_EQ(widths.size(), 4u);
  EXPECT_GT(std::stod(widths[0]), std::stod(widths[3]));
}

TEST(GnuplotScript, PanelsDrawEachSeriesAloneOnTheYRangeOfAll) {
  Plot plot;
  plot.title = "wheel loads";
  plot.panels = true;
  for (int i = 0; i < 4; ++i)
    plot.series.push_back(
        Series{"Wheel" + std::to_string(i + 1), {0, 1}, {100.0 * i, 100.0 * i + 40}, "lines"});
  const std::string script = GnuplotScript(plot, "data.txt");
  EXPECT_NE(script.find("set multiplot layout 2,2 title 'wheel loads'"), std::string::npos)
      << script;
  // One plot command per panel, each of one data block, titled by its series.
  EXPECT_EQ(Between(script, "\nplot 'data.txt' index ", " ").size(), 4u) << script;
  EXPECT_EQ(Between(script, "index ", " using"), (std::vector<std::string>{"0", "1", "2", "3"}));
  EXPECT_EQ(Between(script, "set title '", "'"),
            (std::vector<std::string>{"Wheel1", "Wheel2", "Wheel3", "Wheel4"}));
  // The loads run from 0 to 340 N: 5 % more on each side, the same in every panel.
  EXPECT_EQ(Between(script, "set yrange [", "]"), std::vector<std::string>{"-17:357"})
      << script;
}

Plot Track(std::vector<double> x, std::vector<double> y, double min_extent) {
  Plot plot;
  plot.equal_axes = true;
  plot.min_extent = min_extent;
  plot.series.push_back(Series{"track", std::move(x), std::move(y), "lines"});
  return plot;
}

TEST(EqualAxesRanges, AStraightRunIsAWindowThreeToOneNotAStrip) {
  // 10 m along x with 1 cm of sideways wobble.
  const AxisRanges r = EqualAxesRanges(Track({0, 5, 10}, {0, 0.01, 0}, 1.0));
  EXPECT_DOUBLE_EQ(r.x_min, -0.5);  // 11 m: the run and 5 % on each side
  EXPECT_DOUBLE_EQ(r.x_max, 10.5);
  EXPECT_NEAR(r.y_max - r.y_min, 11.0 / 3, 1e-12);  // widened to a third of x
  EXPECT_NEAR(0.5 * (r.y_min + r.y_max), 0.005, 1e-12);
  const std::string script = GnuplotScript(Track({0, 5, 10}, {0, 0.01, 0}, 1.0), "data.txt");
  EXPECT_NE(script.find("set size ratio -1\nset xrange [-0.5:10.5]\n"), std::string::npos)
      << script;
}

TEST(EqualAxesRanges, AStillBodyIsADotInItsMinimumExtent) {
  const AxisRanges r = EqualAxesRanges(Track({2, 2}, {-3, -3}, 1.0));
  EXPECT_DOUBLE_EQ(r.x_min, 1.5);
  EXPECT_DOUBLE_EQ(r.x_max, 2.5);
  EXPECT_DOUBLE_EQ(r.y_min, -3.5);
  EXPECT_DOUBLE_EQ(r.y_max, -2.5);
  // Without a minimum extent a single point still gets a window.
  const AxisRanges bare = EqualAxesRanges(Track({2}, {-3}, 0.0));
  EXPECT_DOUBLE_EQ(bare.x_max - bare.x_min, 1.0);
  EXPECT_DOUBLE_EQ(bare.y_max - bare.y_min, 1.0);
}

TEST(EqualAxesRanges, ACircleKeepsItsShape) {
  // Radius 2 m around (1, 1), NaN (not logged) left out.
  const AxisRanges r =
      EqualAxesRanges(Track({3, 1, -1, 1, 3, std::nan("")}, {1, 3, 1, -1, 1, 100}, 1.0));
  EXPECT_DOUBLE_EQ(r.x_max - r.x_min, 4.4);
  EXPECT_DOUBLE_EQ(r.y_max - r.y_min, 4.4);
  EXPECT_DOUBLE_EQ(r.x_min, 1 - 2.2);
  EXPECT_DOUBLE_EQ(r.y_min, 1 - 2.2);
}

}  // namespace
}  // namespace simpartner
