// A rigid wheel on sand against measured single-wheel tests: Pavlov and
// Johnson's test bed (validate/data/pavlov_johnson_*.csv, their source and
// licence in the files). Calibration is kept apart from prediction: the
// pressure-sinkage law comes from the plate tests alone, the shear
// modulus K from one slip of the wheel tests; every other trial is
// predicted. The closed-form checks (the sim against Wong's integrals for
// this wheel and soil) are this experiment's pass or fail; the measured
// comparison is reported as residuals, in the notes, apart from them.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/soil_closed_forms.h"
#include "simpartner/validate/soil_rig.h"

namespace simpartner::validate {
namespace {

// The test bed (terramechanics/set_rover_params.m, set_soil_params.m).
constexpr double kTestBedRadius = 0.058, kTestBedWidth = 0.05;  // [m]
constexpr double kTestBedSpeed = 0.01;                     // [m/s]
constexpr double kFrictionAngle = 29.0;  // [deg], the sand's angle of repose, as the source gives it
// Plate points shallower than this are left out of the fit: there the
// pressure is a few hundred Pa, mostly the force sensor's zero.
constexpr double kFitFromSinkage = 0.002;  // [m]
// The slip whose drawbar pull calibrates K; every other slip is predicted.
constexpr double kCalibrationSlip = 0.23;

std::string DataFile(const Context& context, const std::string& name) {
  return (std::filesystem::path(context.models_dir).parent_path() / "validate" / "data" / name)
      .string();
}

// The rows of a CSV file of numbers: '#' lines are comments, the first
// other line names the columns.
std::vector<std::vector<double>> ReadNumbers(const std::string& path, size_t columns) {
  std::ifstream in(path);
  if (!in) throw Error(path + ": cannot open (the measured wheel data)");
  std::vector<std::vector<double>> rows;
  std::string line;
  bool header = true;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty() || line[0] == '#') continue;
    if (header) {
      header = false;
      continue;
    }
    std::vector<double> row;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) {
      size_t used = 0;
      double value = 0;
      try {
        value = std::stod(field, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != field.size() || !std::isfinite(value))
        throw Error(path + ":" + std::to_string(number) + ": '" + field + "' is not a number");
      row.push_back(value);
    }
    if (row.size() != columns)
      throw Error(path + ":" + std::to_string(number) + ": " + std::to_string(row.size()) +
                  " fields, not " + std::to_string(columns));
    rows.push_back(row);
  }
  return rows;
}

// Bekker's p = (k_c / b + k_phi) z^n fitted to the plate tests, b the
// plate's radius: a common n with one ln k per plate size (least squares
// on ln p), then k against 1 / b (least squares over the sizes).
struct PlateFit {
  double n = 0, k_c = 0, k_phi = 0;    // k_c, k_phi in Pa/m^(n+1), Pa/m^(n+2)
  std::map<double, double> rms_error;  // per diameter [m]: RMS of p_fit / p - 1
  int points = 0;
};

PlateFit FitPlates(const std::vector<std::vector<double>>& rows) {
  std::map<double, std::vector<std::pair<double, double>>> by_size;  // ln z, ln p
  for (const auto& r : rows)
    if (r[2] >= kFitFromSinkage && r[3] > 0) by_size[r[0]].push_back({std::log(r[2]), std::log(r[3])});
  PlateFit fit;
  double sxy = 0, sxx = 0;
  std::map<double, std::pair<double, double>> means;
  for (const auto& [d, points] : by_size) {
    double x = 0, y = 0;
    for (const auto& [lx, ly] : points) x += lx, y += ly;
    x /= points.size(), y /= points.size();
    means[d] = {x, y};
    for (const auto& [lx, ly] : points) sxy += (lx - x) * (ly - y), sxx += (lx - x) * (lx - x);
    fit.points += static_cast<int>(points.size());
  }
  fit.n = sxy / sxx;
  double su = 0, sk = 0, suu = 0, suk = 0;
  for (const auto& [d, m] : means) {
    const double u = 1.0 / (0.5 * d), k = std::exp(m.second - fit.n * m.first);
    su += u, sk += k, suu += u * u, suk += u * k;
  }
  const double count = static_cast<double>(means.size());
  fit.k_c = (count * suk - su * sk) / (count * suu - su * su);
  fit.k_phi = (sk - fit.k_c * su) / count;
  for (const auto& [d, points] : by_size) {
    double sum = 0;
    for (const auto& [lx, ly] : points) {
      const double p = (fit.k_c / (0.5 * d) + fit.k_phi) * std::exp(fit.n * lx);
      sum += std::pow(p / std::exp(ly) - 1, 2);
    }
    fit.rms_error[d] = std::sqrt(sum / points.size());
  }
  return fit;
}

// The wheel trials of one commanded slip: means, and the spread between
// trials (sample standard deviation).
struct SlipGroup {
  double slip = 0, load = 0, pull = 0, sinkage = 0;
  double pull_sd = 0, sinkage_sd = 0;
  int trials = 0;
};

std::vector<SlipGroup> GroupBySlip(const std::vector<std::vector<double>>& rows) {
  std::map<long, std::vector<const std::vector<double>*>> groups;  // slip in hundredths
  for (const auto& r : rows) groups[std::lround(r[0] * 100)].push_back(&r);
  std::vector<SlipGroup> out;
  for (const auto& [key, trials] : groups) {
    SlipGroup g;
    g.trials = static_cast<int>(trials.size());
    for (const auto* r : trials)
      g.slip += (*r)[0] / g.trials, g.pull += (*r)[1] / g.trials, g.load += (*r)[2] / g.trials,
          g.sinkage += (*r)[3] / g.trials;
    for (const auto* r : trials)
      g.pull_sd += std::pow((*r)[1] - g.pull, 2), g.sinkage_sd += std::pow((*r)[3] - g.sinkage, 2);
    const double dof = std::max(1, g.trials - 1);
    g.pull_sd = std::sqrt(g.pull_sd / dof), g.sinkage_sd = std::sqrt(g.sinkage_sd / dof);
    out.push_back(g);
  }
  return out;
}

// The sand as the closed forms and the world read it: Bekker's k for this
// wheel's width (k_c = 0, k_phi = k_c / b + k_phi: the plates give a
// negative k_c, which the soil library refuses, and the wheel has one
// width), c = 0 (dry sand), the angle of repose, K as calibrated; the
// unloading line as the library assumes for its sands (LETE sand's).
model::SoilParameters Sand(const PlateFit& fit, double shear_modulus) {
  model::SoilParameters p;
  p.n = fit.n;
  p.k_c = 0;
  p.k_phi = (fit.k_c / kTestBedWidth + fit.k_phi) / 1e3;
  p.cohesion = 0;
  p.friction_angle = kFrictionAngle;
  p.shear_modulus = shear_modulus;
  p.unloading_stiffness = 0;
  p.unloading_growth = 503000;
  return p;
}

// Wong's rigid wheel in this sand at `slip` under `load`.
struct WongWheel {
  double sinkage = 0, pull = 0;  // [m], [N]
};

WongWheel Wong(const model::SoilParameters& p, double slip, double load,
               int intervals = kSimpsonIntervals) {
  const double z = RollingSinkage(p, kTestBedRadius, kTestBedWidth, slip, load, 0.0, intervals);
  return {z, RollingWheel(p, kTestBedRadius, kTestBedWidth, z, slip, 0.0, intervals).pull};
}

// K such that Wong's pull at the calibration slip is the measured one
// (the pull falls as K grows): bisection in log K over 0.1 to 200 mm, to
// 1e-8 of K, on 2,000 intervals (the pull to 1e-6 N of 20,000's).
double CalibrateShearModulus(const PlateFit& fit, const SlipGroup& g) {
  double lo = std::log(1e-4), hi = std::log(0.2);
  for (int i = 0; i < 30; ++i) {
    const double mid = 0.5 * (lo + hi);
    (Wong(Sand(fit, std::exp(mid)), g.slip, g.load, 2000).pull > g.pull ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

std::string Overrides(const model::SoilParameters& p) {
  auto tag = [](const char* name, double value) {
    return std::string("<") + name + ">" + FormatNumber(value) + "</" + name + ">";
  };
  return tag("n", p.n) + tag("kc", p.k_c) + tag("kphi", p.k_phi) + tag("cohesion", p.cohesion) +
         tag("frictionAngle", p.friction_angle) + tag("shearModulus", p.shear_modulus) +
         tag("unloadingStiffness", p.unloading_stiffness) +
         tag("unloadingGrowth", p.unloading_growth) + tag("viscosity", 0);
}

std::string Signed(double v, int decimals) {
  return (v >= 0 ? "+" : "") + FormatFixed(v, decimals);
}

// One slip: the trials, the sim on the rig, and Wong's integrals where
// they apply (a driven or rolling wheel).
struct Compared {
  SlipGroup measured;
  RigRun sim;
  bool has_wong = false;
  WongWheel wong;
  bool calibrates = false;  // K was fitted at this slip
  // Rounded, and + 0.0 so that rolling's -0.001 reads "0.00", not "-0.00".
  double Slip() const { return std::round(100 * measured.slip) / 100 + 0.0; }
};

RigRun RunTrial(const Context& context, const model::SoilParameters& sand, const SlipGroup& g,
                std::string* not_applicable) {
  RigSetup setup;
  setup.soil = {"dry_sand", Overrides(sand)};
  setup.load = g.load;
  setup.slip = g.slip;
  setup.speed = kTestBedSpeed;
  setup.radius = kTestBedRadius;
  setup.width = kTestBedWidth;
  setup.wheel_mass = 1.0;
  setup.drive_seconds = context.quick ? 5.0 : 10.0;  // 5 to 10 cm of travel
  return RunRig(context, setup, not_applicable);
}

std::string Row(const Compared& c) {
  const SlipGroup& g = c.measured;
  const double sim_mm = 1000 * c.sim.sinkage[0];
  return "| " + FormatFixed(c.Slip(), 2) + (c.calibrates ? " (K's fit)" : "") + " | " +
         std::to_string(g.trials) + " | " + FormatFixed(g.load, 1) + " | " +
         FormatFixed(g.pull, 2) + " ± " + FormatFixed(g.pull_sd, 2) + " | " +
         FormatFixed(c.sim.pull, 2) + " | " + (c.has_wong ? FormatFixed(c.wong.pull, 2) : "-") +
         " | " + Signed(c.sim.pull - g.pull, 2) + " | " + FormatFixed(1000 * g.sinkage, 1) +
         " ± " + FormatFixed(1000 * g.sinkage_sd, 1) + " | " + FormatFixed(sim_mm, 1) + " | " +
         (c.has_wong ? FormatFixed(1000 * c.wong.sinkage, 1) : "-") + " | " +
         Signed(100 * (c.sim.sinkage[0] / g.sinkage - 1), 0) + " % |\n";
}

std::vector<Plot> Plots(const std::vector<Compared>& compared) {
  Series measured{"measured (Pavlov and Johnson)", {}, {}, "mark"};
  Series sim{"sim", {}, {}, "linespoints"}, wong{"Wong's integrals", {}, {}, "dashed"};
  Plot pull, sinkage;
  pull.series = sinkage.series = {measured, sim, wong};
  for (const Compared& c : compared) {
    const double x = c.measured.slip;
    auto add = [x](Series* s, double y) { s->x.push_back(x), s->y.push_back(y); };
    add(&pull.series[0], c.measured.pull);
    add(&pull.series[1], c.sim.pull);
    add(&sinkage.series[0], 1000 * c.measured.sinkage);
    add(&sinkage.series[1], 1000 * c.sim.sinkage[0]);
    if (c.has_wong) add(&pull.series[2], c.wong.pull), add(&sinkage.series[2], 1000 * c.wong.sinkage);
  }
  pull.file = "soil_measured_pull.png";
  pull.title = "Smooth wheel (r 58 mm, b 50 mm) on sand: drawbar pull";
  pull.xlabel = sinkage.xlabel = "slip";
  pull.ylabel = "drawbar pull [N]";
  sinkage.file = "soil_measured_sinkage.png";
  sinkage.title = "Smooth wheel on sand: sinkage";
  sinkage.ylabel = "sinkage [mm]";
  return {pull, sinkage};
}

std::string Notes(const PlateFit& fit, const model::SoilParameters& sand,
                  const std::string& table) {
  std::string plates;
  for (const auto& [d, rms] : fit.rms_error)
    plates += (plates.empty() ? "" : ", ") + FormatFixed(1000 * d, 0) + " mm " +
              FormatFixed(100 * rms, 1) + " %";
  return
      "Measured single-wheel tests: C. Pavlov and A. M. Johnson's test bed (Carnegie Mellon "
      "University), the data of github.com/robomechanics/3d-terramechanics at commit 55a6e92 as "
      "`validate/data/pavlov_johnson_*.csv` (their MIT licence and how each figure was read are "
      "in the files). A smooth rigid wheel, r 58 mm and b 50 mm, driven straight at 10 mm/s and "
      "free to sink under 18 to 26 N, on a sand the source names only by its bulk density "
      "(1,330 kg/m^3) and angle of repose (29 deg); three trials per slip.\n\n"
      "**Calibration, apart from the prediction.** Bekker's law from the plate tests alone (60, 80 "
      "and 100 mm plates, 18 runs, " + std::to_string(fit.points) +
      " points deeper than 2 mm; b = the plate's radius): n = " + FormatFixed(fit.n, 3) +
      ", k_c = " + FormatFixed(fit.k_c / 1e3, 0) + " kN/m^(n+1), k_phi = " +
      FormatFixed(fit.k_phi / 1e3, 0) + " kN/m^(n+2) (the pressure grows with the plate, so k_c "
      "is negative: the wheel takes k = k_c / b + k_phi = " + FormatFixed(sand.k_phi, 0) +
      " kN/m^(n+2) at its width); the fit's RMS error in pressure " + plates +
      ". c = 0 (dry sand), phi = 29 deg (the source's angle of repose; no shear test was made). "
      "K = " + FormatFixed(1000 * sand.shear_modulus, 1) +
      " mm, fitted by Wong's integrals to the drawbar pull at slip 0.23 alone. Every other figure "
      "below is a prediction.\n\n"
      "**Checks** (pass or fail): the sim on the rig against Wong's integrals for this wheel and "
      "sand at each driven slip and rolling (pull within 1 % of the load, sinkage within 0.5 %). "
      "The closed forms are for a driven wheel, so the braked trials have none.\n\n"
      "**Against the measurements** (residuals, reported, not checked):\n\n"
      "| slip | trials | load [N] | pull, measured [N] | sim | Wong | sim - measured | "
      "sinkage, measured [mm] | sim | Wong | sim / measured - 1 |\n"
      "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n" +
      table +
      "\n± is the spread between the trials. What the residuals say:\n\n"
      "1. Rolling (slip 0), the model's rolling resistance is near the measured one (1.6 against "
      "1.3 N), but it sinks the wheel a quarter less (10.9 against 14.4 mm), though the same "
      "sand's plates set its law. Bekker's plate law is known to under-predict the sinkage of "
      "wheels this small (a diameter effect: G. Meirion-Griffith and M. Spenko, \"Toward "
      "establishing a comprehensive pressure-sinkage model for small diameter wheels on "
      "deformable terrains\", and their Journal of Terramechanics paper of 2011).\n"
      "2. Driven, the measured sinkage grows with slip, from 14 mm rolling to 26 mm at slip 0.9: "
      "slip sinkage, the soil dug out from under the wheel and carried back (M. Lyasko, \"Slip "
      "sinkage effect in soil-vehicle mechanics\", J. Terramechanics 47(1), 2010). Wong's rigid "
      "wheel has none, so its sinkage stays near 11 mm and its pull rises to 5 N where the "
      "test bed's stays near 1 N, the deeper rut's resistance taking the thrust.\n"
      "3. Braked and locked, the measured resistance grows to 39 N, twice the load, as the wheel "
      "sinks to 50 mm, near its axle, and pushes a heap of sand ahead of it (bulldozing), which "
      "the model leaves out: it gives 13 N.\n\n"
      "These are the model's limits, not the engines': both meet Wong's integrals (the checks), "
      "and both give the same residuals.";
}

}  // namespace

ExperimentResult SoilMeasured(const Context& context) {
  ExperimentResult result;
  const PlateFit fit = FitPlates(ReadNumbers(DataFile(context, "pavlov_johnson_plates.csv"), 4));
  const std::vector<SlipGroup> groups =
      GroupBySlip(ReadNumbers(DataFile(context, "pavlov_johnson_smooth_wheel.csv"), 5));
  const auto calibration = std::find_if(groups.begin(), groups.end(), [](const SlipGroup& g) {
    return std::abs(g.slip - kCalibrationSlip) < 0.01;
  });
  if (calibration == groups.end()) throw Error("pavlov_johnson_smooth_wheel.csv: no trial at slip 0.23");
  const model::SoilParameters sand = Sand(fit, CalibrateShearModulus(fit, *calibration));
  std::vector<Compared> compared;
  std::string table;
  for (const SlipGroup& g : groups) {
    Compared c;
    c.measured = g;
    c.calibrates = &g == &*calibration;
    if (context.quick && std::abs(g.slip) > 0.01 && !c.calibrates) continue;
    c.sim = RunTrial(context, sand, g, &result.not_applicable);
    if (!result.not_applicable.empty()) return result;
    result.sim_seconds += c.sim.sim_seconds;
    c.has_wong = g.slip > -0.01;  // the closed forms are for a driven (or rolling) wheel
    if (c.has_wong) {
      c.wong = Wong(sand, std::max(0.0, g.slip), g.load);
      const std::string at = "slip " + FormatFixed(c.Slip(), 2);
      result.checks.push_back(Absolute("drawbar pull against Wong's, " + at, c.sim.pull,
                                       c.wong.pull, 0.01 * g.load, "N"));
      result.checks.push_back(Relative("sinkage against Wong's, " + at, 1000 * c.sim.sinkage[0],
                                       1000 * c.wong.sinkage, 0.005, "mm"));
    }
    table += Row(c);
    compared.push_back(c);
  }
  result.plots = Plots(compared);
  result.notes = Notes(fit, sand, table);
  return result;
}

}  // namespace simpartner::validate
