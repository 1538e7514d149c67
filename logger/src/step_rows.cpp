#include "step_rows.h"

#include <cppconn/exception.h>

#include <algorithm>

#include "row_sink.h"
#include "simpartner/logger/axis_angle.h"
#include "writer_text.h"

namespace simpartner::logger {

StepSpan SpanOf(const std::vector<RunItem>& items) {
  StepSpan span;
  for (const RunItem& item : items) {
    if (item.is_gap) continue;
    const int64_t step = item.state.step;
    if (!span.any_state) {
      span.lo = span.hi = step;
      span.bodies = item.state.bodies.size();
      span.joints = item.state.joints.size();
    }
    span.any_state = true;
    span.lo = std::min(span.lo, step);
    span.hi = std::max(span.hi, step);
  }
  return span;
}

std::string StepRange(uint32_t simulation, const StepSpan& span) {
  return " WHERE simulationID = " + std::to_string(simulation) + " AND step BETWEEN " +
         std::to_string(span.lo) + " AND " + std::to_string(span.hi);
}

StepPresence ReadPresence(DbConnection* db, uint32_t simulation, const StepSpan& span) {
  StepPresence presence;
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT r.step, r.simulationRowID,"
      " (SELECT COUNT(*) FROM Pose p WHERE p.simulationRowID = r.simulationRowID),"
      " (SELECT COUNT(*) FROM ForceAndTorque f WHERE f.simulationRowID = r.simulationRowID),"
      " (SELECT COUNT(*) FROM JointPose j WHERE j.simulationRowID = r.simulationRowID)"
      " FROM SimulationRow r" + StepRange(simulation, span),
      "SELECT step FROM SimulationRow");
  try {
    while (rows->next()) {
      const int64_t step = rows->getInt64(1);
      if (rows->getUInt64(3) == span.bodies && rows->getUInt64(4) == span.bodies &&
          rows->getUInt64(5) == span.joints)
        presence.present.insert(step);
      else
        presence.incomplete[step] = static_cast<int64_t>(rows->getUInt64(2));
    }
  } catch (const sql::SQLException&) {
    db->Rethrow("read SimulationRow");
  }
  return presence;
}

StepPlan PlanSteps(const std::vector<RunItem>& items, int64_t last_step, int stride,
                   const StepPresence& presence) {
  StepPlan plan;
  std::set<int64_t> present = presence.present;
  plan.last_step = last_step;
  int64_t& last = plan.last_step;
  // Steps after `last` up to before `next` that never came.
  auto not_received = [&](int64_t next) {
    if (last >= 0 && next > last + stride)
      plan.gaps.push_back({last + stride, next - stride, (next - last) / stride - 1, kGapNotReceived});
  };
  for (const RunItem& item : items) {
    if (item.is_gap) {
      // Steps the receiver had but could not keep; any steps before them
      // that never came are a gap of their own.
      const GapPayload& g = item.gap;
      not_received(g.first_step);
      if (g.last_step > last) {
        plan.gaps.push_back({g.first_step, g.last_step, g.missing, g.reason});
        last = g.last_step;
      }
      continue;
    }
    const state_t& s = item.state;
    not_received(s.step);
    last = std::max(last, s.step);
    if (!present.insert(s.step).second) {
      ++plan.states_present;
      continue;
    }
    if (presence.incomplete.count(s.step) > 0) plan.repaired.push_back(&s);
    else plan.fresh.push_back(&s);
  }
  return plan;
}

uint64_t InsertGaps(DbConnection* db, uint32_t simulation, const std::vector<GapRow>& gaps) {
  RowSink sink(db, InsertMethod::kMultiRowInsert, "", "LogGap",
               "simulationID,firstStep,lastStep,missing,detectedAt,reason",
               "lastStep = VALUES(lastStep), missing = VALUES(missing), reason = VALUES(reason)");
  for (const GapRow& gap : gaps) {
    sink.BeginRow();
    sink.Int(simulation);
    sink.Int(gap.first_step);
    sink.Int(gap.last_step);
    sink.Int(gap.missing);
    sink.Expression("UTC_TIMESTAMP(6)");
    sink.Text(ColumnText(gap.reason, 255));
    sink.EndRow();
  }
  sink.Finish();
  return sink.rows();
}

uint64_t InsertSimulationRows(DbConnection* db, uint32_t simulation, const StepSpan& span,
                              const std::vector<const state_t*>& states,
                              std::unordered_map<int64_t, int64_t>* row_ids) {
  RowSink steps(db, InsertMethod::kMultiRowInsert, "", "SimulationRow",
                "simulationID,step,simulationTime,publishedUtime");
  for (const state_t* s : states) {
    steps.BeginRow();
    steps.Int(simulation);
    steps.Int(s->step);
    steps.Double(s->sim_time);
    steps.Int(s->utime);
    steps.EndRow();
  }
  steps.Finish();
  std::unique_ptr<sql::ResultSet> rows = db->Query(
      "SELECT step, simulationRowID FROM SimulationRow" + StepRange(simulation, span),
      "SELECT FROM SimulationRow");
  try {
    while (rows->next()) (*row_ids)[rows->getInt64(1)] = static_cast<int64_t>(rows->getUInt64(2));
  } catch (const sql::SQLException&) {
    db->Rethrow("read SimulationRow");
  }
  return steps.rows();
}

namespace {

void AppendPose(RowSink* poses, int64_t row, int64_t body_id, const body_state_t& body) {
  const AxisAngle aa = AxisAngleFromQuaternion(body.orientation);
  poses->BeginRow();
  poses->Int(row);
  poses->Int(body_id);
  for (double p : body.position) poses->Double(p);
  for (double a : aa.axis) poses->Double(a);
  poses->Double(aa.angle);
  poses->EndRow();
}

void AppendForce(RowSink* forces, int64_t row, int64_t body_id, const body_state_t& body) {
  forces->BeginRow();
  forces->Int(row);
  forces->Int(body_id);
  for (double f : body.contact_force) forces->Double(f);
  for (double t : body.contact_torque) forces->Double(t);
  forces->EndRow();
}

void AppendJoint(RowSink* joints, int64_t row, int64_t joint_id, const joint_state_t& joint) {
  joints->BeginRow();
  joints->Int(row);
  joints->Int(joint_id);
  for (double a : joint.anchor) joints->Double(a);
  for (double p : joint.position) joints->Double(p);
  for (double r : joint.rate) joints->Double(r);
  for (double f : joint.force1) joints->Double(f);
  for (double t : joint.torque1) joints->Double(t);
  for (double p : joint.continuous_position) joints->Double(p);
  joints->EndRow();
}

void AppendWheelSoil(RowSink* wheels, int64_t row, int64_t body_id, const wheel_soil_t& wheel) {
  wheels->BeginRow();
  wheels->Int(row);
  wheels->Int(body_id);
  for (double v : {wheel.sinkage, wheel.slip, wheel.thrust, wheel.drawbar_pull, wheel.load,
                   wheel.axle_torque})
    wheels->Double(v);
  for (double f : wheel.normal_force) wheels->Double(f);
  for (double f : wheel.shear_force) wheels->Double(f);
  wheels->Int(wheel.stuck ? 1 : 0);
  wheels->EndRow();
}

}  // namespace

uint64_t InsertStateRows(DbConnection* db, const std::vector<const state_t*>& states,
                         const StateRowsTarget& target) {
  const bool keep = target.keep_existing;
  RowSink poses(db, target.method, target.scratch_dir, "Pose",
                "simulationRowID,bodyID,x,y,z,axisX,axisY,axisZ,angle", keep ? "x = x" : "");
  RowSink forces(db, target.method, target.scratch_dir, "ForceAndTorque",
                 "simulationRowID,bodyID,F_x,F_y,F_z,T_x,T_y,T_z", keep ? "F_x = F_x" : "");
  RowSink joints(db, target.method, target.scratch_dir, "JointPose",
                 "simulationRowID,jointID,anchorx,anchory,anchorz,angle,angle2,angle3,rate,"
                 "rate2,rate3,F_x,F_y,F_z,T_x,T_y,T_z,continuousAngle,continuousAngle2,"
                 "continuousAngle3",
                 keep ? "angle = angle" : "");
  RowSink wheels(db, target.method, target.scratch_dir, "WheelSoil",
                 "simulationRowID,bodyID,sinkage,slip,thrust,drawbarPull,wheelLoad,axleTorque,"
                 "Fn_x,Fn_y,Fn_z,Fs_x,Fs_y,Fs_z,stuck",
                 keep ? "slip = slip" : "");
  for (const state_t* s : states) {
    const int64_t row = target.row_ids.at(s->step);
    for (size_t b = 0; b < s->bodies.size(); ++b) {
      AppendPose(&poses, row, target.body_ids[b], s->bodies[b]);
      AppendForce(&forces, row, target.body_ids[b], s->bodies[b]);
    }
    for (size_t j = 0; j < s->joints.size(); ++j)
      AppendJoint(&joints, row, target.joint_ids[j], s->joints[j]);
    for (const wheel_soil_t& wheel : s->wheel_soil)
      AppendWheelSoil(&wheels, row, target.body_ids[static_cast<size_t>(wheel.body)], wheel);
  }
  poses.Finish();
  forces.Finish();
  joints.Finish();
  wheels.Finish();
  return poses.rows() + forces.rows() + joints.rows() + wheels.rows();
}

}  // namespace simpartner::logger
