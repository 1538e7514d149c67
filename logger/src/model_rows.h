// A model as rows: its Simulation row, then Robot, Material, Body, `Joint`,
// Sensor, Actuator and RobotComponent rows, each table one multi-row INSERT
// inside the caller's transaction.
#pragma once

#include <cstdint>
#include <vector>

#include "simpartner/logger/db.h"
#include "simpartner/logger/writer.h"
#include "simpartner/model_t.hpp"

namespace simpartner::logger {

// Database ids by bus index (-1 where a row is missing).
struct ModelIds {
  std::vector<int64_t> robot_ids, body_ids, joint_ids, sensor_ids;
};

// Inserts the Simulation row of `model` (received at received_us) and
// returns its simulationID.
uint32_t InsertSimulation(DbConnection* db, const model_t& model, const WriterOptions& options,
                          int64_t received_us);
// Inserts the rows of every part of the model under `simulation`.
ModelIds InsertModelRows(DbConnection* db, const model_t& model, uint32_t simulation);
// `table`'s id_column of each of the simulation's rows by busIndex, for
// `count` rows.
std::vector<int64_t> LoadIds(DbConnection* db, const char* table, const char* id_column,
                             uint32_t simulation, size_t count);

}  // namespace simpartner::logger
