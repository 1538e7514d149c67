// gen1 experiments: the two circle runs and, on slippery ground, the
// skidding wheels, the caterpillar gait and rolling walking.
#include <algorithm>
#include <cmath>
#include <string>

#include "simpartner/validate/analysis.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

std::string Num(double v) { return FormatNumber(v); }

constexpr double kWheelRadius = 0.235;  // SPEC 7
constexpr double kAxleDistance = 0.6;   // SPEC 7: a, Turner joint to each axle

struct CircleRunResult {
  CircleFit front, rear;            // axle midpoints over the measured part
  Series front_path, rear_path;     // x, z over the whole run
  Series radius_error;              // rear axle: distance to the fitted centre - r, vs t
  double front_load = 0.0, rear_load = 0.0;  // mean vertical load per wheel [N]
  double mass = 0.0;
  double sim_seconds = 0.0;
  double Radius() const { return (front.radius + rear.radius) / 2.0; }
  double WorstDeviation() const { return std::max(front.worst_deviation, rear.worst_deviation); }
};

// gen1 on flat ground, playing a shipped sequence (sequences/): steer to
// alpha with TurnerMotor while standing, then drive the left (inner) wheels
// at v_left and the right ones at v_right [m/s] from t = 2 s; the circles
// are fitted to the axle midpoints once the turn is steady.
CircleRunResult RunCircle(const Context& context, double mu, double settle, double duration,
                          const std::string& sequence) {
  Parameters params = context.params;
  params.contactMu = mu;  // gen1_flat.xml's ground takes its friction from contactMu
  SimRun run(context, "gen1_flat.xml", params);
  const int wheel[4] = {run.Body("Wheel1"), run.Body("Wheel2"), run.Body("Wheel3"),
                        run.Body("Wheel4")};
  constexpr double kSteerTime = 2.0;
  run.PlaySequence(sequence);
  CircleRunResult out;
  for (const sim::FlatBody& b : run.sim().flat().bodies) out.mass += b.source->mass;
  std::vector<Eigen::Vector2d> front, rear;
  std::vector<double> times;
  double front_load = 0.0, rear_load = 0.0;
  const int every = std::max<int>(1, static_cast<int>(std::lround(0.01 / run.dt())));
  run.RunUntil(kSteerTime + settle + duration, [&] {
    if (run.sim().step() % every != 0) return;
    const double t = run.time();
    const Eigen::Vector3d f = (run.Position(wheel[0]) + run.Position(wheel[1])) / 2.0;
    const Eigen::Vector3d r = (run.Position(wheel[2]) + run.Position(wheel[3])) / 2.0;
    out.front_path.x.push_back(f.x());
    out.front_path.y.push_back(f.z());
    out.rear_path.x.push_back(r.x());
    out.rear_path.y.push_back(r.z());
    if (t < kSteerTime + settle) return;
    front.emplace_back(f.x(), f.z());
    rear.emplace_back(r.x(), r.z());
    times.push_back(t);
    front_load += (run.VerticalContactForce(wheel[0]) + run.VerticalContactForce(wheel[1])) / 2.0;
    rear_load += (run.VerticalContactForce(wheel[2]) + run.VerticalContactForce(wheel[3])) / 2.0;
  });
  out.sim_seconds = run.time();
  out.front = FitCircle(front);
  out.rear = FitCircle(rear);
  out.front_load = front_load / std::max<size_t>(1, times.size());
  out.rear_load = rear_load / std::max<size_t>(1, times.size());
  out.radius_error.title = "rear axle: distance to the fitted centre - r";
  for (size_t i = 0; i < rear.size(); ++i) {
    out.radius_error.x.push_back(times[i]);
    out.radius_error.y.push_back(((rear[i] - out.rear.centre).norm() - out.rear.radius) * 1000.0);
  }
  return out;
}

Series CirclePoints(const Eigen::Vector2d& centre, double radius, const std::string& title) {
  Series s{title, {}, {}, "dashed"};
  for (int k = 0; k <= 360; ++k) {
    const double a = 2.0 * M_PI * k / 360.0;
    s.x.push_back(centre.x() + radius * std::cos(a));
    s.y.push_back(centre.y() + radius * std::sin(a));
  }
  return s;
}

// The radius an ideal slipping vehicle with this run's loads would turn at.
double CoulombRadius(const CircleRunResult& run, double mu, double alpha, double v_left,
                     double v_right) {
  SkidSteerVehicle v;
  v.alpha = alpha;
  v.v_left = v_left;
  v.v_right = v_right;
  v.axle = kAxleDistance;
  v.half_track = 0.3;
  v.mass = run.mass;
  v.mu = mu;
  v.front_load = run.front_load;
  v.rear_load = run.rear_load;
  return SkidSteerRadius(v);
}

}  // namespace

ExperimentResult CircleEqualSpeeds(const Context& context) {
  ExperimentResult result;
  constexpr double kAlpha = 0.2972;
  constexpr double kSpeed = 1.0;  // [m/s] every wheel
  const double kinematic = kAxleDistance / std::tan(kAlpha / 2.0);
  // One lap (26 s at ~4.7 m and 1 m/s) after the turn has settled.
  const double settle = context.quick ? 3.0 : 8.0, duration = context.quick ? 8.0 : 30.0;
  Plot paths;
  paths.file = "circle_equal.png";
  paths.title = "gen1, alpha 0.2972 rad, equal wheel speeds: axle-midpoint paths";
  paths.xlabel = "x [m]";
  paths.ylabel = "z [m]";
  paths.equal_axes = true;
  Plot errors;
  errors.file = "circle_equal_error.png";
  errors.title = "gen1, alpha 0.2972 rad, equal speeds: distance from the fitted circle";
  errors.xlabel = "t [s]";
  errors.ylabel = "rear axle midpoint: distance to centre - r [mm]";
  std::string figures;
  for (const double mu : {0.5, 1.0}) {
    const CircleRunResult run = RunCircle(context, mu, settle, duration,
                                          "gen1_circle_equal_speeds.xml");
    result.sim_seconds += run.sim_seconds;
    result.checks.push_back(Relative("radius, mu " + Num(mu) + " (axle midpoints)", run.Radius(),
                                     kinematic, 0.10, "m"));
    const double coulomb = CoulombRadius(run, mu, kAlpha, kSpeed, kSpeed);
    figures += "| " + Num(mu) + " | " + Num(run.front.radius) + " | " + Num(run.rear.radius) +
               " | " + Num(run.WorstDeviation() * 1000.0) + " | " + Num(coulomb) + " |\n";
    Series front = run.front_path, rear = run.rear_path;
    front.title = "front axle, mu " + Num(mu);
    rear.title = "rear axle, mu " + Num(mu);
    paths.series.push_back(front);
    paths.series.push_back(rear);
    Series error = run.radius_error;
    error.title = "mu " + Num(mu);
    errors.series.push_back(error);
    if (mu == 1.0)
      paths.series.push_back(CirclePoints(run.rear.centre, kinematic,
                                          "r = a cot(alpha/2) = " + Num(kinematic) + " m"));
  }
  result.plots = {paths, errors};
  result.notes =
      "gen1 on flat ground (`gen1_flat.xml`, ground friction from `contactMu`): `TurnerMotor` "
      "steers to alpha = 0.2972 rad (P 100, I 100), then at t = 2 s all four wheels turn at "
      "1 m/s / 0.235 m (1000 N m motors). Circles are fitted (least squares) to the paths of "
      "both axle midpoints over " + Num(duration) + " s after " + Num(settle) +
      " s of settling; r is the mean of the two.\n\n"
      "| mu | front axle r [m] | rear axle r [m] | worst deviation [mm] | ideal slipping vehicle "
      "[m] |\n|---|---|---|---|---|\n" + figures +
      "\n**Why the target is physically wrong.** r = a cot(alpha/2) = " + Num(kinematic) +
      " m is the radius of a vehicle whose wheels roll without slipping. On that circle the "
      "outer wheels travel (r + 0.3) / (r - 0.3) = 1.16 times as far as the inner ones, so with "
      "equal wheel speeds every wheel must slip, and the radius is set by the balance of the "
      "friction forces, not by the steering geometry. The last column solves that balance for "
      "an ideal rigid vehicle with the run's wheel loads, point wheels and isotropic Coulomb "
      "friction (`SkidSteerRadius` in validate_lib): about 4.9 m, 22 % above the kinematic "
      "radius, independent of mu. Ours lies between (ODE's friction pyramid holds a little "
      "more sideways than a Coulomb cone, and each cylinder wheel touches at two points); the "
      "original's 4.30 m is not a physical answer either. No tolerance around 4.01 m is "
      "right for this run; the check keeps the team's 10 % and fails.";
  return result;
}

ExperimentResult CircleDifferentialSpeeds(const Context& context) {
  ExperimentResult result;
  constexpr double kAlpha = 0.2;
  const double kinematic = kAxleDistance / std::tan(kAlpha / 2.0);
  const double settle = context.quick ? 3.0 : 8.0, duration = context.quick ? 8.0 : 38.0;
  // Outer wheels at the speed that matches the steering: (r + t) / (r - t).
  const double matched = (kinematic + 0.3) / (kinematic - 0.3);
  const CircleRunResult run = RunCircle(context, 1.0, settle, duration,
                                            "gen1_circle_differential.xml");
  const CircleRunResult exact = RunCircle(context, 1.0, settle, duration,
                                          "gen1_circle_matched.xml");
  result.sim_seconds = run.sim_seconds + exact.sim_seconds;
  result.checks.push_back(Relative("radius, 1.00 / 1.10 m/s (axle midpoints)", run.Radius(),
                                   kinematic, 0.0025, "m"));
  result.checks.push_back(Absolute("worst deviation from the fitted circle, 1.00 / 1.10 m/s",
                                   run.WorstDeviation(), 0.0, 0.001, "m"));
  result.checks.push_back(Relative("radius, 1.00 / " + Num(matched) + " m/s (matched)",
                                   exact.Radius(), kinematic, 0.0025, "m"));
  result.checks.push_back(Absolute("worst deviation from the fitted circle, matched speeds",
                                   exact.WorstDeviation(), 0.0, 0.001, "m"));
  const double coulomb = CoulombRadius(run, 1.0, kAlpha, 1.00, 1.10);
  Plot paths;
  paths.file = "circle_differential.png";
  paths.title = "gen1, alpha 0.2 rad, inner 1.00 / outer 1.10 m/s: axle-midpoint paths";
  paths.xlabel = "x [m]";
  paths.ylabel = "z [m]";
  paths.equal_axes = true;
  Series front = run.front_path, rear = run.rear_path;
  front.title = "front axle";
  rear.title = "rear axle";
  paths.series = {front, rear,
                  CirclePoints(run.rear.centre, run.rear.radius, "fitted, r = " + Num(run.Radius()) + " m"),
                  CirclePoints(run.rear.centre, kinematic, "r = a cot(alpha/2) = " + Num(kinematic) + " m")};
  Plot errors;
  errors.file = "circle_differential_error.png";
  errors.title = "gen1, alpha 0.2 rad: distance of the rear axle midpoint from the fitted circle";
  errors.xlabel = "t [s]";
  errors.ylabel = "distance to centre - r [mm]";
  Series e1 = run.radius_error, e2 = exact.radius_error;
  e1.title = "1.00 / 1.10 m/s";
  e2.title = "1.00 / " + Num(matched) + " m/s (matched)";
  errors.series = {e1, e2};
  result.plots = {paths, errors};
  result.notes =
      "As the circle above, steering alpha = 0.2 rad, the inner (left) wheels at 1.00 m/s and "
      "the outer at 1.10 m/s; circles fitted over " + Num(duration) + " s (about one lap) after " +
      Num(settle) + " s of settling. r = " + Num(run.Radius()) + " m (front axle " +
      Num(run.front.radius) + ", rear " + Num(run.rear.radius) + "), " +
      FormatFixed((run.Radius() / kinematic - 1.0) * 100.0, 2) + " % above a cot(alpha/2) = " +
      Num(kinematic) + " m; circular within " + Num(run.WorstDeviation() * 1000.0) + " mm.\n\n"
      "**Why the 0.25 % target is physically wrong for 1.00 / 1.10 m/s.** Rolling without slip "
      "on the steering's circle needs the outer wheels at (r + 0.3) / (r - 0.3) = " +
      Num(matched) + " times the inner ones' speed; 1.10 asks for a circle of 6.3 m. The "
      "wheels must slip, and the radius falls between the two, where the friction forces "
      "balance: an ideal rigid vehicle with isotropic Coulomb friction and the run's wheel "
      "loads turns at " + Num(coulomb) + " m (+" +
      FormatFixed((coulomb / kinematic - 1.0) * 100.0, 2) + " %). Our " + Num(run.Radius()) + " m is as close to that as the friction model allows. "
      "The same run with the outer wheels at the matched " + Num(matched) +
      " m/s is the experiment the formula describes: it gives " + Num(exact.Radius()) +
      " m, circular within " + Num(exact.WorstDeviation() * 1000.0) + " mm.";
  return result;
}

// ---------------------------------------------------------------- gaits
namespace {

// A statically stable gait of the 18 kg gen1, played from its shipped
// sequence (sequences/make_sequences.py writes the leg targets, computed
// from the legs' geometry, at 50 Hz, and holds the standing feet's wheels
// at each phase change). The sequence starts the first cycle at t = 1 s.
struct GaitSequence {
  std::string file;
  int cycles = 0;
  double cycle_time = 0.0;  // [s]
};

constexpr double kGaitStart = 1.0;  // [s] the first cycle's start in the files

struct GaitRun {
  Series x;
  double speed = 0.0;   // over the whole cycles after the first
  double sim_seconds = 0.0;
};

GaitRun RunGait(const Context& context, const GaitSequence& gait) {
  SimRun run(context, "slippery_ground.xml");
  const int chassis = run.Body("RearChassis");
  const double end = kGaitStart + gait.cycles * gait.cycle_time;
  const SimRun::SequenceTimes times = run.PlaySequence(gait.file);
  // The speed is measured over whole cycles: a file that does not last
  // them would measure something else.
  if (std::abs(times.end - end) > 0.5 * run.dt())
    throw Error(gait.file + " lasts " + Num(times.end) + " s, not the " + Num(end) + " s of " +
                std::to_string(gait.cycles) + " cycles of " + Num(gait.cycle_time) + " s");
  GaitRun out;
  out.x.title = "rear chassis x";
  double x_after_first = 0.0;
  run.RunUntil(end, [&] {
    const double t = run.time();
    if (std::abs(t - (kGaitStart + gait.cycle_time)) < 0.5 * run.dt())
      x_after_first = run.Position(chassis).x();
    if (run.sim().step() % 10 == 0) {
      out.x.x.push_back(t);
      out.x.y.push_back(run.Position(chassis).x());
    }
  });
  out.sim_seconds = run.time();
  out.speed = (run.Position(chassis).x() - x_after_first) / ((gait.cycles - 1) * gait.cycle_time);
  return out;
}

}  // namespace

namespace {

struct SkidRun {
  double speed = 0.0;          // steady, over the last 5 s
  double acceleration = 0.0;   // over the first 0.4 s after the start
  Series velocity;
  double sim_seconds = 0.0;
};

// The 18 kg gen1 on ice (mu 0.025) with all four wheels at 1 rad/s from t = 1 s.
SkidRun RunSkid(const Context& context, double duration) {
  constexpr double kStart = 1.0;
  SimRun run(context, "slippery_ground.xml");
  run.PlaySequence("gen1_light_skid.xml");  // the wheels at 1 rad/s from kStart
  const int chassis = run.Body("RearChassis");
  SkidRun out;
  out.velocity.title = "rear chassis speed";
  std::vector<double> t_accel, v_accel;
  double x_late = 0.0;
  const double late = kStart + duration - 5.0;
  run.RunUntil(kStart + duration, [&] {
    const double t = run.time();
    const double v = run.Read(chassis).linear_velocity.x();
    if (t > kStart + 0.05 && t < kStart + 0.45) {
      t_accel.push_back(t);
      v_accel.push_back(v);
    }
    if (std::abs(t - late) < 0.5 * run.dt()) x_late = run.Position(chassis).x();
    if (run.sim().step() % 10 == 0) {
      out.velocity.x.push_back(t);
      out.velocity.y.push_back(v);
    }
  });
  out.sim_seconds = run.time();
  out.speed = (run.Position(chassis).x() - x_late) / 5.0;
  out.acceleration = FitLine(t_accel, v_accel).y();
  return out;
}

}  // namespace

ExperimentResult SkiddingWheels(const Context& context) {
  ExperimentResult result;
  constexpr double kMu = 0.025, kG = 9.81;  // slippery_ground.xml's ice
  const SkidRun run = RunSkid(context, 15.0);
  result.sim_seconds = run.sim_seconds;
  const double no_skid = 1.0 * kWheelRadius;
  result.checks.push_back(Relative("speed after 10 s vs no skid (1 rad/s x 0.235 m)", run.speed,
                                   no_skid, 0.01, "m/s"));
  result.checks.push_back(Relative("acceleration while the wheels skid vs mu g", run.acceleration,
                                   kMu * kG, 0.05, "m/s^2"));
  Plot plot;
  plot.file = "skid.png";
  plot.title = "gen1 18 kg on ice (mu 0.025), wheels at 1 rad/s from t = 1 s";
  plot.xlabel = "t [s]";
  plot.ylabel = "speed [m/s]";
  Series traction{"traction-limited: mu g (t - 1)", {1.0, 1.0 + no_skid / (kMu * kG)},
                  {0.0, no_skid}, "dashed"};
  Series rolling{"no skid: 0.235 m/s", {0.0, 16.0}, {no_skid, no_skid}, "dashed"};
  plot.series = {run.velocity, traction, rolling};
  result.plots.push_back(plot);
  result.notes =
      "The light gen1 (18 kg, `slippery_ground.xml`: ice, mu 0.025) starts its four wheels at "
      "1 rad/s (1000 N m motors). The wheels skid at first and the ice pushes the robot with "
      "at most mu m g, so it accelerates at mu g = 0.245 m/s^2 (measured " +
      Num(run.acceleration) + ") until the wheels roll at 0.235 m/s after about a second; on "
      "flat ground nothing then resists the rolling, so it keeps that speed (measured " +
      Num(run.speed) + " m/s).\n\n"
      "**The original's 0.0038 m/s is not physical for this setting.** A vehicle needs "
      "traction only to accelerate or to overcome resistance; with no slope and no rolling "
      "resistance, any mu > 0 lets it reach the wheels' speed. The original's figure suggests "
      "that its wheels never gripped (for example ODE's mu taken as a force in newtons, "
      "which it is without dContactApprox1) or that the ground resisted in a way the "
      "SPEC does not describe. See caterpillar and rolking for what that means for the "
      "comparison of the gaits.";
  return result;
}

namespace {

ExperimentResult GaitExperiment(const Context& context, const GaitSequence& sequence,
                                const std::string& file, const std::string& name,
                                double original, const std::string& description) {
  ExperimentResult result;
  const GaitRun gait = RunGait(context, sequence);
  const SkidRun skid = RunSkid(context, 10.0);
  result.sim_seconds = gait.sim_seconds + skid.sim_seconds;
  result.checks.push_back(AtLeast(name + " speed / skidding wheels' speed", gait.speed / skid.speed,
                                  10.0, ""));
  Plot plot;
  plot.file = file;
  plot.title = "gen1 18 kg on ice (mu 0.025): " + name;
  plot.xlabel = "t [s]";
  plot.ylabel = "x of the rear chassis [m]";
  plot.series = {gait.x};
  result.plots.push_back(plot);
  result.notes =
      "The light gen1 on ice (`slippery_ground.xml`). " + description +
      " A moving foot's wheel rolls with it, driven at the matching ground speed; a standing "
      "foot's wheel is held. Hip and knee targets follow from the "
      "legs' geometry (0.3 m links, hips 0.48 m above the axles) and are sent at 50 Hz "
      "(P 100, target one time constant ahead) by the shipped sequence `sequences/" +
      sequence.file + "`. Cycle " + Num(sequence.cycle_time) + " s; " +
      std::to_string(sequence.cycles) + " cycles, the speed measured over all but the first: " +
      Num(gait.speed) + " m/s (the original: " + Num(original) + " m/s). Skidding wheels at "
      "1 rad/s on the same ice: " + Num(skid.speed) + " m/s (the original: 0.0038 m/s).\n\n"
      "**Why the ordering check fails.** The gaits are statically stable: in every phase the "
      "held wheels' static friction (at most mu N, 0.025 of the weight they carry) must "
      "accelerate what moves, which bounds their speed to a few centimetres per second, as "
      "in the original. But the skidding wheels of the original (0.0038 m/s) are not "
      "physical on flat ice (see skid): with mu 0.025 they accelerate the robot at mu g to "
      "0.235 m/s within a second. On homogeneous ground with Coulomb friction, a wheeled "
      "robot that can walk by friction can also roll; the gaits win only where rolling "
      "meets a resistance that a held wheel does not (sinking in snow or sand), which the "
      "SPEC's flat ice does not have. The gait's speed is of the same order as the "
      "original's.";
  return result;
}

}  // namespace

ExperimentResult CaterpillarGait(const Context& context) {
  // Two phases: 1.5 s + 3.5 s (sequences/make_sequences.py, caterpillar()).
  return GaitExperiment(context, {"gen1_light_caterpillar.xml", 6, 5.0}, "caterpillar.png",
                        "caterpillar", 0.057,
                        "Caterpillar: the front feet reach 0.25 m forward (1.5 s) while the "
                        "rear wheels hold the body; then the front wheels hold while the legs "
                        "pull the body, and with it the rolling rear wheels, 0.25 m forward "
                        "over them (3.5 s).");
}

ExperimentResult RollingWalking(const Context& context) {
  // Four 1 s steps and a 3 s push (sequences/make_sequences.py, rolking()).
  return GaitExperiment(context, {"gen1_light_rolking.xml", 5, 7.0}, "rolking.png", "rolking",
                        0.048,
                        "Rolling walking, after the real robot's: one leg at a time (1, 3, 2, "
                        "4; 1 s each) reaches 0.25 m forward, its wheel rolling, while the "
                        "other three stand; then all four stand and the legs push the body "
                        "0.25 m forward over the feet (3 s).");
}

}  // namespace simpartner::validate
