// The validation experiments, shortened where they run for minutes (fewer
// laps, a shorter scan, three gait cycles, the test track's planks alone),
// with the team's tolerances. Targets are written here
// from SPEC 8 and from physics, never taken from sp_validate.
//
// Where a SPEC 8 target is physically wrong (docs/validation explains
// why), the test asserts what physics does predict.
#include <gtest/gtest.h>

#include <map>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/diagnostic.h"
#include "simpartner/model/loader.h"
#include "simpartner/parameters.h"
#include "simpartner/sim/controllers.h"
#include "simpartner/validate/experiment.h"

namespace simpartner::validate {
namespace {

Context Quick() {
  Context context;
  context.models_dir = std::string(SP_SOURCE_DIR) + "/models";
  context.quick = true;
  return context;
}

// Each experiment runs once per test program: several tests read one run
// (the circles take minutes under the sanitizers), and a run is
// deterministic, so a second would give the same numbers.
ExperimentResult RunNamed(const char* name) {
  static std::map<std::string, ExperimentResult> runs;
  if (const auto it = runs.find(name); it != runs.end()) return it->second;
  const Experiment* experiment = FindExperiment(name);
  EXPECT_NE(experiment, nullptr) << name;
  if (experiment == nullptr) return ExperimentResult{};
  ExperimentResult result = RunExperiment(*experiment, Quick());
  EXPECT_EQ(result.error, "") << name;
  runs.emplace(name, result);
  return result;
}

constexpr double kG = 9.81;

TEST(Validation, FreeFallErrorSlopeIsGDtOverTwo) {
  const ExperimentResult r = RunNamed("free_fall");
  for (const double dt : {0.02, 0.01, 0.005, 0.001}) {
    std::ostringstream label;
    label << "error slope, g 9.81, dt " << dt << " s";
    EXPECT_NEAR(r.Measured(label.str()), kG * dt / 2.0, 0.01 * kG * dt / 2.0) << label.str();
  }
  EXPECT_NEAR(r.Measured("error slope, g 50, dt 0.001 s"), 0.025, 0.01 * 0.025);
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, StepTimeCoversEveryStepOfEveryRunAndNothingElse) {
  const ExperimentResult r = RunNamed("free_fall");
  // 10 s at dt 0.02, 0.01, 0.005 and 0.001 s with g 9.81, and at 0.001 s
  // with g 50.
  EXPECT_EQ(r.stepping.steps, 500 + 1000 + 2000 + 10000 + 10000);
  EXPECT_GT(r.stepping.seconds, 0.0);
  // The steps alone: less than the experiment's wall time, which also
  // loads the worlds and analyses every step.
  EXPECT_LT(r.stepping.seconds, r.wall_seconds);
  EXPECT_GT(r.stepping.MicrosecondsPerStep(), 0.0);
  EXPECT_TRUE(std::isnan(StepTiming{}.MicrosecondsPerStep()));
}

TEST(Validation, ThrownBodyKeepsItsHorizontalVelocity) {
  const ExperimentResult r = RunNamed("free_fall_thrown");
  EXPECT_LE(r.Measured("largest horizontal error"), 1e-9);
}

TEST(Validation, SlidingCubeFollowsCoulombFriction) {
  const ExperimentResult r = RunNamed("sliding_cube");
  const double v0 = 10.0, mu = 0.5;
  EXPECT_LE(r.Measured("largest |v - (v0 - mu g t)|"), 0.01 * v0);
  EXPECT_LE(r.Measured("largest step-to-step deviation"), 0.01 * mu * kG * 0.001);
  EXPECT_NEAR(r.Measured("sliding distance"), v0 * v0 / (2 * mu * kG), 0.01 * 10.19);
}

TEST(Validation, TwoSpheresBounceSymmetrically) {
  const ExperimentResult r = RunNamed("two_spheres");
  EXPECT_LE(r.Measured("largest mirror asymmetry"), 1e-9);
  // Touching at centre distance 1.0, found within one 1 ms step of 2 m/s.
  EXPECT_NEAR(r.Measured("closest centre distance"), 1.0, 0.002 + 1e-9);
  EXPECT_NEAR(r.Measured("relative speed after the bounce"), 2.0, 0.02);
}

// The circles as the thesis ran them: 0.5 along each wheel's rolling
// direction, 1.0 across it. A rigid articulated vehicle whose wheels keep
// their paths turns where its steering points: the axle centres on
// a cot(alpha/2), the mean of the four wheels on a cot(alpha/2) cos(alpha/2)
// (a = 0.6 m, SPEC 7).
double AxleCentres(double alpha) { return 0.6 / std::tan(alpha / 2.0); }

// Both points of a thesis-friction circle within `tolerance` (relative).
void ExpectTheSteeringsCircle(const ExperimentResult& r, double alpha, double tolerance) {
  const double axle = AxleCentres(alpha), legs = axle * std::cos(alpha / 2.0);
  EXPECT_NEAR(r.Measured("radius at the axle centres, thesis friction"), axle, tolerance * axle);
  EXPECT_NEAR(r.Measured("radius of the mean of the four wheels, thesis friction"), legs,
              tolerance * legs);
}

TEST(Validation, CircleEqualSpeedsWithTheThesisFrictionFollowsTheSteering) {
  ExpectTheSteeringsCircle(RunNamed("circle_equal"), 0.2972, 0.0003);
}

// Isotropic friction along the slip: with equal wheel speeds every wheel
// slides, and the vehicle turns outside the steering's circle (the Coulomb
// cone's steady state of the same vehicle: 4.68 to 4.75 m with the run's
// loads), the same for both mu.
TEST(Validation, CircleEqualSpeedsIsotropicSlidesOutsideTheSteeringsCircle) {
  const ExperimentResult r = RunNamed("circle_equal");
  const double r05 = r.Measured("radius, isotropic mu 0.5"), r1 = r.Measured("radius, isotropic mu 1");
  for (const double radius : {r05, r1}) {
    EXPECT_GT(radius, AxleCentres(0.2972) * 1.10);
    EXPECT_LT(radius, 4.93);
  }
  EXPECT_NEAR(r05 / r1, 1.0, 0.01);
}

// 1.00 / 1.10 m/s with the thesis's friction: tighter than the thesis's own
// 0.03 % at the point it measured; the world CFM on the friction
// rows made this +0.11 %.
TEST(Validation, CircleDifferentialSpeedsWithTheThesisFrictionWithinThreeHundredthsOfAPercent) {
  const ExperimentResult r = RunNamed("circle_differential");
  ExpectTheSteeringsCircle(r, 0.2, 0.0003);
  EXPECT_LE(r.Measured("worst deviation from the fitted circle, thesis friction"), 0.001);
}

TEST(Validation, CircleDifferentialSpeedsIsotropicAndMatchedSpeeds) {
  const ExperimentResult r = RunNamed("circle_differential");
  // The outer wheels at 1.10 m/s are slower than the 1.1056 rolling on the
  // steering's circle needs: they slide, while the inner wheels roll on the
  // edge nearer the vehicle's middle, which carries more than half their
  // load and can hold the rest within mu N (see the report). The vehicle
  // then rides the steering's circle.
  EXPECT_NEAR(r.Measured("radius, isotropic mu 1 (self-consistency"), AxleCentres(0.2),
              0.003 * AxleCentres(0.2));
  EXPECT_LT(r.Measured("friction the inner wheels' held rim edges need"), 1.0);
  // Outer wheels at (5.98 + 0.3) / (5.98 - 0.3) = 1.1056 m/s: no slip needed.
  EXPECT_NEAR(r.Measured("radius, 1.00 / 1.10563 m/s (matched)"), AxleCentres(0.2),
              0.0025 * AxleCentres(0.2));
  EXPECT_LE(r.Measured("worst deviation from the fitted circle, matched"), 0.001);
}

TEST(Validation, ScannerReadsLOverCosWithinAMillimetre) {
  const ExperimentResult r = RunNamed("scanner");
  EXPECT_LE(r.Measured("largest error, middle ray"), 0.001);
  EXPECT_LE(r.Measured("largest error, all 11 rays"), 0.001);
}

TEST(Validation, PoleTaskSetsThePoleOnTheSecondPair) {
  const ExperimentResult r = RunNamed("pole_task");
  // The original: about 700 N per front wheel, 350 N per rear one.
  EXPECT_NEAR(r.Measured("front/rear wheel load ratio"), 2.0, 0.2);
  // On the second pair of 1 m cubes (tops at 1.0, centred at x 4.2, |z| 0.5 to 1.5).
  EXPECT_NEAR(r.Measured("pole centre height"), 1.05, 0.005);
  EXPECT_NEAR(r.Measured("pole centre x"), 4.2, 0.5);
  EXPECT_GE(r.Measured("pole ends' overlap"), 0.3);
  EXPECT_NEAR(r.Measured("cubes carry the pole's weight"), 5.0 * kG, 0.02 * 5.0 * kG);
  EXPECT_LE(r.Measured("pole speed at the end"), 0.001);
}

// gen4 is calibrated on the mean of the real robot's four runs (SPEC 8's
// loads). The runs' cross weights (W2 + W4) - (W1 + W3) were 237, 219, 182
// and 172 N (the team's records of the runs): the mean of four is known to s / 2 on the cross
// weight and s / 8 on a wheel (a change D of the cross weight moves each
// wheel by D / 4), s the runs' sample standard deviation (30.6 N). The
// calibration must hold in the sim within that; SPEC 8 asks for 2 %.
TEST(Validation, Gen4StaticLoadsKeepTheCalibrationWithinTheRunsSpread) {
  const ExperimentResult r = RunNamed("gen4_loads");
  const double real[4] = {579.15, 774.90, 669.12, 676.03};
  const double runs[4] = {237.0, 219.0, 182.0, 172.0};
  const double mean = (runs[0] + runs[1] + runs[2] + runs[3]) / 4.0;
  double squares = 0.0;
  for (const double c : runs) squares += (c - mean) * (c - mean);
  const double s = std::sqrt(squares / 3.0);
  EXPECT_NEAR(s, 30.6, 0.05);
  double w[4];
  for (int k = 0; k < 4; ++k) {
    const std::string wheel = "Wheel" + std::to_string(k + 1);
    w[k] = r.Measured(wheel + " load");
    EXPECT_NEAR(w[k], real[k], s / 8.0) << wheel;
    EXPECT_NEAR(w[k], real[k], 0.02 * real[k]) << wheel;
  }
  EXPECT_NEAR((w[1] + w[3]) - (w[0] + w[2]), (real[1] + real[3]) - (real[0] + real[2]), s / 2.0);
  EXPECT_NEAR(r.Measured("cross weight"), (w[1] + w[3]) - (w[0] + w[2]), 1e-9);
}

// What gen4's masses and supports must give on flat ground at step h, from
// the robot file and the default parameters (not from the SPEC's loads; the
// file's comment derives its numbers from those, tests/models checks that):
//  - the total: the weight W = M g;
//  - each wheel stands on its tyre, a physical stiffness k of the whole
//    contact (the same at any step), shared by two contact points at its
//    faces (a cylinder on a plane touches along a line), k_p = k / 2, in
//    series with its leg: the position rows of the axle, knee and hip
//    hinges (each a spring of jointStiffness k_j, the same at any step)
//    and the knee's hold (torque kHoldGain / c_m per radian, c_m the
//    motor's motorCompliance, at the knee's horizontal distance l from
//    the axle): k_v = 1 / (1 / k + 3 / k_j + l^2 c_m / G);
//  - cross weight: legs 2 and 4 are delta longer (their wheels sit delta
//    lower in the file); on flat ground the chassis settles halfway, so
//    (W2 + W4) - (W1 + W3) = 2 k_v delta;
//  - front/rear and left/right: moments about the ground-level axes, with
//    the robot leaning on its supports by an angle that moves the centre of
//    mass over by its height h_c times the angle; in roll each wheel also
//    carries a moment through its two contact points (+-w, w half the
//    wheel's width):
//      front - rear = 4 k_v a W x / (4 k_v a^2 - W h_c),
//      left - right = 4 k_v t W z_left / (4 k_v t^2 + 8 k_p w^2 - W h_c).
struct Gen4Sums {
  double weight, front_minus_rear, left_minus_right, cross;
};

// The same at any step size: every compliance in it is physical.
Gen4Sums PredictGen4Sums() {
  const std::string file = std::string(SP_SOURCE_DIR) + "/models/robots/workpartner_gen4.xml";
  const model::RobotLoadResult loaded = model::LoadRobotFile(file);
  if (!loaded.robot) throw Error(loaded.diagnostics.Format());
  const model::Robot& robot = *loaded.robot;
  const Parameters params;  // the defaults, as the experiment runs

  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  for (const model::Body& b : robot.bodies) com += b.mass * (b.pose * b.com);
  com /= robot.TotalMass();
  const double weight = robot.TotalMass() * kG;

  const model::Body* wheel[4];
  for (int k = 0; k < 4; ++k) {
    wheel[k] = robot.FindBody("Wheel" + std::to_string(k + 1));
    if (wheel[k] == nullptr) throw Error("gen4 has no Wheel" + std::to_string(k + 1));
  }
  // The tyre against gen4_flat.xml's ground, which has no material: the
  // tyre's stiffness is far below the default contact's at these steps.
  double k_wheel = 0.0;
  for (const model::Material& m : robot.materials)
    if (m.name == wheel[0]->material && m.HasStiffness()) k_wheel = *m.stiffness;
  if (k_wheel <= 0.0) throw Error("gen4's tyre material has no stiffness");
  const double k_point = k_wheel / 2.0;
  const double half_width = wheel[0]->geometry.size.y() / 2.0;  // cylinder length / 2
  const model::Joint* knee = robot.FindJoint("Knee1");
  const model::Joint* axle = robot.FindJoint("Axle1");
  if (knee == nullptr || axle == nullptr) throw Error("gen4 has no Knee1 or Axle1");
  const double lever = std::abs(knee->anchor.x() - axle->anchor.x());
  const double leg_compliance =
      3.0 / params.jointStiffness + lever * lever * params.motorCompliance / sim::kHoldGain;
  const double k_v = 1.0 / (1.0 / k_wheel + leg_compliance);
  const double a = std::abs(wheel[0]->pose.translation().x());
  const double t = std::abs(wheel[0]->pose.translation().z());
  const double delta = (wheel[0]->pose.translation().y() + wheel[2]->pose.translation().y() -
                        wheel[1]->pose.translation().y() - wheel[3]->pose.translation().y()) /
                       2.0;
  const double height = com.y() - weight / (4.0 * k_wheel);  // less the tyres' sag
  Gen4Sums sums;
  sums.weight = weight;
  sums.front_minus_rear = 4.0 * k_v * a * weight * com.x() / (4.0 * k_v * a * a - weight * height);
  sums.left_minus_right =
      4.0 * k_v * t * weight * -com.z() /
      (4.0 * k_v * t * t + 8.0 * k_point * half_width * half_width - weight * height);
  sums.cross = 2.0 * k_v * delta;
  return sums;
}

// Tolerance 0.1 % of the weight (2.7 N) on each sum: the model leaves out
// the legs' yielding sideways, the chassis' twist at the Turner hinge and
// the contact points' shift as the wheels tilt, each well under 0.1 % of
// the ~200 N differences by the same arithmetic (rows of 2e7 N m/rad
// against moments of tens of N m); 2.7 N on a sum is 0.7 N on a wheel.
void ExpectGen4LoadsFollowTheSupports(const ExperimentResult& r, double h) {
  const Gen4Sums predicted = PredictGen4Sums();
  double w[4];
  for (int k = 0; k < 4; ++k) w[k] = r.Measured("Wheel" + std::to_string(k + 1) + " load");
  const double tolerance = 0.001 * predicted.weight;
  EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], predicted.weight, tolerance) << "h " << h;
  EXPECT_NEAR((w[0] + w[1]) - (w[2] + w[3]), predicted.front_minus_rear, tolerance) << "h " << h;
  EXPECT_NEAR((w[1] + w[2]) - (w[0] + w[3]), predicted.left_minus_right, tolerance) << "h " << h;
  EXPECT_NEAR((w[1] + w[3]) - (w[0] + w[2]), predicted.cross, tolerance) << "h " << h;
}

TEST(Validation, Gen4StaticLoadsFollowTheMassesAndTheSupports) {
  ExpectGen4LoadsFollowTheSupports(RunNamed("gen4_loads"), Parameters().stepsize);
}

// The tyre, the legs' joint rows and the knee's hold are physical (a
// spring, springs, a motor's velocity per force), so the loads do not
// depend on the step size: within 0.05 % on every wheel between 0.5, 1
// and 2 ms. With the joints per step (jointStiffness=0: globalERP 0.2,
// globalCFM 1e-5), the cross weight was 205.7, 202.7 and 196.9 N, and
// wheel 1 moved 0.4 %; the tyre given per step (ERP 1/36, CFM 1/3600, the
// same spring at 1 ms only) moved wheel 1 by 8.6 %.
TEST(Validation, Gen4StaticLoadsAgreeAcrossStepSizes) {
  const Experiment* experiment = FindExperiment("gen4_loads");
  ASSERT_NE(experiment, nullptr);
  double lowest[4], highest[4];
  std::fill(std::begin(lowest), std::end(lowest), 1e9);
  std::fill(std::begin(highest), std::end(highest), -1e9);
  const double steps[] = {0.0005, 0.001, 0.002};
  std::vector<ExperimentResult> runs;
  for (const double h : steps) {
    Context context = Quick();
    context.params.stepsize = h;
    runs.push_back(RunExperiment(*experiment, context));
    ASSERT_EQ(runs.back().error, "") << "h " << h;
    for (int k = 0; k < 4; ++k) {
      const double load = runs.back().Measured("Wheel" + std::to_string(k + 1) + " load");
      lowest[k] = std::min(lowest[k], load);
      highest[k] = std::max(highest[k], load);
    }
  }
  for (int k = 0; k < 4; ++k)
    EXPECT_LE(highest[k] / lowest[k] - 1.0, 0.0005) << "Wheel" << k + 1 << ": " << lowest[k]
                                                   << " to " << highest[k] << " N";
  for (size_t i = 0; i < runs.size(); ++i) ExpectGen4LoadsFollowTheSupports(runs[i], steps[i]);
}

// The 18 kg gen1 on ice (mu 0.025), wheels at 1 rad/s: the ice pushes it
// with at most mu m g until the wheels roll, then nothing resists.
TEST(Validation, SkiddingWheelsAccelerateAtMuGToTheWheelsSpeed) {
  const ExperimentResult r = RunNamed("skid");
  EXPECT_NEAR(r.Measured("acceleration while the wheels skid"), 0.025 * kG, 0.05 * 0.025 * kG);
  EXPECT_NEAR(r.Measured("speed after 10 s"), 1.0 * 0.235, 0.01 * 0.235);
}

// The gaits (three cycles here): with the held wheels within mu N (the
// report derives the forces), the body advances one 0.25 m stride per
// cycle; the legs' lag and the rolling under moving legs are within 10 %.
// On flat ice rolling is faster than either gait (the SPEC's ordering,
// from the original's non-physical 0.0038 m/s, is not the physics).
TEST(Validation, CaterpillarAdvancesAStridePerCycle) {
  const ExperimentResult r = RunNamed("caterpillar");
  EXPECT_NEAR(r.Measured("caterpillar speed vs stride"), 0.25 / 5.0, 0.10 * 0.25 / 5.0);
  EXPECT_LT(r.Measured("caterpillar speed / skidding wheels' speed"), 1.0);
}

// The pitch [rad] of a gen1 calf (knee to foot, from forward towards up)
// with its foot `ahead` of the hip, the hip 0.48 m above the axle and both
// links 0.3 m: the knee is where the two links' circles meet, behind the
// hip-foot line for the front legs and ahead of it for the rear ones.
double CalfPitchFromKnee(bool front, double ahead) {
  const double hip_x = 0.0, hip_y = 0.48, link = 0.3;
  const double dx = ahead - hip_x, dy = -hip_y, d = std::hypot(dx, dy);
  const double along = d / 2.0, across = std::sqrt(link * link - along * along);
  const double mid_x = hip_x + dx / 2.0, mid_y = hip_y + dy / 2.0;
  // The unit normal (-dy, dx) / d points forward-up of the line downwards.
  const double side = front ? -1.0 : 1.0;
  const double knee_x = mid_x + side * across * (-dy / d);
  const double knee_y = mid_y + side * across * (dx / d);
  return std::atan2(0.0 - knee_y, ahead - knee_x);
}

// A held wheel keeps its angle to its calf, so in the push (each foot from
// 0.25 m ahead of its hip to below it) it rolls r times its calf's pitch
// change: the part of rolking's creep that needs no slip at all.
TEST(Validation, RollingWalkingAdvancesAStridePerCycle) {
  const ExperimentResult r = RunNamed("rolking");
  EXPECT_NEAR(r.Measured("rolking speed vs stride"), 0.25 / 7.0, 0.10 * 0.25 / 7.0);
  EXPECT_LT(r.Measured("rolking speed / skidding wheels' speed"), 1.0);
  const double front = 0.235 * (CalfPitchFromKnee(true, 0.25) - CalfPitchFromKnee(true, 0.0));
  const double rear = 0.235 * (CalfPitchFromKnee(false, 0.25) - CalfPitchFromKnee(false, 0.0));
  EXPECT_NEAR(front, 0.0665, 0.0001);  // 0.283 rad
  EXPECT_NEAR(rear, 0.1592, 0.0001);   // 0.677 rad
  EXPECT_NEAR(r.Measured("rolking front held wheels' roll in the push"), front, 0.01 * front);
  EXPECT_NEAR(r.Measured("rolking rear held wheels' roll in the push"), rear, 0.01 * rear);
}

// The test track's planks alone (the unit tests' short drive, from 2.3 m
// before them): climbing a 5 cm plank edge, one axle rises and the load
// shifts between front and rear; on the level snow before them the
// diagonal rocking cancels in that sum. The same drive on flat ground has
// no such event, so a track without planks fails here.
TEST(Validation, TestTrackPlanksMakeALoadTransferEventAFlatRunDoesNot) {
  const ExperimentResult r = RunNamed("test_track");
  ASSERT_EQ(r.error, "");
  const double on_track = r.Measured("load transfer event at the planks");
  const double on_flat = r.Measured("no event on the flat control run at the planks");
  // A 5 cm edge on a 0.235 m wheel: the axle rises 5 cm over 1.2 m of
  // wheelbase, a pitch of 2.4 degrees; with the centre of mass 0.75 m up
  // the weight alone shifts W 0.75 tan(2.4 deg) / 0.6 = 140 N.
  EXPECT_GT(on_track, 100.0);
  EXPECT_LT(on_flat, 0.1 * on_track);
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, RollingSphereComesToRest) {
  const ExperimentResult r = RunNamed("rolling_sphere");
  // rho 2 mm, r 0.1 m: a = 5/7 rho g / r = 0.1401 m/s^2 from 1 m/s.
  const double a = 5.0 / 7.0 * 0.002 * kG / 0.1;
  EXPECT_LE(r.Measured("speed at 1.5 x the stopping time"), 0.001);
  EXPECT_NEAR(r.Measured("time to come to rest"), 1.0 / a, 0.05 / a);
  EXPECT_NEAR(r.Measured("rolling distance"), 1.0 / (2 * a), 0.05 / (2 * a));
  EXPECT_NEAR(r.Measured("sphere without rolling friction keeps rolling"), 1.0, 0.01);
}

TEST(Validation, PassivePendulumCreatesNoEnergy) {
  const ExperimentResult r = RunNamed("pendulum_energy");
  EXPECT_LE(r.Measured("highest turning-point energy"), 1e-5);
  EXPECT_LE(r.Measured("energy at the last turning point"), 0.0);
  // 2 pi sqrt(2 L / 3 g) for small swings, times 2 K(sin 45 deg) / pi.
  EXPECT_NEAR(r.Measured("period"), 2 * M_PI * std::sqrt(2.0 / (3 * kG)) * 1.18034, 0.005 * 1.93);
}

// The soil experiments (shortened: fewer soils, loads and slips).
// Targets from the shipped library's figures (models/soils/wong2008.xml)
// and the closed forms written out here.
TEST(Validation, WheelOnDrySandRestsAtBekkersSinkage) {
  const ExperimentResult r = RunNamed("soil_sinkage");
  // Bekker's static sinkage of a 50 kg wheel (r 0.3 m, b 0.2 m) on dry
  // sand: 17.926 mm (docs/soil.md, tests/sim_core/soil_contact_test.cpp).
  EXPECT_NEAR(r.Measured("sinkage, dry sand, 490.5 N"), 17.926, 0.005 * 17.926);
  // The load grows as z^(n + 1/2): twice the load, 2^(1/1.6) the sinkage
  // (within 1 %: the arc's shape is not quite that power).
  EXPECT_NEAR(r.Measured("sinkage, dry sand, 981 N") / r.Measured("sinkage, dry sand, 490.5 N"),
              std::pow(2.0, 1 / 1.6), 0.01 * std::pow(2.0, 1 / 1.6));
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, TowedWheelsResistanceIsBekkersLessTheRebound) {
  const ExperimentResult r = RunNamed("soil_compaction");
  // Dry sand (n 1.1, k_c 0.99, k_phi 1528.43; unloading k_0 0 and A_u
  // 503,000 kPa/m^2, so k_u = max(A_u z, n p(z) / z)), b 0.2 m, at the
  // sinkage the sim reached: b (k_c/b + k_phi) z^(n+1) / (n+1) less
  // b p(z)^2 / (2 k_u).
  const double z = r.Measured("sinkage, dry sand") / 1000, b = 0.2;
  const double k = (0.99 / b + 1528.43) * 1e3, p = k * std::pow(z, 1.1);
  const double k_u = std::max(503000e3 * z, 1.1 * p / z);
  const double resistance = b * k * std::pow(z, 2.1) / 2.1 - b * p * p / (2 * k_u);
  EXPECT_NEAR(r.Measured("compaction resistance, dry sand"), resistance, 0.01 * resistance);
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, DrawbarPullGrowsWithSlipAsWongsIntegral) {
  const ExperimentResult r = RunNamed("soil_traction");
  const double low = r.Measured("drawbar pull, dry sand, slip 0.1");
  const double high = r.Measured("drawbar pull, dry sand, slip 0.6");
  // At most the soil's shear strength over the contact less the
  // compaction: (c A + W tan phi) with W = 490.5 N, A < 0.2 x 0.25 m^2.
  EXPECT_GT(low, 0.0);
  EXPECT_GT(high, 3 * low);
  EXPECT_LT(high, 1.04e3 * 0.05 + 490.5 * std::tan(28 * M_PI / 180));
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, SoilFiguresDoNotDependOnTheStep) {
  const ExperimentResult r = RunNamed("soil_step_size");
  for (const char* figure : {"standing sinkage", "rolling sinkage, slip 0.3"}) {
    const double at_1ms = r.Measured(std::string(figure) + ", 1 ms");
    EXPECT_NEAR(r.Measured(std::string(figure) + ", 0.5 ms"), at_1ms, 0.002 * at_1ms) << figure;
    EXPECT_NEAR(r.Measured(std::string(figure) + ", 2 ms"), at_1ms, 0.002 * at_1ms) << figure;
  }
  const double pull = r.Measured("drawbar pull, slip 0.3, 1 ms");
  EXPECT_NEAR(r.Measured("drawbar pull, slip 0.3, 2 ms"), pull, 0.002 * 490.5);
  EXPECT_TRUE(r.Passed());
}

TEST(Validation, SecondPassInTheRutSinksLess) {
  const ExperimentResult r = RunNamed("soil_multipass");
  const double first = r.Measured("first pass's sinkage, dry sand");
  const double second = r.Measured("second pass's sinkage, dry sand");
  EXPECT_GT(second, first);             // below the untouched surface, in the rut
  EXPECT_LT(second - first, 0.5 * first);  // but it deepens the rut far less
  EXPECT_TRUE(r.Passed());
}

// soil_robot, quick: gen3 on the shipped dry sand. The rear wheels run
// in the front wheels' ruts, so they sink to about the ruts' depth, not to
// a fresh wheel's (25.5 mm at their load, the closed form), and the robot
// goes slower than on hard ground.
TEST(Validation, Gen3OnSandMatchesTheSingleWheelInItsRuts) {
  const ExperimentResult r = RunNamed("soil_robot");
  const double front = r.Measured("sinkage, dry_sand, Wheel1");
  const double rear = r.Measured("sinkage, dry_sand, Wheel3");
  EXPECT_GT(rear, front);
  EXPECT_LT(rear - front, 0.1 * front);
  EXPECT_LT(r.Measured("speed on dry_sand"), r.Measured("speed on hard ground"));
  EXPECT_TRUE(r.Passed());
}

// soil_measured, quick: rolling and the slip K is fitted at. The sim meets
// Wong's integrals for the test bed's wheel and sand; against the
// measurement it sinks a quarter less rolling (14.4 mm measured, three
// trials within 0.8 mm), which the report states as a residual.
TEST(Validation, TestBedWheelMeetsWongsIntegralsAndItsResidualsAreReported) {
  const ExperimentResult r = RunNamed("soil_measured");
  EXPECT_EQ(r.error, "");
  EXPECT_NEAR(r.Measured("drawbar pull against Wong's, slip 0.23"), 0.70, 0.05);
  const double rolling = r.Measured("sinkage against Wong's, slip 0.00");
  EXPECT_GT(rolling, 9.0);
  EXPECT_LT(rolling, 12.0);
  EXPECT_NE(r.notes.find("| 0.23 (K's fit) |"), std::string::npos) << r.notes;
  EXPECT_TRUE(r.Passed());
}

// The sensor rig's closed forms on both engines (quick: 10 s
// turning, 1,000 IMU samples, the statistical tolerances widened to match).
TEST(Validation, SensorRigMeetsItsClosedFormsOnBothEngines) {
  for (const char* engine : {"ode", "mujoco"}) {
    Context context = Quick();
    context.params.engine = engine;
    const ExperimentResult r = RunExperiment(*FindExperiment("sensors"), context);
    EXPECT_EQ(r.error, "") << engine;
    EXPECT_NEAR(r.Measured("TableImu turning: acceleration toward the axis"), 2.0 * 2.0 * 0.8,
                0.001 * 3.2)
        << engine;
    EXPECT_EQ(r.Measured("SpindleEncoder readings off"), 0) << engine;
    EXPECT_TRUE(r.Passed()) << engine;
  }
}

// Soil runs on MuJoCo as on ODE (soil_contact.h): the multi-pass
// experiment meets its closed forms with the same tolerances.
TEST(Validation, SoilMultipassMeetsItsClosedFormsOnMujoco) {
  Context context = Quick();
  context.params.engine = "mujoco";
  const ExperimentResult r = RunExperiment(*FindExperiment("soil_multipass"), context);
  EXPECT_EQ(r.error, "");
  EXPECT_EQ(r.not_applicable, "");
  EXPECT_FALSE(r.checks.empty());
  EXPECT_TRUE(r.Passed());
}

}  // namespace
}  // namespace simpartner::validate
