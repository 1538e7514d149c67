#include "simpartner/logger/logged_run.h"

#include <cppconn/exception.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "joint_unwrap.h"
#include "simpartner/logger/export.h"
#include "simpartner/logger/simulations.h"
#include "simpartner/text.h"
#include "step_table_fetch.h"

namespace simpartner::logger {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A body or joint of the simulation.
struct Part {
  int64_t id = 0;
  std::string name;
  int rotational_axes = 0;  // joints
};

std::vector<Part> ReadParts(DbConnection* db, uint32_t simulation, PartKind kind) {
  const bool joints = kind == PartKind::kJoint;
  const std::string sql =
      joints ? "SELECT jointID, name, type FROM `Joint`" : "SELECT bodyID, name FROM Body";
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      sql + " WHERE simulationID = " + std::to_string(simulation) + " ORDER BY busIndex", sql);
  std::vector<Part> parts;
  try {
    while (rows->next())
      parts.push_back(
          {rows->getInt64(1), rows->getString(2), joints ? RotationalAxes(rows->getString(3)) : 0});
  } catch (const sql::SQLException&) {
    db->Rethrow(sql);
  }
  return parts;
}

// The parts selected, in bus order.
std::vector<Part> SelectParts(DbConnection* db, uint32_t simulation, PartKind kind,
                              const PartSelection& selection) {
  std::vector<Part> parts = ReadParts(db, simulation, kind);
  if (selection.all) return parts;
  std::vector<std::string> names;
  for (const Part& p : parts) names.push_back(p.name);
  for (const std::string& wanted : selection.names)
    RequirePartName(names, simulation, kind, wanted);
  parts.erase(std::remove_if(parts.begin(), parts.end(),
                             [&](const Part& p) {
                               return std::find(selection.names.begin(), selection.names.end(),
                                                p.name) == selection.names.end();
                             }),
              parts.end());
  return parts;
}

StepTableFetch Fetch(const std::string& table, const std::string& id_column,
                     std::vector<std::string> columns, const std::vector<Part>& parts, bool all) {
  StepTableFetch fetch;
  fetch.table = table;
  fetch.id_column = id_column;
  fetch.columns = std::move(columns);
  for (const Part& p : parts) fetch.ids.push_back(p.id);
  fetch.every_part = all;
  return fetch;
}

// Joint rows of 15 numbers, or 18 with the stored continuous angles last:
// 15 numbers with the angles continuous (the stored ones where a row has
// them, else the logged angles unwrapped from the first step read).
std::vector<double> ContinuousAngles(std::vector<double> values, size_t steps, size_t read_columns,
                                     int rotational_axes) {
  AngleUnwrapper unwrapper;
  if (read_columns == kJointColumns) {
    for (size_t i = 0; i < steps; ++i)
      unwrapper.Unwrap(&values[i * kJointColumns + kJointAngleColumn], rotational_axes);
    return values;
  }
  std::vector<double> out(steps * kJointColumns);
  for (size_t i = 0; i < steps; ++i) {
    double* row = &values[i * read_columns];
    const bool stored = read_columns > kJointColumns && !std::isnan(row[kJointColumns]);
    if (stored)
      std::copy(row + kJointColumns, row + kJointColumns + 3, row + kJointAngleColumn);
    else
      unwrapper.Unwrap(row + kJointAngleColumn, rotational_axes);
    std::copy(row, row + kJointColumns, &out[i * kJointColumns]);
  }
  return out;
}

// Pose rows of 7 numbers -> 10, with vx, vy, vz: central differences of x,
// y, z, one-sided at the first and last step (NaN for a single step).
std::vector<double> WithVelocities(const std::vector<double>& poses,
                                   const std::vector<double>& time) {
  const size_t steps = time.size();
  std::vector<double> out(steps * (kPoseColumns + 3));
  for (size_t i = 0; i < steps; ++i) {
    const size_t before = i > 0 ? i - 1 : 0, after = i + 1 < steps ? i + 1 : i;
    const double dt = time[after] - time[before];
    double* row = &out[i * (kPoseColumns + 3)];
    std::copy(&poses[i * kPoseColumns], &poses[i * kPoseColumns] + kPoseColumns, row);
    for (size_t k = 0; k < 3; ++k)
      row[kPoseColumns + k] =
          dt > 0 ? (poses[after * kPoseColumns + k] - poses[before * kPoseColumns + k]) / dt : kNaN;
  }
  return out;
}

// Keeps the steps with from <= time <= to (the read had steps around them
// for the differences, or every step from the first for the unwrapping).
void KeepTimeRange(double from, double to, LoggedRun* run) {
  const auto first = std::lower_bound(run->time.begin(), run->time.end(), from) - run->time.begin();
  const auto end = std::upper_bound(run->time.begin(), run->time.end(), to) - run->time.begin();
  const size_t steps = run->time.size();
  if (first == 0 && static_cast<size_t>(end) == steps) return;
  const auto slice = [&](auto* values, size_t columns) {
    values->erase(values->begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(end) * columns),
                  values->end());
    values->erase(values->begin(), values->begin() + static_cast<std::ptrdiff_t>(
                                                         static_cast<size_t>(first) * columns));
  };
  for (auto* parts : {&run->poses, &run->forces, &run->joints})
    for (PartArray& p : *parts) slice(&p.values, steps ? p.values.size() / steps : 0);
  slice(&run->time, 1);
  slice(&run->step, 1);
}

void CheckRange(const LoggedRunRequest& request) {
  if (request.from > request.to)
    throw Error("time range: from " + ShortestNumber(request.from) + " s is after to " +
                ShortestNumber(request.to) + " s");
}

const std::vector<std::string> kJointStateColumns = {
    "anchorx", "anchory", "anchorz", "angle", "angle2", "angle3", "rate", "rate2",
    "rate3",   "F_x",     "F_y",     "F_z",   "T_x",    "T_y",    "T_z"};

// What to read: the parts, and whether the sim stored continuous angles.
struct ReadPlan {
  std::vector<Part> bodies, joints;
  bool stored_continuous = false;
};

ReadPlan PlanRead(DbConnection* db, uint32_t simulation, const LoggedRunRequest& request) {
  ReadPlan plan;
  if (request.poses || request.forces)
    plan.bodies = SelectParts(db, simulation, PartKind::kBody, request.bodies);
  if (request.joint_states)
    plan.joints = SelectParts(db, simulation, PartKind::kJoint, request.joints);
  plan.stored_continuous = !plan.joints.empty() && HasStoredContinuousAngle(db, simulation);
  return plan;
}

// The steps to read: velocities need one logged step more on each side;
// unwrapping angles that were not stored continuous needs every step from
// the first.
StepIndex ReadSteps(DbConnection* db, uint32_t simulation, const LoggedRunRequest& request,
                    const ReadPlan& plan) {
  const double margin = request.velocities ? 1.5 * LoggedStepTime(db, simulation) : 0;
  const double from = !plan.joints.empty() && !plan.stored_continuous
                          ? -std::numeric_limits<double>::infinity()
                          : request.from - margin;
  return StepIndex::Read(db, simulation, from, request.to + margin);
}

// One fetch per table asked for, in the order poses, forces, joints.
std::vector<StepTableFetch> Fetches(const LoggedRunRequest& request, const ReadPlan& plan) {
  std::vector<StepTableFetch> fetches;
  if (request.poses)
    fetches.push_back(Fetch("Pose", "bodyID", {"x", "y", "z", "axisX", "axisY", "axisZ", "angle"},
                            plan.bodies, request.bodies.all));
  if (request.forces)
    fetches.push_back(Fetch("ForceAndTorque", "bodyID", {"F_x", "F_y", "F_z", "T_x", "T_y", "T_z"},
                            plan.bodies, request.bodies.all));
  std::vector<std::string> joint_columns = kJointStateColumns;
  if (plan.stored_continuous)
    joint_columns.insert(joint_columns.end(),
                         {"continuousAngle", "continuousAngle2", "continuousAngle3"});
  if (request.joint_states)
    fetches.push_back(
        Fetch("JointPose", "jointID", joint_columns, plan.joints, request.joints.all));
  return fetches;
}

// The arrays of the fetches, with velocities and continuous angles, into *run.
void Assemble(const LoggedRunRequest& request, const ReadPlan& plan,
              std::vector<StepTableFetch>* fetches, LoggedRun* run) {
  auto fetch = fetches->begin();
  if (request.poses) {
    for (size_t i = 0; i < plan.bodies.size(); ++i)
      run->poses.push_back({plan.bodies[i].name, request.velocities
                                                     ? WithVelocities(fetch->arrays[i], run->time)
                                                     : std::move(fetch->arrays[i])});
    ++fetch;
  }
  if (request.forces) {
    for (size_t i = 0; i < plan.bodies.size(); ++i)
      run->forces.push_back({plan.bodies[i].name, std::move(fetch->arrays[i])});
    ++fetch;
  }
  if (request.joint_states)
    for (size_t i = 0; i < plan.joints.size(); ++i)
      run->joints.push_back(
          {plan.joints[i].name,
           ContinuousAngles(std::move(fetch->arrays[i]), run->time.size(), fetch->columns.size(),
                            plan.joints[i].rotational_axes)});
}

}  // namespace

LoggedRun ReadLoggedRun(DbConnection* db, const LoggedRunRequest& request) {
  CheckRange(request);
  LoggedRun run;
  run.simulation = ResolveSimulation(db, request.simulation);
  run.engine = SimulationEngine(db, run.simulation);
  const ReadPlan plan = PlanRead(db, run.simulation, request);
  const StepIndex steps = ReadSteps(db, run.simulation, request, plan);
  std::vector<StepTableFetch> fetches = Fetches(request, plan);
  FetchStepTables(db, run.simulation, steps, &fetches);
  run.time = steps.time();
  run.step = steps.step();
  Assemble(request, plan, &fetches, &run);
  KeepTimeRange(request.from, request.to, &run);
  return run;
}

}  // namespace simpartner::logger
