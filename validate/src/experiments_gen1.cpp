// gen1 experiments: the two circle runs and, on slippery ground, the
// skidding wheels, the caterpillar gait and rolling walking.
#include <algorithm>
#include <cmath>
#include <string>

#include "simpartner/validate/analysis.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/gait.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

constexpr double kAxleDistance = 0.6;   // SPEC 7: a, Turner joint to each axle
constexpr double kWheelWidth = 0.14;    // workpartner_gen1.xml: the wheels' cylinder length

// The two friction settings of the circle runs: the thesis's own (ground
// material 0.5 along the slip, 1.0 across it: gen1_flat_thesis.xml) and
// isotropic Coulomb friction mu (gen1_flat.xml, whose ground takes
// contactMu).
struct CircleFriction {
  std::string world;
  double mu = 1.0;  // contactMu; the thesis world's ground has its own material
  std::string Describe() const;
};
const CircleFriction kThesisFriction{"gen1_flat_thesis.xml", 1.0};
CircleFriction Isotropic(double mu) { return {"gen1_flat.xml", mu}; }
std::string CircleFriction::Describe() const {
  return world == kThesisFriction.world ? "0.5 along the slip, 1.0 across (the thesis)"
                                        : "isotropic mu " + FormatNumber(mu);
}

struct CircleRunResult {
  CircleFit front, rear;            // axle midpoints over the measured part
  CircleFit legs;                   // the mean of the four wheel centres (the thesis's point)
  Series front_path, rear_path;     // x, z over the whole run
  Series radius_error;              // rear axle: distance to the fitted centre - r, vs t
  // Mean vertical load [N] of Wheel1..4 (front right, front left, rear left, rear right).
  double wheel_load[4] = {0, 0, 0, 0};
  // Mean share of each wheel's load on its rim edge nearer the vehicle's
  // middle (the edge nearer its axle's midpoint), same order.
  double middle_edge_share[4] = {0, 0, 0, 0};
  double mass = 0.0;
  double sim_seconds = 0.0;
  double Radius() const { return (front.radius + rear.radius) / 2.0; }
  double WorstDeviation() const { return std::max(front.worst_deviation, rear.worst_deviation); }
};

// A gen1 wheel (a cylinder of radius kWheelRadius about its local z)
// stands on two contacts at its rim edges, e = +-w/2 along its axle a. Its
// contact torque about its centre, along h = a x up, is sum e_i N_i + r F.a
// (the normal loads' lever arms, and the ground friction's across the
// wheel acting r below the centre), so the edges share the load N as
// N/2 +- (tau.h - r F.a) / w. Returns the share of the edge nearer
// axle_midpoint (the vehicle's middle), or 0.5 when the wheel is unloaded.
double MiddleEdgeShare(const sim::BodyReadout& wheel, const Eigen::Vector3d& axle_midpoint) {
  const Eigen::Vector3d up = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d axle = wheel.orientation * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d h = axle.cross(up);
  const double load = wheel.contact_force.dot(up);
  if (!(load > 0.0)) return 0.5;
  const double moment =
      wheel.contact_torque.dot(h) - kWheelRadius * wheel.contact_force.dot(axle);
  const double plus_share = 0.5 + moment / (kWheelWidth * load);  // the edge at +w/2 along a
  const bool plus_is_middle = axle.dot(axle_midpoint - wheel.position) > 0.0;
  return plus_is_middle ? plus_share : 1.0 - plus_share;
}

// gen1 on flat ground, playing a shipped sequence (sequences/): steer to
// alpha with TurnerMotor while standing, then drive the left (inner) wheels
// at v_left and the right ones at v_right [m/s] from t = 2 s; the circles
// are fitted to the axle midpoints once the turn is steady.
CircleRunResult RunCircle(const Context& context, const CircleFriction& friction, double settle,
                          double duration, const std::string& sequence) {
  Parameters params = context.params;
  params.contactMu = friction.mu;
  SimRun run(context, friction.world, params);
  const int wheel[4] = {run.Body("Wheel1"), run.Body("Wheel2"), run.Body("Wheel3"),
                        run.Body("Wheel4")};
  constexpr double kSteerTime = 2.0;
  run.PlaySequence(sequence);
  CircleRunResult out;
  for (const model::FlatBody& b : run.sim().flat().bodies) out.mass += b.source->mass;
  std::vector<Eigen::Vector2d> front, rear, legs;
  std::vector<double> times;
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
    legs.emplace_back((f.x() + r.x()) / 2.0, (f.z() + r.z()) / 2.0);
    times.push_back(t);
    for (int k = 0; k < 4; ++k) {
      out.wheel_load[k] += run.VerticalContactForce(wheel[k]);
      const Eigen::Vector3d axle_midpoint = k < 2 ? f : r;
      out.middle_edge_share[k] += MiddleEdgeShare(run.Read(wheel[k]), axle_midpoint);
    }
  });
  out.sim_seconds = run.time();
  out.front = FitCircle(front);
  out.rear = FitCircle(rear);
  out.legs = FitCircle(legs);
  const double samples = static_cast<double>(std::max<size_t>(1, times.size()));
  for (double& load : out.wheel_load) load /= samples;
  for (double& share : out.middle_edge_share) share /= samples;
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

// The ideal vehicle of SkidSteerRadius with this run's mass and loads.
SkidSteerVehicle IdealVehicle(const CircleRunResult& run, double mu, double alpha, double v_left,
                              double v_right) {
  SkidSteerVehicle v;
  v.alpha = alpha;
  v.v_left = v_left;
  v.v_right = v_right;
  v.axle = kAxleDistance;
  v.half_track = 0.3;
  v.contact_half_width = kWheelWidth / 2.0;
  v.mass = run.mass;
  v.mu = mu;
  v.front_load = (run.wheel_load[0] + run.wheel_load[1]) / 2.0;
  v.rear_load = (run.wheel_load[2] + run.wheel_load[3]) / 2.0;
  // Each wheel's own load: the turn moves load to the outer (right) wheels.
  const double loads[4] = {run.wheel_load[1], run.wheel_load[0], run.wheel_load[2],
                           run.wheel_load[3]};
  std::copy(loads, loads + 4, v.wheel_loads);
  const double shares[4] = {run.middle_edge_share[1], run.middle_edge_share[0],
                            run.middle_edge_share[2], run.middle_edge_share[3]};
  std::copy(shares, shares + 4, v.middle_edge_share);
  return v;
}

// The radius an ideal slipping vehicle with this run's loads would turn at.
double CoulombRadius(const CircleRunResult& run, double mu, double alpha, double v_left,
                     double v_right) {
  return SkidSteerRadius(IdealVehicle(run, mu, alpha, v_left, v_right));
}

// Tolerances of the thesis-friction circles: the thesis came within 0.03 %
// of the point it measured at 1.00 / 1.10 m/s (8.5 % at equal speeds); the
// sim, with friction rows of their own small compliance (contactSlip),
// comes within 0.003 % at 0.5, 1 and 2 ms.
constexpr double kCircleEqualTolerance = 0.0003;
constexpr double kCircleDifferentialTolerance = 0.0003;
// Isotropic runs against the steady state of the same vehicle, the issue's
// 2 % and 0.3 %. At equal speeds every contact slides; at 1.00 / 1.10 m/s
// the inner wheels roll on the steering's circle and the outer ones slide
// (see the notes).
constexpr double kIsotropicEqualTolerance = 0.02;
constexpr double kIsotropicDifferentialTolerance = 0.003;
// Their target is built from the run's own wheel loads and rim-edge
// shares, so the check says so: it shows the run agrees with the Coulomb
// steady state of the loads it produced, not that the loads are right.
constexpr const char* kSelfConsistent =
    " (self-consistency: the steady state from this run's loads and edge shares)";

// What the thesis's circles measure, for a rigid articulated vehicle whose
// wheels roll without slipping: the axle centres ride a cot(alpha/2) about
// the turn's centre, and the mean of the four wheel centres (the thesis
// averaged the legs' positions), which lies on the chord between them,
// rides a cot(alpha/2) cos(alpha/2).
double AxleCentreRadius(double alpha) { return kAxleDistance / std::tan(alpha / 2.0); }
double LegAverageRadius(double alpha) { return AxleCentreRadius(alpha) * std::cos(alpha / 2.0); }

void AddPaths(const CircleRunResult& run, const std::string& label, Plot* paths, Plot* errors) {
  Series front = run.front_path, rear = run.rear_path;
  front.title = "front axle, " + label;
  rear.title = "rear axle, " + label;
  paths->series.push_back(front);
  paths->series.push_back(rear);
  Series error = run.radius_error;
  error.title = label;
  errors->series.push_back(error);
}

std::string CircleRow(const std::string& friction, const std::string& speeds,
                      const CircleRunResult& run, const std::string& reference) {
  return "| " + friction + " | " + speeds + " | " + FormatNumber(run.front.radius) + " | " +
         FormatNumber(run.rear.radius) + " | " + FormatNumber(run.legs.radius) + " | " +
         FormatNumber(run.WorstDeviation() * 1000.0) + " | " + reference + " |\n";
}

const char* kCircleTableHead =
    "| friction | wheel speeds | front axle centre r [m] | rear axle centre r [m] | mean of the "
    "four wheels r [m] | worst deviation [mm] | reference |\n|---|---|---|---|---|---|---|\n";

}  // namespace

ExperimentResult CircleEqualSpeeds(const Context& context) {
  ExperimentResult result;
  constexpr double kAlpha = 0.2972;
  constexpr double kSpeed = 1.0;  // [m/s] every wheel
  const double axle = AxleCentreRadius(kAlpha), legs = LegAverageRadius(kAlpha);
  // One lap (26 s at ~4.7 m and 1 m/s) after the turn has settled.
  const double settle = context.quick ? 3.0 : 8.0, duration = context.quick ? 8.0 : 30.0;
  Plot paths;
  paths.file = "circle_equal.png";
  paths.title = "gen1, alpha 0.2972 rad, equal wheel speeds: axle-centre paths";
  paths.xlabel = "x [m]";
  paths.ylabel = "z [m]";
  paths.equal_axes = true;
  Plot errors;
  errors.file = "circle_equal_error.png";
  errors.title = "gen1, alpha 0.2972 rad, equal speeds: distance from the fitted circle";
  errors.xlabel = "t [s]";
  errors.ylabel = "rear axle centre: distance to centre - r [mm]";
  std::string rows;

  // Validation: the thesis's experiment as it ran.
  const CircleRunResult thesis =
      RunCircle(context, kThesisFriction, settle, duration, "gen1_circle_equal_speeds.xml");
  result.sim_seconds += thesis.sim_seconds;
  result.checks.push_back(Relative("radius at the axle centres, thesis friction", thesis.Radius(),
                                   axle, kCircleEqualTolerance, "m"));
  result.checks.push_back(Relative("radius of the mean of the four wheels, thesis friction",
                                   thesis.legs.radius, legs, kCircleEqualTolerance, "m"));
  rows += CircleRow(kThesisFriction.Describe(), "1 / 1 m/s", thesis,
                    "a cot(alpha/2) = " + FormatNumber(axle) + ", x cos(alpha/2) = " + FormatNumber(legs));
  AddPaths(thesis, "thesis friction", &paths, &errors);

  // A second check: isotropic friction against the steady state of the
  // same vehicle solved apart from the sim.
  for (const double mu : {0.5, 1.0}) {
    const CircleRunResult run =
        RunCircle(context, Isotropic(mu), settle, duration, "gen1_circle_equal_speeds.xml");
    result.sim_seconds += run.sim_seconds;
    const double coulomb = CoulombRadius(run, mu, kAlpha, kSpeed, kSpeed);
    result.checks.push_back(Relative("radius, isotropic mu " + FormatNumber(mu) + kSelfConsistent,
                                     run.Radius(), coulomb, kIsotropicEqualTolerance, "m"));
    rows += CircleRow(Isotropic(mu).Describe(), "1 / 1 m/s", run,
                      "steady state, isotropic Coulomb: " + FormatNumber(coulomb));
    AddPaths(run, "isotropic mu " + FormatNumber(mu), &paths, &errors);
  }
  paths.series.push_back(CirclePoints(thesis.rear.centre, axle,
                                      "r = a cot(alpha/2) = " + FormatNumber(axle) + " m"));
  result.plots = {paths, errors};
  result.notes =
      "gen1 on flat ground plays `sequences/gen1_circle_equal_speeds.xml`: `TurnerMotor` steers "
      "to alpha = 0.2972 rad (P 100, I 100), then at t = 2 s all four wheels turn at 1 m/s / "
      "0.235 m (1000 N m motors). Circles are fitted (least squares) over " + FormatNumber(duration) +
      " s after " + FormatNumber(settle) + " s of settling to three points: each axle's centre (the "
      "midpoint of its two wheels) and the mean of the four wheel centres.\n\n" +
      kCircleTableHead + rows +
      "\n**Which point each number is.** Rolling without slip, the axle centres ride "
      "a cot(alpha/2) = " + FormatNumber(axle) + " m about the turn's centre; the mean of the four "
      "wheels, on the chord between the axle centres, rides a cot(alpha/2) cos(alpha/2) = " +
      FormatNumber(legs) + " m. The thesis averaged the legs' positions, so its 4.30 m belongs to the "
      "second point (8.5 % off it); the target 4.01 m is the first.\n\n"
      "**The thesis's friction.** It ran these circles with \"0.5 and 1.0 for tangential and "
      "normal friction\". Read in the wheel's frame, as vehicle simulators do: 0.5 along each "
      "wheel's rolling direction (tangential to the tyre) and 1.0 across it (normal to the "
      "wheel's plane); `gen1_flat_thesis.xml`'s ground asks for the rolling direction of "
      "every wheel on it (docs/contacts.md). The outer wheels then slip along their rolling "
      "direction while the grip across holds each wheel on its path, and the vehicle turns "
      "where its steering points: " + FormatNumber(thesis.Radius()) + " m at the axle centres (" +
      FormatFixed((thesis.Radius() / axle - 1.0) * 100.0, 2) + " % from a cot(alpha/2)), " +
      FormatNumber(thesis.legs.radius) + " m for the mean of the wheels (" +
      FormatFixed((thesis.legs.radius / legs - 1.0) * 100.0, 2) + " %). Read instead with the "
      "first direction along each contact's sliding velocity (`frictionDirection` slip), the "
      "same coefficients gave 5.04573 m at the axle centres (measured 2026-11-26, "
      "`simpartner-validate --only circle_equal --models COPY` with that world's ground set to "
      "slip in a copy of models/): mu2 = 1.0 held across each contact's slip kept the slips "
      "from turning, and the vehicle rode wider than with isotropic mu 0.5 (below). That "
      "reading is not a Coulomb law (across a slip's own direction a force can act only while "
      "the contact sticks), and since 2026-11-26 a `slip` material with mu2 other than mu is "
      "refused at load (docs/contacts.md). Only the wheel-frame reading gives the thesis's "
      "circles.\n\n"
      "**Isotropic friction** (the same 0.5 or 1.0 both ways, along the slip) is a second "
      "check, not the thesis's experiment, and a self-consistency check: the last column "
      "solves the steady state of an "
      "ideal rigid vehicle, isotropic Coulomb friction (the force against each contact's "
      "slip, none across it), each wheel touching at its two rim edges 0.14 m apart, with "
      "each wheel's load and each edge's share of it as measured in the run (the turn moves "
      "load to the outer wheels; the edges' shares come from the wheel's contact torque), "
      "independently of the sim (`SkidSteerRadius` in sp_validate); the mass sits at the "
      "steering joint. Every contact here slides faster than mu h N / m (what one step of "
      "friction can stop), where the sim applies that cone: friction across the slip is "
      "zero (docs/contacts.md). Until 2026-11-23 it held up to mu N across the slip (ODE's "
      "pyramid), so a slide could not turn and the run rode 4.93 m.";
  return result;
}

ExperimentResult CircleDifferentialSpeeds(const Context& context) {
  ExperimentResult result;
  constexpr double kAlpha = 0.2;
  const double axle = AxleCentreRadius(kAlpha), legs = LegAverageRadius(kAlpha);
  const double settle = context.quick ? 3.0 : 8.0, duration = context.quick ? 8.0 : 38.0;
  // Outer wheels at the speed that matches the steering: (r + t) / (r - t).
  const double matched = (axle + 0.3) / (axle - 0.3);
  std::string rows;

  const CircleRunResult thesis =
      RunCircle(context, kThesisFriction, settle, duration, "gen1_circle_differential.xml");
  const CircleRunResult isotropic =
      RunCircle(context, Isotropic(1.0), settle, duration, "gen1_circle_differential.xml");
  const CircleRunResult exact =
      RunCircle(context, Isotropic(1.0), settle, duration, "gen1_circle_matched.xml");
  result.sim_seconds = thesis.sim_seconds + isotropic.sim_seconds + exact.sim_seconds;
  result.checks.push_back(Relative("radius at the axle centres, thesis friction", thesis.Radius(),
                                   axle, kCircleDifferentialTolerance, "m"));
  result.checks.push_back(Relative("radius of the mean of the four wheels, thesis friction",
                                   thesis.legs.radius, legs, kCircleDifferentialTolerance, "m"));
  result.checks.push_back(Absolute("worst deviation from the fitted circle, thesis friction",
                                   thesis.WorstDeviation(), 0.0, 0.001, "m"));
  const SkidSteerVehicle ideal = IdealVehicle(isotropic, 1.0, kAlpha, 1.00, 1.10);
  const double coulomb = SkidSteerRadius(ideal);
  result.checks.push_back(Relative(std::string("radius, isotropic mu 1") + kSelfConsistent,
                                   isotropic.Radius(), coulomb, kIsotropicDifferentialTolerance,
                                   "m"));
  // Why that steady state is the steering's circle: the inner wheels roll
  // (one rim edge each at rest on the ground), the outer ones slide, which
  // is a Coulomb steady state when the held edges need at most mu N.
  const SkidSteerRolling rolling = SkidSteerRollingInnerWheels(ideal);
  result.checks.push_back(AtMost("friction the inner wheels' held rim edges need, of mu N",
                                 rolling.friction_needed, 1.0, ""));
  SkidSteerVehicle even_edges = ideal;
  std::fill(even_edges.middle_edge_share, even_edges.middle_edge_share + 4, 0.0);
  const SkidSteerRolling rolling_even = SkidSteerRollingInnerWheels(even_edges);
  const double coulomb_even = SkidSteerRadius(even_edges);
  result.checks.push_back(Relative("radius, 1.00 / " + FormatNumber(matched) + " m/s (matched), isotropic mu 1",
                                   exact.Radius(), axle, 0.0025, "m"));
  result.checks.push_back(Absolute("worst deviation from the fitted circle, matched speeds",
                                   exact.WorstDeviation(), 0.0, 0.001, "m"));
  rows += CircleRow(kThesisFriction.Describe(), "1.00 / 1.10 m/s", thesis,
                    "a cot(alpha/2) = " + FormatNumber(axle) + ", x cos(alpha/2) = " + FormatNumber(legs));
  rows += CircleRow(Isotropic(1.0).Describe(), "1.00 / 1.10 m/s", isotropic,
                    "steady state, isotropic Coulomb: " + FormatNumber(coulomb) +
                        " (inner wheels rolling: a cot(alpha/2) = " + FormatNumber(axle) + ")");
  rows += CircleRow(Isotropic(1.0).Describe(), "1.00 / " + FormatNumber(matched) + " m/s", exact,
                    "no slip needed: a cot(alpha/2) = " + FormatNumber(axle));
  Plot paths;
  paths.file = "circle_differential.png";
  paths.title = "gen1, alpha 0.2 rad, inner 1.00 / outer 1.10 m/s, thesis friction: axle-centre paths";
  paths.xlabel = "x [m]";
  paths.ylabel = "z [m]";
  paths.equal_axes = true;
  Series front = thesis.front_path, rear = thesis.rear_path;
  front.title = "front axle";
  rear.title = "rear axle";
  paths.series = {front, rear,
                  CirclePoints(thesis.rear.centre, thesis.rear.radius,
                               "fitted, r = " + FormatNumber(thesis.Radius()) + " m"),
                  CirclePoints(thesis.rear.centre, axle, "r = a cot(alpha/2) = " + FormatNumber(axle) + " m")};
  Plot errors;
  errors.file = "circle_differential_error.png";
  errors.title = "gen1, alpha 0.2 rad: distance of the rear axle centre from the fitted circle";
  errors.xlabel = "t [s]";
  errors.ylabel = "distance to centre - r [mm]";
  Series e0 = thesis.radius_error, e1 = isotropic.radius_error, e2 = exact.radius_error;
  e0.title = "1.00 / 1.10 m/s, thesis friction";
  e1.title = "1.00 / 1.10 m/s, isotropic mu 1";
  e2.title = "1.00 / " + FormatNumber(matched) + " m/s (matched), isotropic mu 1";
  errors.series = {e0, e1, e2};
  result.plots = {paths, errors};
  result.notes =
      "As the circle above, steering alpha = 0.2 rad, the inner (left) wheels at 1.00 m/s and "
      "the outer at 1.10 m/s (`sequences/gen1_circle_differential.xml`); circles fitted over " +
      FormatNumber(duration) + " s (about one lap) after " + FormatNumber(settle) + " s of settling.\n\n" +
      kCircleTableHead + rows +
      "\n**Which point each number is.** The target 5.98 m is a cot(alpha/2) = " + FormatNumber(axle) +
      " m, the axle centres' radius; the thesis's 5.9516 m was the mean of the legs, whose "
      "rolling radius is a cot(alpha/2) cos(alpha/2) = " + FormatNumber(legs) + " m, so it came within " +
      FormatFixed(std::abs(5.9516 / legs - 1.0) * 100.0, 2) + " % of the point it measured.\n\n"
      "Rolling without slip on the steering's circle needs the outer wheels at (r + 0.3) / "
      "(r - 0.3) = " + FormatNumber(matched) + " times the inner ones' speed; at 1.10 the outer wheels "
      "slip a little along their rolling direction and the grip across holds the path. With "
      "the thesis's friction (wheel frame, as above) the axle centres ride " +
      FormatNumber(thesis.Radius()) + " m, " + FormatFixed((thesis.Radius() / axle - 1.0) * 100.0, 2) +
      " % outside a cot(alpha/2). Until 2026-11-23 it was +0.11 %: the world CFM (1e-5) "
      "acted on the friction rows too and let the wheels creep sideways; friction now has "
      "its own compliance, `contactSlip` = 1e-7 m/(N s), a velocity per force and so the "
      "same at any step (5.98012 / 5.98012 / 5.98013 m at 0.5 / 1 / 2 ms). The run with the "
      "matched speed (`gen1_circle_matched.xml`) needs no slip and is the formula's own case. "
      "**The isotropic run** is checked against the Coulomb steady state of the same ideal "
      "vehicle as the circles at equal speeds (`SkidSteerRadius`; each wheel's load and each "
      "rim edge's share of it measured in the run): " + FormatNumber(isotropic.Radius()) +
      " m against " + FormatNumber(coulomb) + " m. That steady state is the steering's circle: the "
      "inner wheels roll, each on the rim edge nearer the vehicle's middle, which stays at "
      "rest on the ground, and the outer wheels (slower than the " + FormatNumber(matched) +
      " m/s rolling needs) slide. It holds when the two resting edges can balance the "
      "sliding ones and the centripetal force within mu N each (`SkidSteerRollingInnerWheels`): "
      "they need " + FormatNumber(rolling.friction_needed) + " of mu N with the run's edge loads (the "
      "inner wheels carry " + FormatFixed(ideal.middle_edge_share[0] * 100.0, 1) + " and " +
      FormatFixed(ideal.middle_edge_share[2] * 100.0, 1) + " % of their load, front and rear, "
      "on that edge). With half of each wheel's load on each edge, as the solve assumed "
      "until 2026-11-25, they would need " + FormatNumber(rolling_even.friction_needed) +
      " of mu N, the inner wheels cannot roll, and the all-sliding steady state turns at " +
      FormatNumber(coulomb_even) + " m: the 6.025 m this report used to compare with, 0.74 % from the "
      "run. The difference was the edge loads, not the sim's friction: a rigid contact "
      "model gives a steady turn whose radius depends on how each wheel's load is shared "
      "across its width.";
  return result;
}

// ---------------------------------------------------------------- gaits
// A statically stable gait of the 18 kg gen1, played from its shipped
// sequence (sequences/make_sequences.py writes the leg targets, computed
// from the legs' geometry, at 50 Hz, and holds the standing feet's wheels
// at each phase change): validate/src/gait.cpp.
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
      FormatNumber(run.acceleration) + ") until the wheels roll at 0.235 m/s after about a second; on "
      "flat ground nothing then resists the rolling, so it keeps that speed (measured " +
      FormatNumber(run.speed) + " m/s).\n\n"
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

// gait: the run of `sequence`; why_not_exact: why the speed is not one
// stride per cycle exactly.
ExperimentResult GaitExperiment(const Context& context, const GaitSequence& sequence,
                                const GaitRun& gait, const std::string& file,
                                const std::string& name, double original,
                                const std::string& description, const std::string& friction_bound,
                                const std::string& why_not_exact) {
  ExperimentResult result;
  const SkidRun skid = RunSkid(context, 10.0);
  result.sim_seconds = gait.sim_seconds + skid.sim_seconds;
  // With no slip of the held wheels the body advances one stride per cycle.
  const double expected = sequence.stride / sequence.CycleTime();
  result.checks.push_back(Relative(name + " speed vs stride / cycle (held wheels within mu N)",
                                   gait.speed, expected, 0.10, "m/s"));
  result.checks.push_back(AtMost(name + " speed / skidding wheels' speed (flat ice: rolling wins)",
                                 gait.speed / skid.speed, 1.0, ""));
  Plot plot;
  plot.file = file;
  plot.title = "gen1 18 kg on ice (mu 0.025): " + name;
  plot.xlabel = "t [s]";
  plot.ylabel = "x of the rear chassis [m]";
  const double t_end = kGaitStart + gait.cycles * sequence.CycleTime();
  Series stride_line{"one stride per cycle (no slip)", {kGaitStart, t_end},
                     {gait.x.y.empty() ? 0.0 : gait.x.y.front(),
                      (gait.x.y.empty() ? 0.0 : gait.x.y.front()) +
                          gait.cycles * sequence.stride},
                     "dashed"};
  plot.series = {gait.x, stride_line};
  result.plots.push_back(plot);
  result.notes =
      "The light gen1 on ice (`slippery_ground.xml`, mu 0.025). " + description +
      " A moving foot's wheel rolls with it, driven at the matching ground speed; a standing "
      "foot's wheel is held. Hip and knee targets follow from the "
      "legs' geometry (0.3 m links, hips 0.48 m above the axles) and are sent at 50 Hz "
      "(P 100, target one time constant ahead) by the shipped sequence `sequences/" +
      sequence.file + "`; every move follows 0.5 - 0.5 cos(pi u) over its phase. Cycle " +
      FormatNumber(sequence.CycleTime()) + " s; " + std::to_string(gait.cycles) +
      " cycles, the speed measured over all but the first: " + FormatNumber(gait.speed) +
      " m/s (the original: " + FormatNumber(original) + " m/s).\n\n"
      "**Expected speed.** If the held wheels do not slip, the body advances one stride (" +
      FormatNumber(sequence.stride) + " m) per cycle: " + FormatNumber(expected) + " m/s. They do not slip if "
      "the largest force the move needs stays below the friction they can give, mu N: " +
      friction_bound + " The check holds the speed to 10 % of stride / cycle: " + why_not_exact + " (measured " +
      FormatFixed((gait.speed / expected - 1.0) * 100.0, 1) + " %).\n\n"
      "**Against skidding wheels.** The SPEC's ordering (the original: gaits 0.057 and 0.048 "
      "m/s, skidding wheels 0.0038 m/s) does not hold here, and should not: skidding wheels "
      "at 1 rad/s on the same ice reach " + FormatNumber(skid.speed) + " m/s (see skid), " +
      FormatFixed(skid.speed / gait.speed, 1) + " times the gait. On homogeneous flat ground "
      "with Coulomb friction and no rolling resistance, a wheeled robot that can walk by "
      "friction can also roll; the gaits win only where rolling meets a resistance a held "
      "wheel does not (sinking in snow or sand), which the SPEC's flat ice does not have. "
      "The check asserts that physics (gait slower than rolling); the gait's speed is of the "
      "same order as the original's.";
  return result;
}

}  // namespace

namespace {

// Rolking's push and steps in the wheels' terms (gait.phases: four steps,
// then the push), per cycle.
struct RolkingCreep {
  double front_roll = 0.0, rear_roll = 0.0;  // [m] closed form: r times the calves' pitch in the push
  const PhaseSlip* push = nullptr;
  double push_feet = 0.0;      // [m] the held wheels' mean displacement in the push
  double steps_body = 0.0;     // [m] the body's displacement over the four steps
  double held_slid_steps = 0.0;  // [m] the held wheels' mean slide per step
  double stepping_slid[2] = {0, 0};  // [m] a stepping wheel's slide, front and rear legs
  double Pair(double WheelInPhase::*field, int first) const {
    return (push->wheels[first].*field + push->wheels[first + 1].*field) / 2.0;
  }
};

RolkingCreep MeasureRolkingCreep(const GaitSequence& sequence, const GaitRun& gait) {
  RolkingCreep out;
  const double stride = sequence.stride;
  out.front_roll = HeldWheelRoll(true, stride, 0.0);
  out.rear_roll = HeldWheelRoll(false, stride, 0.0);
  out.push = &gait.phases.back();
  for (const WheelInPhase& w : out.push->wheels) out.push_feet += w.moved / kGaitWheels;
  int held = 0;
  for (size_t p = 0; p + 1 < gait.phases.size(); ++p) {
    out.steps_body += gait.phases[p].body_moved;
    for (int i = 0; i < kGaitWheels; ++i) {
      const double slid = gait.phases[p].wheels[i].slid;
      if (gait.phases[p].phase.driven[i]) {
        out.stepping_slid[i < 2 ? 0 : 1] += slid / 2.0;  // two steps each
      } else {
        out.held_slid_steps += slid;
        ++held;
      }
    }
  }
  out.held_slid_steps /= std::max(1, held);
  return out;
}

// Why rolking gains on one stride per cycle: the checks on the held
// wheels' roll and the report's account of the creep.
void ExplainHeldWheelCreep(const GaitSequence& sequence, const GaitRun& gait,
                           ExperimentResult* result) {
  const RolkingCreep c = MeasureRolkingCreep(sequence, gait);
  // A held wheel turns with its calf: that roll is kinematic (the legs
  // reach their targets well within each phase), so 1 % covers the
  // controllers' residual and the body's pitch.
  result->checks.push_back(Relative("rolking front held wheels' roll in the push vs r x calf pitch",
                                    c.Pair(&WheelInPhase::rolled, 0), c.front_roll, 0.01, "m"));
  result->checks.push_back(Relative("rolking rear held wheels' roll in the push vs r x calf pitch",
                                    c.Pair(&WheelInPhase::rolled, 2), c.rear_roll, 0.01, "m"));
  auto cm = [](double m) { return FormatFixed(m * 100.0, 2) + " cm"; };
  auto back = [&cm](double m) { return cm(std::abs(m)) + (m < 0.0 ? " back" : " forward"); };
  const double gain = gait.speed * sequence.CycleTime() - sequence.stride;
  result->notes +=
      "\n\n**The held wheels' creep: held to their calves, not to the ice.** The body gains " +
      cm(gain) + " a cycle on its stride. Per phase and wheel, at this run's step (means per "
      "cycle; `build/bench/gait_slip` prints the same at 2, 1, 0.5 and 0.25 ms, "
      "docs/validation-summary.md has those figures):\n\n" +
      PhaseSlipTable(gait.phases, 0.025) +
      "\nA held wheel's axle motor holds its angle to the calf, so the wheel turns with the "
      "calf. In the push each foot goes from 0.25 m ahead of its hip to below it; the legs' "
      "geometry (0.3 m links, hips 0.48 m above the axles) pitches a front calf by " +
      FormatFixed(c.front_roll / kWheelRadius, 3) + " rad and a rear one, whose knee bends the "
      "other way, by " + FormatFixed(c.rear_roll / kWheelRadius, 3) + " rad, so a held wheel "
      "that does not slide rolls " + cm(c.front_roll) + " (front) or " + cm(c.rear_roll) +
      " (rear) forward (measured " + cm(c.Pair(&WheelInPhase::rolled, 0)) + " and " +
      cm(c.Pair(&WheelInPhase::rolled, 2)) + ": the two checks above). Rolling costs no "
      "friction, so nothing has to exceed mu N for this (the push needs 2.47 N against 4.41 "
      "N). The chassis is rigid between the axles, though, so the four feet advance together "
      "and the pairs' " + cm(c.rear_roll - c.front_roll) + " difference slides: the rear "
      "wheels slide " + back(c.Pair(&WheelInPhase::slid, 2)) + ", the front ones " +
      back(c.Pair(&WheelInPhase::slid, 0)) + ", and the feet end " + cm(c.push_feet) + " ahead, "
      "which the body adds to its 0.25 m over them (it moves " + cm(c.push->body_moved) +
      ").\n\nThe stepping wheel turns with its calf too, the other way: driven at its foot's "
      "speed relative to the calf, it rolls r times its calf's pitch short and slides forward "
      "about that far (measured " + cm(c.stepping_slid[0]) + " front, " + cm(c.stepping_slid[1]) +
      " rear) against mu times its load, which pulls the body back. And the leg targets, "
      "sent at 50 Hz to P 100 controllers (a 10 ms time constant), make the leg joints' "
      "speeds jump every 20 ms; the 1000 N m motors take each jump within a step, a jolt at "
      "which wheels lose or multiply their load and slide at mu N. Over the four steps the "
      "standing wheels slide " + back(c.held_slid_steps) + " a step and the body moves " +
      back(c.steps_body) + ". Net, " + cm(c.push_feet) + " - " + cm(-c.steps_body) + " = " +
      cm(c.push_feet + c.steps_body) + " against the " + cm(gain) + " gained (the rest: the "
      "legs' lag at the phases' ends). The creep is the gait's kinematics, not the ice's "
      "friction or the solver's: sequences whose held wheels turn against their calves' "
      "pitch, with targets every 2 ms, walk within 4 % of one stride per cycle "
      "(docs/validation-summary.md).";
}

}  // namespace

// The friction bounds (sequences/make_sequences.py: a move of s over T
// along 0.5 - 0.5 cos(pi t / T) peaks at a = s pi^2 / (2 T^2)).
ExperimentResult CaterpillarGait(const Context& context) {
  // Two phases: 1.5 s + 3.5 s (sequences/make_sequences.py, caterpillar()).
  const GaitSequence sequence = CaterpillarSequence();
  return GaitExperiment(
      context, sequence, RunGait(context, sequence), "caterpillar.png", "caterpillar", 0.057,
      "Caterpillar: the front feet reach 0.25 m forward (1.5 s) while the "
      "rear wheels hold the body; then the front wheels hold while the legs "
      "pull the body, and with it the rolling rear wheels, 0.25 m forward "
      "over them (3.5 s).",
      "pulling the whole 18 kg 0.25 m in 3.5 s peaks at 0.25 pi^2 / (2 3.5^2) = 0.101 m/s^2, "
      "1.81 N, against mu m g = 4.41 N of all four wheels (the rolling rear wheels, driven at "
      "the body's speed, push their own share); the front wheels alone, carrying 47 % of the "
      "weight, hold 2.1 N. Reaching accelerates only the front legs (2 x 2.5 kg at 0.25 pi^2 / "
      "(2 1.5^2) = 0.55 m/s^2, 2.7 N), against 4.41 N of all four wheels (the front ones roll "
      "at the feet's speed).",
      "the leg controllers lag their targets and the wheels roll a little under the moving "
      "legs, which the stride does not count");
}

ExperimentResult RollingWalking(const Context& context) {
  // Four 1 s steps and a 3 s push (sequences/make_sequences.py, rolking()).
  const GaitSequence sequence = RollingWalkingSequence();
  const GaitRun gait = RunGait(context, sequence);
  ExperimentResult result = GaitExperiment(
      context, sequence, gait, "rolking.png", "rolking", 0.048,
      "Rolling walking, after the real robot's: one leg at a time (1, 3, 2, "
      "4; 1 s each) reaches 0.25 m forward, its wheel rolling, while the "
      "other three stand; then all four stand and the legs push the body "
      "0.25 m forward over the feet (3 s).",
      "pushing the whole 18 kg 0.25 m in 3 s on four held wheels peaks at 0.25 pi^2 / "
      "(2 3^2) = 0.137 m/s^2, 2.47 N, against mu m g = 4.41 N; a single leg's step (1.23 "
      "m/s^2 on a 2.5 kg leg, 3.1 N) by the friction of all four (the stepping wheel rolls at "
      "its foot's speed).",
      "the held wheels creep, which the stride does not count (below)");
  ExplainHeldWheelCreep(sequence, gait, &result);
  return result;
}

}  // namespace simpartner::validate
