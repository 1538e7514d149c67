#include "simpartner/logger/export.h"

#include <cppconn/exception.h>

#include <cmath>
#include <deque>
#include <map>
#include <memory>

#include "joint_unwrap.h"
#include "simpartner/logger/simulations.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/text.h"

namespace simpartner::logger {
namespace {


void CheckRequest(const ExportRequest& request) {
  if (request.every < 1)
    throw Error("--every " + std::to_string(request.every) +
                ": must be 1 or more (every Nth step)");
  if (request.from > request.to)
    throw Error("--from " + ShortestNumber(request.from) + " is after --to " +
                ShortestNumber(request.to));
  if (request.velocities && request.kind != ExportKind::kPoses)
    throw Error("--velocities is for poses (joints carry their rates in rate, rate2, rate3)");
  if (request.unwrap && request.kind != ExportKind::kJoints)
    throw Error("--unwrap is for joints (their angle, angle2, angle3)");
}

// The statement of an export; `range` and `name_filter` are its extra
// conditions on r (SimulationRow) and the body or joint.
std::string ExportSql(ExportKind kind, const std::string& sim, const std::string& conditions,
                      bool stored_continuous) {
  switch (kind) {
    case ExportKind::kPoses:
      return "SELECT r.simulationTime, r.step, b.name, p.x, p.y, p.z, p.axisX, p.axisY, p.axisZ, "
             "p.angle FROM SimulationRow r JOIN Pose p ON p.simulationRowID = r.simulationRowID "
             "JOIN Body b ON b.bodyID = p.bodyID WHERE r.simulationID = " +
             sim + conditions + " ORDER BY r.step, b.busIndex";
    case ExportKind::kForces:
      return "SELECT r.simulationTime, r.step, b.name, f.F_x, f.F_y, f.F_z, f.T_x, f.T_y, f.T_z "
             "FROM SimulationRow r JOIN ForceAndTorque f ON f.simulationRowID = r.simulationRowID "
             "JOIN Body b ON b.bodyID = f.bodyID WHERE r.simulationID = " +
             sim + conditions + " ORDER BY r.step, b.busIndex";
    case ExportKind::kJoints:
      return "SELECT r.simulationTime, r.step, j.name, p.anchorx, p.anchory, p.anchorz, p.angle, "
             "p.angle2, p.angle3, p.rate, p.rate2, p.rate3, p.F_x, p.F_y, p.F_z, p.T_x, p.T_y, "
             "p.T_z" +
             std::string(stored_continuous
                             ? ", p.continuousAngle, p.continuousAngle2, p.continuousAngle3 "
                             : " ") +
             "FROM SimulationRow r JOIN JointPose p ON p.simulationRowID = r.simulationRowID "
             "JOIN `Joint` j ON j.jointID = p.jointID WHERE r.simulationID = " +
             sim + conditions + " ORDER BY r.step, j.busIndex";
  }
  return "";
}

// Velocity of `row` from the same body in `before` and `after` (x, y, z
// are values 0..2), appended to its values; NaN if it is missing in either.
void AppendVelocity(const ExportStep& before, const ExportStep& after, ExportRow* row) {
  const ExportRow* a = nullptr;
  const ExportRow* b = nullptr;
  for (const ExportRow& r : before.rows)
    if (r.name == row->name) a = &r;
  for (const ExportRow& r : after.rows)
    if (r.name == row->name) b = &r;
  const double dt = after.time - before.time;
  for (size_t k = 0; k < 3; ++k)
    row->values.push_back(a != nullptr && b != nullptr && dt > 0
                              ? (b->values[k] - a->values[k]) / dt
                              : std::numeric_limits<double>::quiet_NaN());
}

// The steps as read, in order, become the steps kept: joint angles made
// continuous, velocities from the steps before and after, then the time
// range and every Nth step.
class StepPipeline {
 public:
  StepPipeline(const ExportRequest& request, std::map<std::string, int> rotational_axes,
               const std::function<void(const ExportStep&)>& sink)
      : request_(request), rotational_axes_(std::move(rotational_axes)), sink_(sink) {}

  void Take(ExportStep step) {
    if (request_.unwrap)
      for (ExportRow& row : step.rows) Unwrap(&row);
    if (!request_.velocities) return Emit(step);
    window_.push_back(std::move(step));
    if (window_.size() == 2 && !first_emitted_) {
      EmitWithVelocity(window_[0], window_[0], window_[1]);
      first_emitted_ = true;
    } else if (window_.size() == 3) {
      EmitWithVelocity(window_[1], window_[0], window_[2]);
      window_.pop_front();
    }
  }

  // The last step (or the only one) gets its one-sided difference.
  void Finish() {
    if (!request_.velocities) return;
    if (window_.size() == 1 && !first_emitted_)
      EmitWithVelocity(window_[0], window_[0], window_[0]);
    else if (window_.size() == 2)
      EmitWithVelocity(window_[1], window_[0], window_[1]);
  }

 private:
  void Unwrap(ExportRow* row) {
    if (row->values.size() > kJointColumns) {
      // The stored continuous angle (NaN where a row has none).
      const bool stored = !std::isnan(row->values[kJointColumns]);
      if (stored)
        std::copy(row->values.begin() + kJointColumns, row->values.begin() + kJointColumns + 3,
                  row->values.begin() + kJointAngleColumn);
      row->values.resize(kJointColumns);
      if (stored) return;
    }
    unwrappers_[row->name].Unwrap(&row->values[kJointAngleColumn], rotational_axes_[row->name]);
  }
  void EmitWithVelocity(const ExportStep& step, const ExportStep& before, const ExportStep& after) {
    ExportStep out = step;
    for (ExportRow& row : out.rows) AppendVelocity(before, after, &row);
    Emit(out);
  }
  void Emit(const ExportStep& step) {
    if (step.time < request_.from || step.time > request_.to) return;
    if (in_range_++ % request_.every == 0) sink_(step);
  }

  const ExportRequest& request_;
  std::map<std::string, int> rotational_axes_;
  const std::function<void(const ExportStep&)>& sink_;
  std::map<std::string, AngleUnwrapper> unwrappers_;
  std::deque<ExportStep> window_;  // velocities: the steps before and after
  bool first_emitted_ = false;
  int64_t in_range_ = 0;  // steps of the range seen, for --every
};

// Reads the rows of `sql` (time, step, name, then `numbers` numbers) and
// hands each step, whole, to `take`.
void ReadSteps(DbConnection* db, const std::string& sql, size_t numbers, StepPipeline* take) {
  std::unique_ptr<sql::ResultSet> rows = db->QueryStreaming(sql, "export");
  ExportStep current;
  bool have_current = false;
  try {
    while (rows->next()) {
      const int64_t step = rows->getInt64(2);
      if (!have_current || step != current.step) {
        if (have_current) take->Take(std::move(current));
        current = ExportStep();
        current.time = static_cast<double>(rows->getDouble(1));
        current.step = step;
        have_current = true;
      }
      ExportRow row;
      row.name = rows->getString(3);
      row.values.reserve(numbers + 3);
      for (size_t k = 0; k < numbers; ++k) {
        const auto column = static_cast<uint32_t>(4 + k);
        row.values.push_back(rows->isNull(column) ? std::numeric_limits<double>::quiet_NaN()
                                                  : static_cast<double>(rows->getDouble(column)));
      }
      current.rows.push_back(std::move(row));
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read the export rows");
  }
  if (have_current) take->Take(std::move(current));
}

}  // namespace

std::vector<std::string> ExportColumns(const ExportRequest& request) {
  switch (request.kind) {
    case ExportKind::kPoses: {
      std::vector<std::string> c = {"x_m", "y_m", "z_m", "axis_x", "axis_y", "axis_z", "angle_rad"};
      if (request.velocities) c.insert(c.end(), {"vx_m_s", "vy_m_s", "vz_m_s"});
      return c;
    }
    case ExportKind::kForces:
      return {"Fx_N", "Fy_N", "Fz_N", "Tx_Nm", "Ty_Nm", "Tz_Nm"};
    case ExportKind::kJoints:
      return {"anchor_x_m", "anchor_y_m", "anchor_z_m", "angle",  "angle2",
              "angle3",     "rate",       "rate2",      "rate3",  "F1x_N",
              "F1y_N",      "F1z_N",      "T1x_Nm",     "T1y_Nm", "T1z_Nm"};
  }
  return {};
}

uint32_t ReadExport(DbConnection* db, const ExportRequest& request,
                    const std::function<void(const ExportStep&)>& sink) {
  CheckRequest(request);
  const uint32_t simulation = ResolveSimulation(db, request.simulation);
  const bool joints = request.kind == ExportKind::kJoints;
  if (!request.name.empty())
    RequirePartName(db, simulation, joints ? PartKind::kJoint : PartKind::kBody, request.name);
  // The time between logged steps, to read one more on each side of the
  // range for the central differences.
  const double logged_dt = LoggedStepTime(db, simulation);
  std::map<std::string, int> rotational_axes;
  if (request.unwrap) rotational_axes = JointRotationalAxes(db, simulation);
  // With the sim's continuous angle stored, --unwrap takes it as stored,
  // which is right however far an axis turned between logged steps and
  // needs no steps before --from.
  const bool stored_continuous = request.unwrap && HasStoredContinuousAngle(db, simulation);
  // Unwrapping here needs every angle from the start; velocities one step more.
  std::string conditions;
  const double margin = request.velocities ? 1.5 * logged_dt : 0;
  if (std::isfinite(request.from) && (!request.unwrap || stored_continuous))
    conditions += " AND r.simulationTime >= " + ShortestNumber(request.from - margin);
  if (std::isfinite(request.to))
    conditions += " AND r.simulationTime <= " + ShortestNumber(request.to + margin);
  if (!request.name.empty())
    conditions += std::string(joints ? " AND j.name = " : " AND b.name = ") + Quoted(request.name);
  const size_t numbers = request.kind == ExportKind::kPoses    ? 7
                         : request.kind == ExportKind::kForces ? 6
                         : stored_continuous                   ? kJointColumns + 3
                                                               : kJointColumns;
  StepPipeline pipeline(request, std::move(rotational_axes), sink);
  ReadSteps(db, ExportSql(request.kind, std::to_string(simulation), conditions, stored_continuous),
            numbers, &pipeline);
  pipeline.Finish();
  return simulation;
}

}  // namespace simpartner::logger
