#include "simpartner/logger/plot_query.h"

#include <cppconn/exception.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "simpartner/edit_distance.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/logged_run.h"
#include "simpartner/logger/simulations.h"
#include "simpartner/text.h"

namespace simpartner::logger {
namespace {


// Wheel1, wheel_left ...: what wheel-forces draws by default.
bool IsWheelName(const std::string& name) {
  return name.size() >= 5 && EditDistance(name.substr(0, 5), "wheel") == 0;
}

bool NeedsJoint(PlotKind kind) {
  return kind == PlotKind::kAngle || kind == PlotKind::kRate || kind == PlotKind::kForce;
}

struct World {
  std::string name;
  double gravity[3] = {0, 0, 0};
  double Gravity() const { return std::hypot(gravity[0], gravity[1], gravity[2]); }
};

World ReadWorld(DbConnection* db, uint32_t simulation) {
  World world;
  std::unique_ptr<sql::ResultSet> r = db->Query(
      "SELECT worldName, gravityX, gravityY, gravityZ FROM Simulation WHERE simulationID = " +
          std::to_string(simulation),
      "SELECT worldName FROM Simulation");
  try {
    if (r->next()) {
      world.name = r->getString(1);
      for (uint32_t k = 0; k < 3; ++k) world.gravity[k] = static_cast<double>(r->getDouble(2 + k));
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the simulation");
  }
  return world;
}

// The track of the first robot's first body (its chassis) by default.
std::string FirstBody(DbConnection* db, uint32_t simulation) {
  std::unique_ptr<sql::ResultSet> r =
      db->Query("SELECT name FROM Body WHERE simulationID = " + std::to_string(simulation) +
                    " ORDER BY robotID IS NULL, busIndex LIMIT 1",
                "SELECT name FROM Body");
  try {
    if (r->next()) return r->getString(1);
  } catch (const sql::SQLException&) {
    db->Rethrow("read the first body");
  }
  throw Error("simulation " + std::to_string(simulation) + " has no bodies to draw a track of");
}

// The two axes of the ground, those across gravity: x and z in the y-up
// worlds, x and y with gravity along z.
struct GroundAxes {
  size_t first = 0, second = 2;
};
GroundAxes GroundPlane(const World& world) {
  size_t up = 1;
  for (size_t k = 0; k < 3; ++k)
    if (std::fabs(world.gravity[k]) > std::fabs(world.gravity[up])) up = k;
  GroundAxes axes;
  axes.first = up == 0 ? 1 : 0;
  axes.second = up == 2 ? 1 : 2;
  return axes;
}

LoggedRunRequest RunRequest(const PlotRequest& request, uint32_t simulation,
                            const std::string& name, const std::vector<std::string>& wheels) {
  LoggedRunRequest r;
  r.simulation = std::to_string(simulation);
  r.from = request.from;
  r.to = request.to;
  const bool joint = NeedsJoint(request.kind);
  r.poses = !joint && request.kind != PlotKind::kWheelForces;
  r.velocities = request.kind == PlotKind::kVelocity;
  r.forces = request.kind == PlotKind::kWheelForces;
  r.joint_states = joint;
  r.bodies = {false, name.empty() ? wheels : std::vector<std::string>{name}};
  r.joints = {false, joint ? std::vector<std::string>{name} : std::vector<std::string>{}};
  return r;
}

std::vector<double> Column(const PartArray& part, size_t columns, size_t column) {
  const size_t steps = columns ? part.values.size() / columns : 0;
  std::vector<double> out(steps);
  for (size_t i = 0; i < steps; ++i) out[i] = part.values[i * columns + column];
  return out;
}

// |(a, b, c)| of three columns.
std::vector<double> Magnitude(const PartArray& part, size_t columns, size_t first) {
  std::vector<double> out = Column(part, columns, first);
  for (size_t i = 0; i < out.size(); ++i) {
    const double* v = &part.values[i * columns + first];
    out[i] = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  }
  return out;
}

// The load on a wheel: its contact force against gravity (|F| without gravity).
std::vector<double> Load(const PartArray& part, const World& world) {
  const double g = world.Gravity();
  if (g <= 0) return Magnitude(part, kForceColumns, 0);
  std::vector<double> out = Column(part, kForceColumns, 0);
  for (size_t i = 0; i < out.size(); ++i) {
    const double* f = &part.values[i * kForceColumns];
    out[i] = -(f[0] * world.gravity[0] + f[1] * world.gravity[1] + f[2] * world.gravity[2]) / g;
  }
  return out;
}

void Add(Plot* plot, const std::string& title, std::vector<double> x, std::vector<double> y) {
  plot->series.push_back(Series{title, std::move(x), std::move(y), "lines"});
}

// The track, and its first and last points as marks (a body that stood
// still is a dot, not an empty plot).
void AddTrack(const PartArray& body, const GroundAxes& axes, Plot* plot) {
  Series track{body.name, Column(body, kPoseColumns, axes.first),
               Column(body, kPoseColumns, axes.second), "lines"};
  std::vector<size_t> finite;
  for (size_t i = 0; i < track.x.size(); ++i)
    if (std::isfinite(track.x[i]) && std::isfinite(track.y[i])) finite.push_back(i);
  std::vector<Series> marks;
  if (!finite.empty())
    for (const auto& [title, i] :
         {std::pair{"start", finite.front()}, std::pair{"end", finite.back()}})
      marks.push_back(Series{title, {track.x[i]}, {track.y[i]}, "mark"});
  plot->series.push_back(std::move(track));
  plot->series.insert(plot->series.end(), marks.begin(), marks.end());
}

void AddSeries(PlotKind kind, const LoggedRun& run, const World& world, Plot* plot) {
  const std::vector<double>& t = run.time;
  switch (kind) {
    case PlotKind::kPosition:
      for (size_t k = 0; k < 3; ++k)
        Add(plot, std::string(1, "xyz"[k]), t, Column(run.poses[0], kPoseColumns, k));
      break;
    case PlotKind::kVelocity:
      for (size_t k = 0; k < 3; ++k)
        Add(plot, "v" + std::string(1, "xyz"[k]), t,
            Column(run.poses[0], kPoseColumns + 3, kPoseColumns + k));
      Add(plot, "speed", t, Magnitude(run.poses[0], kPoseColumns + 3, kPoseColumns));
      break;
    case PlotKind::kAngle:
      Add(plot, "angle (continuous)", t, Column(run.joints[0], kJointColumns, 3));
      break;
    case PlotKind::kRate:
      Add(plot, "rate", t, Column(run.joints[0], kJointColumns, 6));
      break;
    case PlotKind::kForce:
      for (size_t k = 0; k < 3; ++k)
        Add(plot, "F1" + std::string(1, "xyz"[k]), t, Column(run.joints[0], kJointColumns, 9 + k));
      Add(plot, "|F1|", t, Magnitude(run.joints[0], kJointColumns, 9));
      break;
    case PlotKind::kWheelForces:
      for (const PartArray& wheel : run.forces) Add(plot, wheel.name, t, Load(wheel, world));
      break;
    case PlotKind::kTrack:
      AddTrack(run.poses[0], GroundPlane(world), plot);
      break;
  }
}

void Label(const PlotRequest& request, const std::string& where, const std::string& name,
           const World& world, Plot* plot) {
  plot->xlabel = "simulation time [s]";
  switch (request.kind) {
    case PlotKind::kPosition:
      plot->title = where + ": position of " + name;
      plot->ylabel = "position [m]";
      break;
    case PlotKind::kVelocity:
      plot->title =
          where + ": velocity of " + name + " (central differences of the logged positions)";
      plot->ylabel = "velocity [m/s]";
      break;
    case PlotKind::kAngle:
      plot->title = where + ": angle of joint " + name;
      plot->ylabel = "angle [rad] (slider: [m])";
      break;
    case PlotKind::kRate:
      plot->title = where + ": rate of joint " + name;
      plot->ylabel = "rate [rad/s] (slider: [m/s])";
      break;
    case PlotKind::kForce:
      plot->title = where + ": constraint force of joint " + name + " on its body1";
      plot->ylabel = "force [N]";
      break;
    case PlotKind::kWheelForces:
      plot->title = where + ": wheel contact forces against gravity" +
                    (request.name.empty() ? "" : " (" + request.name + ")");
      plot->ylabel = world.Gravity() > 0 ? "contact force along up [N]" : "|contact force| [N]";
      plot->panels = true;
      break;
    case PlotKind::kTrack: {
      const GroundAxes axes = GroundPlane(world);
      plot->title = where + ": track of " + name + " seen from above";
      plot->xlabel = std::string(1, "xyz"[axes.first]) + " [m]";
      plot->ylabel = std::string(1, "xyz"[axes.second]) + " [m]";
      plot->equal_axes = true;
      plot->min_extent = kTrackMinExtent;
      break;
    }
  }
}

// The bodies wheel-forces draws when none is named; Error when there are none.
std::vector<std::string> Wheels(DbConnection* db, uint32_t simulation, const std::string& where) {
  std::vector<std::string> wheels = PartNames(db, simulation, PartKind::kBody);
  wheels.erase(std::remove_if(wheels.begin(), wheels.end(),
                              [](const std::string& n) { return !IsWheelName(n); }),
               wheels.end());
  if (wheels.empty()) throw Error(where + " has no body named Wheel*; name one with --body");
  return wheels;
}

}  // namespace

PlotKind ParsePlotKind(const std::string& word) {
  static const std::vector<std::pair<std::string, PlotKind>> kKinds = {
      {"position", PlotKind::kPosition}, {"velocity", PlotKind::kVelocity},
      {"angle", PlotKind::kAngle},       {"rate", PlotKind::kRate},
      {"force", PlotKind::kForce},       {"wheel-forces", PlotKind::kWheelForces},
      {"track", PlotKind::kTrack}};
  std::string list, nearest;
  size_t best = std::string::npos;
  for (const auto& [name, kind] : kKinds) {
    if (name == word) return kind;
    list += (list.empty() ? "" : ", ") + name;
    const size_t d = EditDistance(name, word);
    if (d < best) {
      best = d;
      nearest = name;
    }
  }
  throw Error("plot: unknown quantity '" + word + "'" +
              (best <= 3 ? " (did you mean '" + nearest + "'?)" : "") + "; one of " + list);
}

Plot MakePlot(DbConnection* db, const PlotRequest& request) {
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  std::string name = request.name;
  if (name.empty() && request.kind == PlotKind::kTrack) name = FirstBody(db, simulation);
  if (name.empty() && request.kind != PlotKind::kWheelForces)
    throw Error(std::string("plot needs ") +
                (NeedsJoint(request.kind) ? "--joint NAME" : "--body NAME") +
                " (simpartner-query names SIM lists them)");
  const World world = ReadWorld(db, simulation);
  const std::string where = "simulation " + std::to_string(simulation) + " (" + world.name + ")";
  const std::vector<std::string> wheels = request.kind == PlotKind::kWheelForces && name.empty()
                                              ? Wheels(db, simulation, where)
                                              : std::vector<std::string>{};
  if (request.from > request.to)
    throw Error("--from " + ShortestNumber(request.from) + " is after --to " +
                ShortestNumber(request.to));
  const LoggedRun run = ReadLoggedRun(db, RunRequest(request, simulation, name, wheels));
  if (run.time.empty())
    throw Error(
        where + " has no logged steps" +
        (std::isfinite(request.from) || std::isfinite(request.to) ? " in the time range" : "") +
        " to plot");
  Plot plot;
  AddSeries(request.kind, run, world, &plot);
  Label(request, where, name, world, &plot);
  return plot;
}

}  // namespace simpartner::logger
