#include "event_rows.h"

#include "decode_record.h"
#include "simpartner/command_reply_t.hpp"
#include "simpartner/command_shape.h"
#include "simpartner/command_t.hpp"
#include "simpartner/sensor_reading_t.hpp"
#include "writer_text.h"

namespace simpartner::logger {

EventRows::EventRows(DbConnection* db)
    : readings_(db, InsertMethod::kMultiRowInsert, "", "SensorReading",
                "simulationID,sensorID,step,simulationTime,receivedUtime,vals,text", "step = step"),
      commands_(db, InsertMethod::kMultiRowInsert, "", "Command",
                "simulationID,meantForBusSimulationID,receivedUtime,sentUtime,sender,requestID,"
                "robot,target,port,action,applyAtStep,vals,text",
                "requestID = requestID"),
      replies_(db, InsertMethod::kMultiRowInsert, "", "CommandReply",
               "simulationID,receivedUtime,sender,requestID,target,accepted,reason,"
               "appliedAtStep,previous,previousText",
               "requestID = requestID") {}

void EventRows::Add(const Record& record, uint32_t simulation,
                    const std::vector<int64_t>& sensor_ids, const DbWriter::Notice& notice) {
  if (record.kind == RecordKind::kSensor) AddReading(record, simulation, sensor_ids, notice);
  else if (record.kind == RecordKind::kCommand) AddCommand(record, simulation, notice);
  else if (record.kind == RecordKind::kCommandReply) AddReply(record, simulation, notice);
}

uint64_t EventRows::Finish() {
  readings_.Finish();
  commands_.Finish();
  replies_.Finish();
  return readings_.rows() + commands_.rows() + replies_.rows();
}

void EventRows::AddReading(const Record& record, uint32_t simulation,
                           const std::vector<int64_t>& sensor_ids, const DbWriter::Notice& notice) {
  sensor_reading_t reading;
  if (!DecodeRecord(record, &reading, notice)) return;
  if (reading.sensor < 0 || reading.sensor >= static_cast<int32_t>(sensor_ids.size()))
    return;  // the receiver checks this against the model
  readings_.BeginRow();
  readings_.Int(simulation);
  readings_.Int(sensor_ids[static_cast<size_t>(reading.sensor)]);
  readings_.Int(reading.step);
  readings_.Double(reading.sim_time);
  readings_.Int(record.received_us);
  readings_.Text(JoinValues(reading.values));
  readings_.Text(reading.text);
  readings_.EndRow();
}

void EventRows::AddCommand(const Record& record, uint32_t simulation, const DbWriter::Notice& notice) {
  command_t c;
  if (!DecodeRecord(record, &c, notice)) return;
  commands_.BeginRow();
  commands_.Int(simulation);
  commands_.Int(c.simulation_id);
  commands_.Int(record.received_us);
  commands_.Int(c.utime);
  commands_.Text(c.sender);
  commands_.Int(c.request_id);
  commands_.Text(c.robot);
  commands_.Text(c.target);
  commands_.Int(c.port);
  commands_.Text(SpellAction(c.action).database);
  commands_.Int(c.apply_at_step);
  commands_.Text(JoinValues(c.values));
  commands_.Text(c.text);
  commands_.EndRow();
}

void EventRows::AddReply(const Record& record, uint32_t simulation, const DbWriter::Notice& notice) {
  command_reply_t c;
  if (!DecodeRecord(record, &c, notice)) return;
  replies_.BeginRow();
  replies_.Int(simulation);
  replies_.Int(record.received_us);
  replies_.Text(c.sender);
  replies_.Int(c.request_id);
  replies_.Text(c.target);
  replies_.Int(c.accepted ? 1 : 0);
  replies_.Text(c.reason);
  replies_.Int(c.applied_at_step);
  replies_.Text(JoinValues(c.previous));
  replies_.Text(c.previous_text);
  replies_.EndRow();
}

}  // namespace simpartner::logger
