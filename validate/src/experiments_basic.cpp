// The experiments on passive objects: free fall, a thrown body, the sliding
// cube, the two spheres, and ours: the rolling sphere and the pendulum.
#include <algorithm>
#include <cmath>
#include <string>

#include "simpartner/validate/experiment.h"
#include "simpartner/validate/sim_run.h"

namespace simpartner::validate {
namespace {

// Least-squares slope of y = k t through the origin.
double SlopeThroughOrigin(const std::vector<double>& t, const std::vector<double>& y) {
  double ty = 0.0, tt = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    ty += t[i] * y[i];
    tt += t[i] * t[i];
  }
  return tt > 0 ? ty / tt : 0.0;
}

}  // namespace

ExperimentResult FreeFall(const Context& context) {
  ExperimentResult result;
  constexpr double kDuration = 10.0;  // from 500 m: 9.5 m left at 10 s, no ground
  Plot plot;
  plot.file = "free_fall.png";
  plot.title = "Free fall from 500 m: height error (exact - simulated) vs time";
  plot.xlabel = "t [s]";
  plot.ylabel = "h_exact - h_sim [m]";
  struct Case {
    const char* world;
    double g;
    double dt;
  };
  const Case cases[] = {{"free_fall.xml", 9.81, 0.02},
                        {"free_fall.xml", 9.81, 0.01},
                        {"free_fall.xml", 9.81, 0.005},
                        {"free_fall.xml", 9.81, 0.001},
                        {"free_fall_g50.xml", 50.0, 0.001}};
  for (const Case& c : cases) {
    Parameters params = context.params;
    params.stepsize = c.dt;
    SimRun run(context, c.world, params);
    const int particle = run.Body("TestParticle");
    const double h0 = run.Position(particle).y();
    Series error;
    error.title = "g " + FormatNumber(c.g) + ", dt " + FormatNumber(c.dt) + " s";
    run.RunUntil(kDuration, [&] {
      const double t = run.time();
      error.x.push_back(t);
      error.y.push_back(h0 - 0.5 * c.g * t * t - run.Position(particle).y());
    });
    result.sim_seconds += run.time();
    const double slope = SlopeThroughOrigin(error.x, error.y);
    const double target = c.g * c.dt / 2.0;
    result.checks.push_back(Relative("error slope, g " + FormatNumber(c.g) + ", dt " + FormatNumber(c.dt) + " s",
                                     slope, target, 0.01, "m/s"));
    Series fitted;
    fitted.title = "fit " + FormatNumber(slope) + " t";
    fitted.style = "dashed";
    fitted.x = {0.0, kDuration};
    fitted.y = {0.0, slope * kDuration};
    if (c.g == 9.81) {  // g = 50 is off the scale of the others; its figure is in the table
      plot.series.push_back(error);
      plot.series.push_back(fitted);
    }
  }
  result.plots.push_back(plot);
  result.notes =
      "The original's 1 kg TestParticle (`free_fall.xml`, `free_fall_g50.xml`) falls from rest "
      "at 500 m for 10 s, once per step size. ODE integrates semi-implicitly (v += g dt, then "
      "x += v dt), so after n steps h = h0 - g dt^2 n (n+1) / 2: the error against "
      "h0 - g t^2 / 2 grows exactly linearly, with slope g dt / 2. The slope is a least-squares "
      "fit through the origin over every step.";
  return result;
}

ExperimentResult FreeFallThrown(const Context& context) {
  ExperimentResult result;
  constexpr double kDuration = 10.0;
  SimRun run(context, "free_fall_thrown.xml");
  const int particle = run.Body("TestParticle");
  const Eigen::Vector3d p0 = run.Position(particle);
  const Eigen::Vector3d v0 = run.Read(particle).linear_velocity;
  double worst = 0.0;
  Series x_error{"x - (x0 + vx t)", {}, {}, "lines"};
  Series z_error{"z - (z0 + vz t)", {}, {}, "dashed"};
  run.RunUntil(kDuration, [&] {
    const double t = run.time();
    const Eigen::Vector3d p = run.Position(particle);
    const double ex = p.x() - (p0.x() + v0.x() * t);
    const double ez = p.z() - (p0.z() + v0.z() * t);
    worst = std::max({worst, std::abs(ex), std::abs(ez)});
    x_error.x.push_back(t);
    x_error.y.push_back(ex);
    z_error.x.push_back(t);
    z_error.y.push_back(ez);
  });
  result.sim_seconds = run.time();
  result.checks.push_back(Absolute("largest horizontal error over 10 s", worst, 0.0, 1e-9, "m"));
  Plot plot;
  plot.file = "free_fall_thrown.png";
  plot.title = "Body thrown at (10, 10, 0) m/s: horizontal error vs time";
  plot.xlabel = "t [s]";
  plot.ylabel = "error [m]";
  plot.series = {x_error, z_error};
  result.plots.push_back(plot);
  result.notes =
      "The TestParticle starts at 500 m with velocity (10, 10, 0) m/s (`free_fall_thrown.xml`). "
      "Nothing acts horizontally, so x must be x0 + 10 t exactly; the tolerance 1e-9 m only "
      "admits the rounding of 10,000 additions of 0.01 m.";
  return result;
}

ExperimentResult SlidingCube(const Context& context) {
  ExperimentResult result;
  SimRun run(context, "sliding_cube.xml");
  const int cube = run.Body("Cube");
  const double mu = run.sim().world().FindMaterial("floor")->mu;
  const double g = -run.sim().world().gravity.y();
  const double v0 = run.Read(cube).linear_velocity.x();
  const double x0 = run.Position(cube).x();
  const double t_stop = v0 / (mu * g);
  const double dv_exact = mu * g * run.dt();
  Series measured{"simulated v_x", {}, {}, "lines"};
  Series exact{"v0 - mu g t", {}, {}, "dashed"};
  double worst_v = 0.0, worst_step = 0.0;
  double previous_v = v0;
  double stop_x = 0.0;
  bool stopped = false;
  run.RunUntil(t_stop + 0.5, [&] {
    const double t = run.time();
    const double v = run.Read(cube).linear_velocity.x();
    measured.x.push_back(t);
    measured.y.push_back(v);
    exact.x.push_back(t);
    exact.y.push_back(std::max(0.0, v0 - mu * g * t));
    // Over the slide: all but the last step, in which the cube stops.
    if (t <= t_stop - run.dt()) {
      worst_v = std::max(worst_v, std::abs(v - (v0 - mu * g * t)));
      worst_step = std::max(worst_step, std::abs((previous_v - v) - dv_exact));
    }
    if (!stopped && std::abs(v) < 1e-6) {
      stopped = true;
      stop_x = run.Position(cube).x() - x0;
    }
    previous_v = v;
  });
  result.sim_seconds = run.time();
  result.checks.push_back(Absolute("largest |v - (v0 - mu g t)| over the slide (1 % of v0)",
                                   worst_v, 0.0, 0.01 * v0, "m/s"));
  result.checks.push_back(Absolute("largest step-to-step deviation from mu g dt (1 %)",
                                   worst_step, 0.0, 0.01 * dv_exact, "m/s"));
  result.checks.push_back(Relative("sliding distance vs v0^2 / (2 mu g)", stop_x,
                                   v0 * v0 / (2 * mu * g), 0.01, "m"));
  Plot plot;
  plot.file = "sliding_cube.png";
  plot.title = "1 m, 1 kg cube sliding from 10 m/s on mu 0.5";
  plot.xlabel = "t [s]";
  plot.ylabel = "v_x [m/s]";
  plot.series = {measured, exact};
  Plot errors;
  errors.file = "sliding_cube_error.png";
  errors.title = "Sliding cube: simulated v_x - (v0 - mu g t) over the slide";
  errors.xlabel = "t [s]";
  errors.ylabel = "velocity error [mm/s]";
  errors.y_from_zero = true;
  Series error{"error", {}, {}, "lines"};
  for (size_t i = 0; i < measured.x.size(); ++i) {
    if (measured.x[i] > t_stop - run.dt()) break;
    error.x.push_back(measured.x[i]);
    error.y.push_back((measured.y[i] - exact.y[i]) * 1000.0);
  }
  errors.series = {error};
  result.plots = {plot, errors};
  result.notes =
      "The cube (`sliding_cube.xml`, mu 0.5 on cube and floor) starts at 10 m/s. Coulomb "
      "friction gives v = v0 - mu g t until it stops at t = " + FormatNumber(t_stop) +
      " s after v0^2 / (2 mu g) = " + FormatNumber(v0 * v0 / (2 * mu * g)) +
      " m. The first check is the largest velocity error over the slide against 1 % of v0; "
      "the second is the largest deviation of one step's velocity change from mu g dt "
      "against 1 % of mu g dt, where a stepwise error would show.";
  return result;
}

ExperimentResult TwoSpheres(const Context& context) {
  ExperimentResult result;
  constexpr double kDuration = 3.0;  // they touch at t = 1 s and part again
  SimRun run(context, "two_spheres.xml");
  const int left = run.Body("SphereLeft");
  const int right = run.Body("SphereRight");
  const double radius = run.sim().flat().bodies[left].source->geometry.size.x();
  const double approach = run.Read(right).linear_velocity.x() - run.Read(left).linear_velocity.x();
  double asymmetry = 0.0, closest = 1e9;
  Series xl{"left sphere x", {}, {}, "lines"};
  Series xr{"right sphere x", {}, {}, "lines"};
  Series mirror{"x_left + x_right (x 1e9)", {}, {}, "dashed"};
  run.RunUntil(kDuration, [&] {
    const Eigen::Vector3d a = run.Position(left), b = run.Position(right);
    asymmetry = std::max({asymmetry, std::abs(a.x() + b.x()), std::abs(a.y() - b.y()),
                          std::abs(a.z() - b.z())});
    closest = std::min(closest, (b - a).norm());
    xl.x.push_back(run.time());
    xl.y.push_back(a.x());
    xr.x.push_back(run.time());
    xr.y.push_back(b.x());
    mirror.x.push_back(run.time());
    mirror.y.push_back((a.x() + b.x()) * 1e9);
  });
  result.sim_seconds = run.time();
  const double v_left = run.Read(left).linear_velocity.x();
  const double v_right = run.Read(right).linear_velocity.x();
  result.checks.push_back(Absolute("largest mirror asymmetry of the positions", asymmetry, 0.0,
                                   1e-9, "m"));
  // Contacts are found at step boundaries: the spheres may overlap by what
  // they close in one step before the bounce turns them round.
  result.checks.push_back(Absolute("closest centre distance (within one step's closing)",
                                   closest, 2 * radius, std::abs(approach) * run.dt() + 1e-9,
                                   "m"));
  result.checks.push_back(Relative("relative speed after the bounce (elastic)",
                                   v_right - v_left, -approach, 0.01, "m/s"));
  Plot plot;
  plot.file = "two_spheres.png";
  plot.title = "Two spheres r 0.5 at -+1 m/s: positions and their mirror asymmetry";
  plot.xlabel = "t [s]";
  plot.ylabel = "x [m]";
  plot.series = {xl, xr, mirror};
  result.plots.push_back(plot);
  result.notes =
      "Two 1 kg spheres of radius 0.5 m (`two_spheres.xml`, zero gravity, frictionless, "
      "restitution 1, hard contact: softCFM 0) approach each other at 1 m/s. The right one's position must be the mirror "
      "image of the left one's at every step (tolerance 1e-9 m); the closest centre distance "
      "may fall short of 1.0 m by at most the 2 mm the two close in one 1 ms step, since "
      "contacts are detected once per step; the bounce must be elastic.";
  return result;
}

ExperimentResult RollingSphere(const Context& context) {
  ExperimentResult result;
  SimRun run(context, "rolling_sphere.xml");
  const int rolling = run.Body("RollingBall");
  const int smooth = run.Body("SmoothBall");
  const model::Body& ball = *run.sim().flat().bodies[static_cast<size_t>(rolling)].source;
  const double radius = ball.geometry.size.x();
  const double rho = run.sim().world().FindMaterial(ball.material)->rolling_friction;
  const double g = -run.sim().world().gravity.y();
  const double v0 = run.Read(rolling).linear_velocity.x();
  const double x0 = run.Position(rolling).x();
  // A solid sphere rolling without slip under a resisting torque rho N:
  // d/dt (7/10 m v^2) = -rho m g v / r, so it decelerates at 5/7 rho g / r.
  const double deceleration = 5.0 / 7.0 * rho * g / radius;
  const double t_stop = v0 / deceleration;
  const double distance = v0 * v0 / (2.0 * deceleration);
  Series v_rolling{"rolling friction 2 mm", {}, {}, "lines"};
  Series v_smooth{"no rolling friction (the original)", {}, {}, "lines"};
  Series v_exact{"v0 - 5/7 rho g t / r", {}, {}, "dashed"};
  double stopped_at = -1.0, stop_x = 0.0;
  run.RunUntil(1.5 * t_stop, [&] {
    const double t = run.time();
    const double v = run.Read(rolling).linear_velocity.norm();
    if (stopped_at < 0 && v < 1e-3) {
      stopped_at = t;
      stop_x = run.Position(rolling).x() - x0;
    }
    if (run.sim().step() % 10 != 0) return;
    v_rolling.x.push_back(t);
    v_rolling.y.push_back(v);
    v_smooth.x.push_back(t);
    v_smooth.y.push_back(run.Read(smooth).linear_velocity.norm());
    v_exact.x.push_back(t);
    v_exact.y.push_back(std::max(0.0, v0 - deceleration * t));
  });
  result.sim_seconds = run.time();
  const sim::BodyReadout end = run.Read(rolling);
  result.checks.push_back(AtMost("speed at 1.5 x the stopping time", end.linear_velocity.norm(),
                                 0.001, "m/s"));
  result.checks.push_back(AtMost("spin at 1.5 x the stopping time", end.angular_velocity.norm(),
                                 0.01, "rad/s"));
  result.checks.push_back(Relative("time to come to rest (below 1 mm/s)", stopped_at, t_stop, 0.05, "s"));
  result.checks.push_back(Relative("rolling distance", stop_x, distance, 0.05, "m"));
  result.checks.push_back(Relative("sphere without rolling friction keeps rolling",
                                   run.Read(smooth).linear_velocity.norm(), v0, 0.01, "m/s"));
  Plot plot;
  plot.file = "rolling_sphere.png";
  plot.title = "Sphere r 0.1 m rolling from 1 m/s on flat ground";
  plot.xlabel = "t [s]";
  plot.ylabel = "speed [m/s]";
  plot.series = {v_rolling, v_exact, v_smooth};
  result.plots.push_back(plot);
  result.notes =
      "Beyond the original, whose rolling sphere never stopped: two solid 1 kg spheres of "
      "radius 0.1 m roll at 1 m/s without slipping (`rolling_sphere.xml`). The ground and one "
      "sphere have a rolling resistance length rho = " + FormatNumber(rho) +
      " m (ODE's rolling friction, which bounds the rolling torque by rho N); a solid sphere "
      "then decelerates at 5/7 rho g / r = " + FormatNumber(deceleration) + " m/s^2 and comes to rest "
      "after " + FormatNumber(t_stop) + " s and " + FormatNumber(distance) + " m. The other sphere has none, as in "
      "the original, and rolls on. The 5 % tolerance on the time and distance is ours.";
  return result;
}

ExperimentResult PendulumEnergy(const Context& context) {
  ExperimentResult result;
  constexpr double kDuration = 60.0;
  SimRun run(context, "pendulum.xml");
  const int pivot = run.Joint("Pivot");
  const double e0 = run.KineticEnergy() + run.PotentialEnergy();
  // Scale: the energy the rod exchanges between potential and kinetic.
  const double swing = run.sim().flat().bodies[0].source->mass * 9.81 * 0.5;
  Series energy{"(E - E0) / (m g L/2), every step", {}, {}, "lines"};
  Series turns{"at the turning points", {}, {}, "points"};
  double highest_turn = -1e9, last_turn = 0.0;
  std::vector<double> bottoms;
  // The unwrapped angle: a swing that reaches the far horizontal (-pi) must
  // not wrap to +pi and count as a bottom.
  auto angle_of = [&] { return run.sim().engine().ReadJoint(pivot).continuous_position[0]; };
  double last_angle = angle_of(), last_rate = 0.0;
  run.RunUntil(kDuration, [&] {
    const double t = run.time();
    const double relative = (run.KineticEnergy() + run.PotentialEnergy() - e0) / swing;
    const double angle = angle_of();
    const double rate = run.sim().engine().JointRate(pivot, 0);
    // Turning points: the rod stops at the top of a swing, where all its
    // energy is potential (semi-implicit Euler's energy error, which
    // swings with the velocity, vanishes there).
    if (t > run.dt() && rate * last_rate < 0.0) {
      highest_turn = std::max(highest_turn, relative);
      last_turn = relative;
      turns.x.push_back(t);
      turns.y.push_back(relative);
    }
    // The bottom of the swing (-pi/2 from the horizontal start), one way.
    if ((last_angle + M_PI / 2) * (angle + M_PI / 2) < 0.0 && angle > last_angle)
      bottoms.push_back(t);
    last_angle = angle;
    last_rate = rate;
    if (run.sim().step() % 10 == 0) {
      energy.x.push_back(t);
      energy.y.push_back(relative);
    }
  });
  result.sim_seconds = run.time();
  const double period =
      bottoms.size() >= 2 ? (bottoms.back() - bottoms.front()) / (bottoms.size() - 1) : 0.0;
  // One step from the turn the rod still moves at most alpha dt: kinetic
  // energy below 1e-5 of m g L/2.
  result.checks.push_back(AtMost("highest turning-point energy over 60 s, of m g L/2",
                                 highest_turn, 1e-5, ""));
  result.checks.push_back(AtMost("energy at the last turning point, of m g L/2", last_turn, 0.0, ""));
  // A rod released from the horizontal: T = 2 pi sqrt(2L/3g) 2K(sin 45 deg)/pi.
  result.checks.push_back(Relative("period", period, 1.9335, 0.005, "s"));
  Plot plot;
  plot.file = "pendulum_energy.png";
  plot.title = "Passive pendulum: energy change over 60 s";
  plot.xlabel = "t [s]";
  plot.ylabel = "(E - E0) / (m g L/2)";
  plot.series = {energy, turns};
  result.plots.push_back(plot);
  result.notes =
      "Beyond the original: a passive 1 kg, 1 m rod hinged at one end (`pendulum.xml`, no "
      "motor, no damping) is released from the horizontal and swings for 60 s. Its energy "
      "E = kinetic + potential must never grow. Semi-implicit Euler makes the energy read "
      "at each step swing by about dt/2 times the power exchanged (here +-0.2 % of the swing "
      "energy m g L/2), in phase with the motion and without drift; at the turning points, "
      "where the rod stands still, that term vanishes, so the check is there: the rod must "
      "never swing higher than it started. It loses a little per swing to the joint's "
      "constraint softness (CFM), which is the safe direction. The period is the physical "
      "pendulum's for a 90 degree amplitude.";
  return result;
}

}  // namespace simpartner::validate
