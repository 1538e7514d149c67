// Experiments with gen2..gen4: the scanner, the pole task, the static wheel
// loads and the test track.
#include <algorithm>
#include <cmath>
#include <string>

#include "simpartner/diagnostic.h"
#include "simpartner/model/surface.h"
#include "simpartner/validate/analysis.h"
#include "simpartner/validate/experiment.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

// SPEC 8: the real robot's static wheel loads [N], wheels 1..4: the means
// of its four test runs (SPEC 8's notes), which gen4 is calibrated on.
constexpr double kRealWheelLoads[4] = {579.15, 774.90, 669.12, 676.03};
// The cross weight (W2 + W4) - (W1 + W3) of each of the four runs [N]
// (the team's records; SPEC 8 gives only the means): what varies between runs of
// the same robot, held at slightly different leg lengths each time.
constexpr double kRunCrossWeights[4] = {237.0, 219.0, 182.0, 172.0};

}  // namespace

ExperimentResult Gen4StaticLoads(const Context& context) {
  ExperimentResult result;
  constexpr double kSettle = 1.5, kAverage = 0.5;  // [s]
  SimRun run(context, "gen4_flat.xml");
  int wheel[4];
  for (int k = 0; k < 4; ++k) wheel[k] = run.Body("Wheel" + std::to_string(k + 1));
  double sum[4] = {0, 0, 0, 0};
  int samples = 0;
  run.RunUntil(kSettle + kAverage, [&] {
    for (int k = 0; k < 4; ++k)
      if (run.time() > kSettle) sum[k] += run.VerticalContactForce(wheel[k]);
    samples += run.time() > kSettle ? 1 : 0;
  });
  result.sim_seconds = run.time();
  double load[4];
  for (int k = 0; k < 4; ++k) load[k] = sum[k] / samples;
  auto pair = [](const double* w, int a, int b) { return w[a] + w[b]; };
  const double cross = pair(load, 1, 3) - pair(load, 0, 2);
  const double real_cross = pair(kRealWheelLoads, 1, 3) - pair(kRealWheelLoads, 0, 2);

  // Tolerance from the run-to-run spread. The runs differ in their cross
  // weight (sample standard deviation s over 4 runs); a change of the cross
  // weight by D moves each wheel by D / 4. The mean of 4 runs is known to
  // s / sqrt(4): per wheel s / 8, on the cross weight s / 2.
  const double run_mean = Mean({std::begin(kRunCrossWeights), std::end(kRunCrossWeights)});
  double squares = 0.0;
  for (double c : kRunCrossWeights) squares += (c - run_mean) * (c - run_mean);
  const double run_sd = std::sqrt(squares / 3.0);
  const double wheel_tolerance = run_sd / 8.0, cross_tolerance = run_sd / 2.0;
  double widest = 0.0;  // the largest departure of one run from the runs' mean
  for (double c : kRunCrossWeights) widest = std::max(widest, std::abs(c - run_mean));
  for (int k = 0; k < 4; ++k)
    result.checks.push_back(Absolute("Wheel" + std::to_string(k + 1) +
                                         " load vs the 4 runs' mean (calibrated on it)",
                                     load[k], kRealWheelLoads[k], wheel_tolerance, "N"));
  result.checks.push_back(Absolute("cross weight (W2 + W4) - (W1 + W3) vs the 4 runs' mean",
                                   cross, real_cross, cross_tolerance, "N"));

  Plot bars;
  bars.file = "gen4_loads.png";
  bars.title = "gen4 static wheel loads: simulated vs the real robot";
  bars.xlabel = "wheel";
  bars.ylabel = "vertical load [N]";
  bars.xtics = {"1 front right", "2 front left", "3 rear left", "4 rear right"};
  bars.y_from_zero = true;
  // SPEC 8: what the original simulator got.
  constexpr double kOriginal[4] = {595.6, 785.1, 670.2, 702.7};
  Series simulated{"simulated", {}, {}, "boxes"}, real{"real robot, mean of 4 runs", {}, {}, "boxes"};
  Series original{"original simulator", {}, {}, "boxes"};
  // Each run's loads as far as the data tells them: the mean's loads with
  // that run's cross weight (each wheel moved by a quarter of the change).
  Series runs{"real robot, each run (its cross weight)", {}, {}, "points"};
  for (int k = 0; k < 4; ++k) {
    simulated.x.push_back(k - 0.26);
    simulated.y.push_back(load[k]);
    real.x.push_back(k);
    real.y.push_back(kRealWheelLoads[k]);
    original.x.push_back(k + 0.26);
    original.y.push_back(kOriginal[k]);
    const double sign = (k == 1 || k == 3) ? 1.0 : -1.0;
    for (double c : kRunCrossWeights) {
      runs.x.push_back(k);
      runs.y.push_back(kRealWheelLoads[k] + sign * (c - real_cross) / 4.0);
    }
  }
  bars.series = {simulated, real, original, runs};
  const double total = load[0] + load[1] + load[2] + load[3];
  const double real_total = kRealWheelLoads[0] + kRealWheelLoads[1] + kRealWheelLoads[2] +
                            kRealWheelLoads[3];
  auto row = [&](const char* what, double simulated, double real) {
    return std::string("| ") + what + " | " + FormatFixed(simulated, 1) + " | " +
           FormatFixed(real, 1) + " | " + FormatFixed((simulated / real - 1.0) * 100.0, 2) +
           " |\n";
  };
  std::string run_rows;
  for (int i = 0; i < 4; ++i)
    run_rows += "| run " + std::to_string(i + 1) + " | " + FormatFixed(kRunCrossWeights[i], 0) +
                " | " + FormatFixed(cross - kRunCrossWeights[i], 1) + " | " +
                FormatFixed((cross - kRunCrossWeights[i]) / run_sd, 2) + " |\n";
  // The supports as the model file sets them (workpartner_gen4.xml writes
  // out the arithmetic): the tyre's stiffness of the whole contact, the one
  // the sim turns into ERP/CFM for the step (ResolveSurface), and how much
  // longer legs 2 and 4 are than legs 1 and 3 (their wheels sit lower).
  const model::Body& tyre_body = *run.sim().flat().bodies[static_cast<size_t>(wheel[0])].source;
  const model::World& world = run.sim().world();
  const model::SurfaceProperties contact = model::CombineSurfaces(
      model::ResolveSurface(world.FindMaterial(tyre_body.material), run.sim().params()),
      model::ResolveSurface(world.FindMaterial(world.plane_material), run.sim().params()));
  if (!contact.HasStiffness())
    throw Error("gen4_flat.xml: the tyre against the ground has no physical stiffness "
                "(workpartner_gen4.xml's gen4Tyre should give <stiffness>)");
  const double tyre_k = contact.stiffness;  // per wheel [N/m]
  double wheel_y[4];
  for (int k = 0; k < 4; ++k)
    wheel_y[k] = run.sim().flat().bodies[static_cast<size_t>(wheel[k])].pose.translation().y();
  const double leg_offset = (wheel_y[0] + wheel_y[2] - wheel_y[1] - wheel_y[3]) / 2.0;
  const double tyre_only_cross = 2.0 * tyre_k * leg_offset;
  const std::string shortfall =
      tyre_only_cross > 0.0 ? FormatFixed((1.0 - cross / tyre_only_cross) * 100.0, 1) : "n/a";
  result.notes =
      "gen4 (`gen4_flat.xml`, 275.15 kg) stands on flat ground; the wheel loads are the "
      "vertical contact forces on Wheel1..4 averaged over 0.5 s after 1.5 s of settling, at "
      "step " + FormatNumber(run.dt()) + " s.\n\n"
      "**Calibration, not validation.** The real robot's loads (SPEC 8) are the means of four "
      "test runs; gen4 is calibrated on them: four model values were chosen so that its four "
      "loads come out as these means, each from a cause the thesis names, and "
      "`workpartner_gen4.xml` lists every one with its reason (total mass from the loads' sum; "
      "the torso offset 5 cm to the left and the power pack in the rear half as the thesis "
      "describes them; the ballast Weight's place for the remaining mass distribution; legs 2 "
      "and 4 0.5235 mm longer for the cross weight). Agreement with the means is therefore by "
      "construction; what this experiment checks is that the sim keeps the calibration (at "
      "every step size: `tests/validate` runs it at 0.5, 1 and 2 ms and holds the loads within "
      "0.5 %), within what the data can tell. The validation on data not used here is the "
      "test track's wheel-force events (`test_track`).\n\n"
      "| sum [N] | simulated | real robot (mean) | difference [%] |\n|---|---|---|---|\n" +
      row("all wheels", total, real_total) +
      row("front (1 + 2)", pair(load, 0, 1), pair(kRealWheelLoads, 0, 1)) +
      row("left (2 + 3)", pair(load, 1, 2), pair(kRealWheelLoads, 1, 2)) +
      row("diagonal 1 + 3", pair(load, 0, 2), pair(kRealWheelLoads, 0, 2)) +
      row("diagonal 2 + 4", pair(load, 1, 3), pair(kRealWheelLoads, 1, 3)) +
      "\n**Against each real run.** The runs differ in their cross weight "
      "(W2 + W4) - (W1 + W3) (the team's records; SPEC 8 gives only the means). Simulated: " +
      FormatFixed(cross, 1) + " N.\n\n"
      "| run | cross weight [N] | simulated - run [N] | in run-to-run SDs |\n|---|---|---|---|\n" +
      run_rows +
      "\nRun-to-run: mean " + FormatFixed(run_mean, 1) + " N (the SPEC's means give " +
      FormatFixed(real_cross, 1) + " N), sample standard deviation s = " + FormatFixed(run_sd, 1) +
      " N, range " + FormatFixed(kRunCrossWeights[0] - kRunCrossWeights[3], 0) +
      " N. The tolerances follow from it: the mean of four runs is known to s / 2 = " +
      FormatFixed(cross_tolerance, 1) + " N on the cross weight, and since a change D of the "
      "cross weight moves each wheel by D / 4, to s / 8 = " + FormatFixed(wheel_tolerance, 2) +
      " N on a wheel. A single run's wheel loads differ from the mean by up to " +
      FormatFixed(widest / 4.0, 1) + " N (the plot's points: the mean's loads with each run's "
      "cross weight), 1.5 % of a wheel: agreement finer than that says nothing about the "
      "model's physics.\n\n"
      "**How the model makes these loads.** Four wheel loads have four degrees of freedom. "
      "The masses fix three of them: the total and, through the centre of mass, the "
      "front/rear and left/right splits. The fourth, the cross weight (real robot " +
      FormatFixed(real_cross, 1) + " N, " + FormatFixed(real_cross / real_total * 100.0, 1) +
      " % of its weight), only the supports can make: a rigid chassis on four "
      "equally stiff supports of equal length on flat ground has equal diagonals. gen4 "
      "stands on compliant tyres, " + FormatNumber(tyre_k) + " N/m per wheel (the tyre "
      "material's physical stiffness, shared by the two contact points of a wheel; the same "
      "spring at any step size), and legs 2 and 4 are " +
      FormatFixed(leg_offset * 1000.0, 4) + " mm longer than legs 1 and 3, standing in for "
      "the real robot's actively held legs. On flat ground the chassis settles halfway, so "
      "wheels 2 and 4 each carry k delta / 2 more and wheels 1 and 3 as much less: a cross "
      "weight of 2 k delta, " + FormatFixed(tyre_only_cross, 1) + " N if the tyres "
      "were the only compliance; the simulated cross weight is " + shortfall + " % less "
      "because ODE's joints in each leg yield a little in series with the tyre (the model "
      "file's arithmetic: 3.2 % at 1 ms). Each position row of a joint is a spring of "
      "jointStiffness, 2e7 N/m, with jointDamping, the same at any step (parameters.txt; "
      "docs/contacts.md), and the knee's hold a motor of motorCompliance, so the cross weight "
      "holds across step sizes (within 0.05 % a wheel between 0.5 and 2 ms). Given per step, "
      "as the original's globalERP / globalCFM did (a spring of ERP / (h CFM): 4e7, 2e7, 1e7 "
      "N/m), it read 205.7, 202.7 and 196.9 N.\n\n"
      "The left/right split is not the point-support value W z / t either: a cylinder wheel "
      "touches the ground along a line, so ODE makes two contact points 0.14 m apart per "
      "wheel and each wheel carries part of the roll moment itself, and the robot leans on "
      "its tyres, which moves its centre of mass over by its height times the roll angle. "
      "Together that makes left - right = 3.244 W z instead of W z / 0.3 = 3.333 W z, so the "
      "centre of mass sits 0.0216 m left of the middle instead of the point supports' "
      "0.0210 m (the ballast Weight's z is solved for it). `tests/models` checks the file's "
      "numbers against the real loads and `tests/validate` these simulated loads against the "
      "file's numbers. The original came within 4 % (cross weight 222 N); how it got its "
      "cross weight the SPEC does not say.";
  result.plots.push_back(bars);
  return result;
}

ExperimentResult Scanner(const Context& context) {
  ExperimentResult result;
  constexpr double kOmega = 0.01;       // [rad/s] SPEC 8
  constexpr double kWallDistance = 5.335;  // [m] scanner to wall, SPEC 8
  constexpr double kPeriod = 0.1;       // [s] between scans
  // Until the middle ray reaches the 10 m range (acos(0.5335) / 0.01 = 100.8 s).
  const double duration = context.quick ? 20.0 : 100.0;
  SimRun run(context, "scanner_wall.xml");
  const int scanner = run.Sensor("Scanner");
  const int turn = run.Joint("TorsoTurn");
  const model::Sensor& source = *run.sim().flat().sensors[static_cast<size_t>(scanner)].source;
  const int rays = source.rays;
  // The torso follows theta = omega t: sequences/gen2_scanner_sweep.xml
  // ramps the angle target omega (t + 1/P) step by step (the
  // AngleController's P term with the target one time constant ahead, so
  // the joint turns at omega without lag).
  run.PlaySequence("gen2_scanner_sweep.xml");
  double worst = 0.0, worst_middle = 0.0, worst_angle = 0.0;
  Series middle{"middle ray, simulated", {}, {}, "lines"};
  Series middle_exact{"L / cos(omega t)", {}, {}, "dashed"};
  Series edge{"ray 0 (alpha0 = -0.1), simulated", {}, {}, "lines"};
  Series edge_exact{"L / cos(alpha0 + omega t)", {}, {}, "dashed"};
  Series error_middle{"middle ray: simulated - L / cos(omega t)", {}, {}, "lines"};
  const int every = static_cast<int>(std::lround(kPeriod / run.dt()));
  run.RunUntil(duration, [&] {
    const double t = run.time();
    if (run.sim().step() % every != 0) return;
    const sensor_reading_t reading = run.sim().ReadSensor(scanner);
    const double theta = kOmega * t;
    worst_angle = std::max(worst_angle, std::abs(run.JointPosition(turn) - theta));
    for (int k = 0; k < rays; ++k) {
      const double alpha = -source.half_span + 2.0 * source.half_span * k / (rays - 1);
      const double exact = kWallDistance / std::cos(alpha + theta);
      if (exact >= source.range - 0.01) continue;  // beyond the range: reads max range
      const double error = reading.values[static_cast<size_t>(k)] - exact;
      worst = std::max(worst, std::abs(error));
      if (k == rays / 2) {
        worst_middle = std::max(worst_middle, std::abs(error));
        middle.x.push_back(t);
        middle.y.push_back(reading.values[static_cast<size_t>(k)]);
        middle_exact.x.push_back(t);
        middle_exact.y.push_back(exact);
        error_middle.x.push_back(t);
        error_middle.y.push_back(error * 1000.0);
      }
      if (k == 0) {
        edge.x.push_back(t);
        edge.y.push_back(reading.values[0]);
        edge_exact.x.push_back(t);
        edge_exact.y.push_back(exact);
      }
    }
  });
  result.sim_seconds = run.time();
  result.checks.push_back(Absolute("largest error, middle ray", worst_middle, 0.0, 0.001, "m"));
  result.checks.push_back(Absolute("largest error, all 11 rays", worst, 0.0, 0.001, "m"));
  Plot distances;
  distances.file = "scanner.png";
  distances.title = "gen2 scanner, wall 5.335 m ahead, torso turning at 0.01 rad/s";
  distances.xlabel = "t [s]";
  distances.ylabel = "distance [m]";
  distances.series = {middle, middle_exact, edge, edge_exact};
  Plot errors;
  errors.file = "scanner_error.png";
  errors.title = "Scanner: middle ray error vs d = L / cos(omega t)";
  errors.xlabel = "t [s]";
  errors.ylabel = "error [mm]";
  errors.series = {error_middle};
  result.plots = {distances, errors};
  result.notes =
      "gen2 stands 6 m from a static wall (`scanner_wall.xml`; the scanner sits on the torso's "
      "turning axis, 5.335 m from the wall). The torso turns at omega = 0.01 rad/s: every step "
      "`TorsoTurnMotor` gets the angle target omega (t + 1/P) with P = 100, so its velocity "
      "output is omega without lag (largest torso angle error " + FormatNumber(worst_angle) +
      " rad). Every 0.1 s the scanner is read; ray k, at alpha_k = -0.1 + 0.02 k rad from the "
      "torso's heading, must read L / cos(alpha_k + omega t) while that is within the 10 m "
      "range. The run lasts until the middle ray reaches the range (" + FormatNumber(duration) + " s).";
  return result;
}

ExperimentResult PoleTask(const Context& context) {
  ExperimentResult result;
  SimRun run(context, "pole_task.xml");
  const int pole = run.Body("Pole");
  const double pole_mass = run.sim().flat().bodies[static_cast<size_t>(pole)].source->mass;
  int wheel[4];
  for (int k = 0; k < 4; ++k) wheel[k] = run.Body("Wheel" + std::to_string(k + 1));
  // The sequence a user replays (sequences/gen3_pole_task.xml, written by
  // sequences/make_sequences.py): open loop, timed: drive 0.1 m into the
  // pole with the wheels ramped at 100 Hz, close the claws (at most
  // 10 N m), lift the elbows 0.3 rad, carry it 3 m at 2 rad/s, lower the
  // elbows, open the claws, back away 0.25 m.
  const SimRun::SequenceTimes sequence = run.PlaySequence("gen3_pole_task.xml");
  const double carry_start =
      sequence.PhaseStart("carry the pole 3 m to the second pair of cubes");
  const double end = sequence.end;

  Series load[4];
  for (int k = 0; k < 4; ++k) load[k].title = "Wheel" + std::to_string(k + 1);
  load[1].style = load[3].style = "dashed";  // gen3 is symmetric: 2 lies on 1, 4 on 3
  Series pole_height{"pole centre height", {}, {}, "lines"};
  Series pole_x{"pole centre x", {}, {}, "lines"};
  double front_sum = 0.0, rear_sum = 0.0;
  int carried = 0;
  const int every = static_cast<int>(std::lround(0.01 / run.dt()));
  run.RunUntil(end, [&] {
    const double now = run.time();
    double f[4];
    for (int k = 0; k < 4; ++k) f[k] = run.VerticalContactForce(wheel[k]);
    // Loads while the lifted pole is held still, before the drive.
    if (now > carry_start - 1.0 && now <= carry_start) {
      front_sum += f[0] + f[1];
      rear_sum += f[2] + f[3];
      ++carried;
    }
    if (run.sim().step() % every != 0) return;
    for (int k = 0; k < 4; ++k) {
      load[k].x.push_back(now);
      load[k].y.push_back(f[k]);
    }
    pole_height.x.push_back(now);
    pole_height.y.push_back(run.Position(pole).y());
    pole_x.x.push_back(now);
    pole_x.y.push_back(run.Position(pole).x());
  });
  result.sim_seconds = run.time();
  const sim::BodyReadout p = run.Read(pole);
  const Eigen::Vector3d axis = p.orientation * Eigen::Vector3d::UnitZ();  // the pole's length
  const double half_length = run.sim().flat().bodies[static_cast<size_t>(pole)].source->geometry.size.y() / 2.0;
  const Eigen::Vector3d end1 = p.position + half_length * axis, end2 = p.position - half_length * axis;
  const double front = front_sum / carried, rear = rear_sum / carried;
  result.checks.push_back(Relative("front/rear wheel load ratio holding the pole", front / rear,
                                   2.0, 0.10, ""));
  result.checks.push_back(Absolute("pole centre height (on the 1 m cubes: 1.05)", p.position.y(),
                                   1.05, 0.005, "m"));
  result.checks.push_back(Absolute("pole centre x (second pair centred at 4.2, 1 m deep)",
                                   p.position.x(), 4.2, 0.5, "m"));
  result.checks.push_back(AtLeast("pole ends' overlap with the cubes (|z| beyond 0.5)",
                                  std::min(std::abs(end1.z()), std::abs(end2.z())) - 0.5, 0.3, "m"));
  result.checks.push_back(Relative("cubes carry the pole's weight", run.VerticalContactForce(pole),
                                   pole_mass * 9.81, 0.02, "N"));
  result.checks.push_back(AtMost("pole speed at the end", p.linear_velocity.norm(), 0.001, "m/s"));
  result.notes =
      "gen3 (`pole_task.xml`) stands with its open claws just behind a 5 kg pole (r 0.05 m, "
      "2.4 m) lying across two 1 m cubes; two more cubes stand 3 m further on. The sequence "
      "is timed and open loop, as a sequencer file plays it: drive 0.1 m into the pole "
      "(wheels ramped at 100 Hz to 0.5 rad/s and back), close both claws (angle controllers "
      "towards -0.3 / +0.3 rad with at most 10 N m, so they squeeze rather than reach their "
      "targets), lift the elbows 0.3 rad, drive 3 m at 2 rad/s, lower the elbows to where "
      "the pole was picked up, open the claws and back away 0.25 m. The front/rear load "
      "ratio is taken while the lifted pole is held still before the drive: " +
      FormatNumber(front / 2.0) + " N per front wheel and " + FormatNumber(rear / 2.0) +
      " N per rear one (the original: about 700 / 350 N). The team's \"close to 2:1\" is "
      "checked within 10 %. The pole rests on the second pair when its centre is at the "
      "cube tops' height plus its radius, over the cubes, both ends on them, at rest, and "
      "the cubes carry its whole weight (the claws have let go).";
  Plot forces;
  forces.file = "pole_task.png";
  forces.title = "gen3 pole task: wheel loads over time";
  forces.xlabel = "t [s]";
  forces.ylabel = "vertical load [N]";
  forces.series = {load[0], load[1], load[2], load[3]};
  result.plots.push_back(forces);
  Plot height;
  height.file = "pole_task_height.png";
  height.title = "gen3 pole task: height of the pole's centre";
  height.xlabel = "t [s]";
  height.ylabel = "y [m]";
  height.series = {pole_height};
  result.plots.push_back(height);
  Plot along;
  along.file = "pole_task_x.png";
  along.title = "gen3 pole task: the pole carried from the first pair of cubes to the second";
  along.xlabel = "t [s]";
  along.ylabel = "x [m]";
  const double t_end = pole_x.x.empty() ? 0.0 : pole_x.x.back();
  along.series = {pole_x,
                  Series{"first pair (x 0.7 to 1.7)", {0.0, t_end, t_end, 0.0, 0.0},
                         {0.7, 0.7, 1.7, 1.7, 0.7}, "dashed"},
                  Series{"second pair (x 3.7 to 4.7)", {0.0, t_end, t_end, 0.0, 0.0},
                         {3.7, 3.7, 4.7, 4.7, 3.7}, "dashed"}};
  result.plots.push_back(along);
  return result;
}

namespace {

constexpr double kTrackWheelSpeed = 1.5;   // [rad/s] SPEC 8
constexpr double kTrackDuration = 104.75;  // [s] the original's run 4
constexpr double kTrackStart = 1.0;        // [s] standing before the wheels turn
// The wheels start at full speed: the robot's own acceleration moves load
// to the rear for about a second; events are looked for after that.
constexpr double kTrackSettled = kTrackStart + 2.0;

// One drive of gen4 with all wheels at 1.5 rad/s (sequences/gen4_test_track.xml).
struct TrackDrive {
  std::vector<double> times, xs;  // every 0.1 s; x of the wheel centres' mean
  // Front/rear load transfer (W1 + W2) - (W3 + W4) [N], the mean over the
  // 0.1 s before each sample, less its value standing before the start.
  std::vector<double> transfer_change;
  Series load[4];  // 1 s means against x
  double sim_seconds = 0.0;

  // The largest |transfer change| while the robot's middle is in [from, to].
  double LargestChange(double from, double to) const {
    double largest = 0.0;
    for (size_t i = 0; i < xs.size(); ++i)
      if (times[i] >= kTrackSettled && xs[i] >= from && xs[i] <= to)
        largest = std::max(largest, std::abs(transfer_change[i]));
    return largest;
  }
};

TrackDrive DriveTrack(const Context& context, const std::string& world,
                      const Eigen::Vector3d& move_robot, double duration) {
  SimRun run(context, world, move_robot);
  run.PlaySequence("gen4_test_track.xml");  // the wheels at kTrackWheelSpeed from kTrackStart
  int wheel[4];
  for (int k = 0; k < 4; ++k) wheel[k] = run.Body("Wheel" + std::to_string(k + 1));
  // The robot's place on the track: the mean of its four wheel centres
  // (the chassis would add its pitching to the speed).
  auto place = [&]() {
    double sum = 0.0;
    for (int k = 0; k < 4; ++k) sum += run.Position(wheel[k]).x();
    return sum / 4.0;
  };
  TrackDrive out;
  for (int k = 0; k < 4; ++k) out.load[k].title = "Wheel" + std::to_string(k + 1);
  const int every = static_cast<int>(std::lround(0.1 / run.dt()));
  const int per_second = static_cast<int>(std::lround(1.0 / run.dt()));
  double load_sum[4] = {0, 0, 0, 0};
  double transfer_sum = 0.0, standing_sum = 0.0;
  int standing_samples = 0;
  double standing = 0.0;
  run.RunUntil(kTrackStart + duration, [&] {
    double w[4];
    for (int k = 0; k < 4; ++k) {
      w[k] = run.VerticalContactForce(wheel[k]);
      load_sum[k] += w[k];
    }
    const double transfer = (w[0] + w[1]) - (w[2] + w[3]);
    transfer_sum += transfer;
    if (run.time() > kTrackStart - 0.5 && run.time() <= kTrackStart) {
      standing_sum += transfer;
      standing = standing_sum / ++standing_samples;
    }
    // Wheel loads as 1 s means: a rigid four-wheeler on uneven ground
    // rocks from one diagonal pair to the other many times a second.
    if (run.sim().step() % per_second == 0) {
      for (int k = 0; k < 4; ++k) {
        out.load[k].x.push_back(place());
        out.load[k].y.push_back(load_sum[k] / per_second);
        load_sum[k] = 0.0;
      }
    }
    if (run.sim().step() % every != 0) return;
    out.times.push_back(run.time());
    out.xs.push_back(place());
    out.transfer_change.push_back(transfer_sum / every - standing);
    transfer_sum = 0.0;
  });
  out.sim_seconds = run.time();
  return out;
}

// The places the thesis names, in x of the robot's middle: the features
// (scripts/make_test_track.py) widened by the 0.6 m from the middle to the
// axles, so that the robot feels a feature from when its front wheels reach
// it until its rear wheels leave it.
struct TrackPlace {
  const char* name;
  double from, to;
};
constexpr TrackPlace kSlope{"slope before the 20 m mark (16 to 19.5 m)", 16.0 - 0.6, 19.5 + 0.6};
constexpr TrackPlace kSecondBump{"second bump and after (24.75 to 27 m)", 24.75 - 0.6, 27.0 + 0.6};
constexpr TrackPlace kPlanks{"planks near 30 m (29.5 to 30.5 m)", 29.5 - 0.6, 30.5 + 0.6};
constexpr TrackPlace kLevel{"level snow (5 to 15 m)", 5.0, 15.0};
// The short drive of the unit tests: the robot starts 2.3 m before the
// planks' first edge (its middle at 27.2 m, on the level after the bumps,
// ground at -0.5 m), the level stretch before them its reference.
constexpr double kPlanksStartX = 27.2, kPlanksGround = -0.5;
constexpr TrackPlace kBeforePlanks{"level snow before the planks (27.4 to 28.7 m)", 27.4, 28.7};
// An event: the front/rear load transfer departs from its standing value by
// more than this many times its largest departure on the level snow.
constexpr double kEventFactor = 2.0;

}  // namespace

ExperimentResult TestTrack(const Context& context) {
  ExperimentResult result;
  constexpr double kTorque = 1000.0;  // [N m] the SPEC's default force per axis
  const double no_slip = kTrackWheelSpeed * 0.235;
  // The full drive, or (the unit tests) the planks alone.
  const bool planks_only = context.quick;
  const Eigen::Vector3d move = planks_only ? Eigen::Vector3d(kPlanksStartX, kPlanksGround + 0.005, 0)
                                           : Eigen::Vector3d::Zero();
  const double duration = planks_only ? (kPlanks.to + 0.3 - kPlanksStartX) / no_slip + 2.0
                                      : kTrackDuration;
  const TrackDrive track = DriveTrack(context, "test_track.xml", move, duration);
  // The control: the same drive on flat ground, from the same x.
  const TrackDrive flat = DriveTrack(context, "gen4_flat.xml",
                                     Eigen::Vector3d(move.x(), 0.0, 0.0), duration);
  result.sim_seconds = track.sim_seconds + flat.sim_seconds;
  const double x0 = track.xs.front();
  const double distance = track.xs.back() - x0;

  const TrackPlace reference = planks_only ? kBeforePlanks : kLevel;
  const double level = track.LargestChange(reference.from, reference.to);
  const double threshold = kEventFactor * level;
  std::vector<TrackPlace> places = {kPlanks};
  if (!planks_only) places = {kSlope, kSecondBump, kPlanks};
  if (!planks_only)
    result.checks.push_back(AtLeast("distance in 104.75 s (past the planks: 31.1 m)", distance,
                                    31.1, "m"));
  std::string table;
  for (const TrackPlace& place : places) {
    const double on_track = track.LargestChange(place.from, place.to);
    const double on_flat = flat.LargestChange(place.from, place.to);
    result.checks.push_back(AtLeast(std::string("load transfer event at the ") + place.name +
                                        ", largest change",
                                    on_track, threshold, "N"));
    result.checks.push_back(AtMost(std::string("no event on the flat control run at the ") +
                                       place.name + ", largest change",
                                   on_flat, threshold, "N"));
    table += std::string("| ") + place.name + " | " + FormatFixed(on_track, 0) + " | " +
             FormatFixed(on_flat, 0) + " |\n";
  }

  // Speed along the track, averaged over 1 s (10 samples), against x.
  Series speed{"speed along x, 1 s average", {}, {}, "lines"};
  for (size_t i = 10; i < track.xs.size(); ++i) {
    if (track.times[i] < kTrackSettled) continue;
    speed.x.push_back((track.xs[i] + track.xs[i - 10]) / 2.0);
    speed.y.push_back((track.xs[i] - track.xs[i - 10]) / (track.times[i] - track.times[i - 10]));
  }
  std::vector<double> level_speeds;
  for (size_t i = 0; i < speed.x.size(); ++i)
    if (speed.x[i] >= reference.from && speed.x[i] <= reference.to)
      level_speeds.push_back(speed.y[i]);
  const double level_speed = Mean(level_speeds);

  Plot speed_plot;
  speed_plot.file = "test_track_speed.png";
  speed_plot.title = "gen4 on the test track, wheels at 1.5 rad/s: speed along the track";
  speed_plot.xlabel = "x of the wheel centres' mean [m]";
  speed_plot.ylabel = "speed along x [m/s]";
  Series slip_free{"no slip: 1.5 rad/s x 0.235 m", {0.0, 40.0}, {no_slip, no_slip}, "dashed"};
  speed_plot.series = {speed, slip_free};
  Plot transfer_plot;
  transfer_plot.file = "test_track_events.png";
  transfer_plot.title = "gen4: front/rear load transfer change, test track vs flat control";
  transfer_plot.xlabel = "x of the wheel centres' mean [m]";
  transfer_plot.ylabel = "(W1 + W2) - (W3 + W4) less its standing value [N]";
  Series on_track{"test track", {}, {}, "lines"}, on_flat{"flat control run", {}, {}, "lines"};
  for (size_t i = 0; i < track.xs.size(); ++i)
    if (track.times[i] >= kTrackSettled) {
      on_track.x.push_back(track.xs[i]);
      on_track.y.push_back(track.transfer_change[i]);
    }
  for (size_t i = 0; i < flat.xs.size(); ++i)
    if (flat.times[i] >= kTrackSettled) {
      on_flat.x.push_back(flat.xs[i]);
      on_flat.y.push_back(flat.transfer_change[i]);
    }
  const double x_last = track.xs.back();
  Series bounds{"event threshold (+-)", {x0, x_last, x_last, x0},
                {threshold, threshold, -threshold, -threshold}, "dashed"};
  transfer_plot.series = {on_track, on_flat, bounds};
  Plot load_plot;
  load_plot.file = "test_track_loads.png";
  load_plot.title = "gen4 on the test track: wheel loads, 1 s means";
  load_plot.xlabel = "x of the wheel centres' mean [m]";
  load_plot.ylabel = "vertical load [N]";
  load_plot.series = {track.load[0], track.load[1], track.load[2], track.load[3]};
  result.plots = {speed_plot, transfer_plot, load_plot};
  // Along the slope the wheels roll a longer path than its x: at 22 % the
  // no-slip speed along x is 0.3525 cos(12.6 deg) = 0.344 m/s.
  result.notes =
      "gen4 on the heightfield track (`test_track.xml`, from `scripts/make_test_track.py`; our "
      "reconstruction of the original's run 4) with all four wheels at 1.5 rad/s from t = 1 s "
      "(JointController, " + FormatNumber(kTorque) + " N m, the SPEC's default force per axis)" +
      (planks_only ? std::string(", here only from 2.3 m before the planks (the unit tests' "
                                 "short drive)")
                   : std::string(" for 104.75 s, the original's run time")) +
      ". It covered " + FormatNumber(distance) + " m in " + FormatNumber(duration) + " s (no slip: " +
      FormatNumber(no_slip * duration) + " m, a bound: along the slope and over the bumps the wheels "
      "roll a path longer than its x; the original simulator: 34.5 m in 104.75 s). Speed "
      "along x, averaged over 1 s: " + FormatNumber(level_speed) + " m/s on the " + reference.name +
      " (" + FormatFixed((1.0 - level_speed / no_slip) * 100.0, 2) +
      " % below no slip: the tyres' slip under the wheels' drive torque).\n\n"
      "**Validation on data not used in the calibration: the wheel-force events.** The thesis "
      "gives the real robot's wheel forces on this track only as figures, and names the places "
      "where they show events: the slope before the 20 m mark, after the second bump, the "
      "planks near 30 m. The comparison is qualitative, as the thesis's was: is there an event "
      "at each of those places, and none where the ground is only snow? An event here is a "
      "change of the front/rear load transfer (W1 + W2) - (W3 + W4) (0.1 s means, less its "
      "value standing before the start) of more than " + FormatNumber(kEventFactor) +
      " times its largest change on the " + reference.name + " (" + FormatFixed(level, 0) +
      " N there, so the threshold is " + FormatFixed(threshold, 0) + " N). The front/rear "
      "transfer is what a slope, a bump or an edge makes (the robot pitches, or one axle "
      "climbs); the rocking from one diagonal pair of wheels to the other on the snow's "
      "unevenness (the loads plot) cancels in it. The same drive on flat ground "
      "(`gen4_flat.xml`, the same start x) is the control: a track without the features "
      "fails these checks at every place for want of the events, not for a slower speed.\n\n"
      "| place (robot middle within 0.6 m) | largest change, test track [N] | flat control [N] |\n"
      "|---|---|---|\n" + table +
      "\nThe wheel loads (1 s means, against the position on the track) show the robot rocking "
      "from one diagonal pair of wheels to the other: gen4's legs are held stiffly and its "
      "only compliance is in its tyres (3.4 mm of sag under its weight, against the snow's "
      "1.5 cm unevenness), so a diagonal pair can take most of the weight while the other is "
      "nearly unloaded, the roles swapping every metre or two.";
  return result;
}

}  // namespace simpartner::validate
