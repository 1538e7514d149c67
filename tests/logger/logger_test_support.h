// What the logger tests share: a private MariaDB server per test (in a
// temporary directory of its own, socket only, removed afterwards), real
// model and state messages from the sim library, and queries.
#pragma once

#include <gtest/gtest.h>

#include <cppconn/resultset.h>
#include <cppconn/resultset_metadata.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "../sim_core/test_worlds.h"
#include "../support/encode.h"
#include "../support/mariadb_seed.h"
#include "../support/test_dir.h"
#include "simpartner/logger/db.h"
#include "simpartner/logger/private_server.h"
#include "simpartner/logger/record.h"
#include "simpartner/model/loader.h"

namespace simpartner::logger::testing {

template <class Message>
Record MakeRecord(RecordKind kind, int64_t simulation_id, const Message& message,
                  int64_t received_us = 1) {
  Record r;
  r.kind = kind;
  r.simulation_id = simulation_id;
  r.received_us = received_us;
  r.payload = test_support::Encode(message);
  return r;
}

// A run of a simulation: its model and every state, as the sim makes them.
struct SimRun {
  model_t model;
  std::vector<state_t> states;  // states[i] is step i + 1
  Record ModelRecord() const { return MakeRecord(RecordKind::kModel, model.simulation_id, model); }
  Record StateRecord(size_t i) const {
    return MakeRecord(RecordKind::kState, model.simulation_id, states[i]);
  }
  std::vector<Record> StateRecords(int64_t first_step, int64_t last_step) const {
    std::vector<Record> out;
    for (int64_t s = first_step; s <= last_step; ++s) out.push_back(StateRecord(static_cast<size_t>(s - 1)));
    return out;
  }
};

inline SimRun MakeRun(sim::Simulation* sim, int steps) {
  SimRun run;
  sim->FillModel(&run.model);
  run.model.host = "testhost";
  for (int i = 0; i < steps; ++i) {
    sim->Step();
    state_t s;
    sim->FillState(&s);
    s.utime = 1700000000000000 + i;
    run.states.push_back(s);
  }
  return run;
}

// The arm world (3 bodies, 2 joints, 3 sensors) with the arm swinging.
inline SimRun ArmRun(int steps, int64_t simulation_id) {
  auto sim = sim::testing::MakeArmSim();
  sim->Reset(simulation_id);
  // Swing the arm: its rotation sweeps through many angles.
  EXPECT_FALSE(sim->Submit(sim::testing::Command(
      "ArmMotor", command_t::ACTION_SET, {1000, 1000, 1000, 0, 0, 3.0, 20.0, 0.0, 0.0})));
  return MakeRun(sim.get(), steps);
}

// WorkPartner gen3 on flat ground (the shipped world: Turner, Wheel1..4...).
inline SimRun Gen3Run(int steps, int64_t simulation_id) {
  model::WorldLoadResult loaded =
      model::LoadWorldFile(std::string(SP_SOURCE_DIR) + "/models/worlds/flat_ground.xml");
  EXPECT_TRUE(loaded.world) << loaded.diagnostics.Format();
  sim::Simulation sim(*loaded.world, Parameters(), simulation_id);
  return MakeRun(&sim, steps);
}

// A private server for one test, stopped and removed at the end.
class ServerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    // Short: the server's socket lives under it (108 bytes at most).
    dir_ = test_support::FreshTestDir("sp_db_", 24);
    server_ = std::make_unique<PrivateServer>(std::string(SP_SOURCE_DIR) + "/scripts/mariadb",
                                              (dir_ / "db").string(), false, test_support::MariaDbSeed());
    server_->Start();
  }
  void TearDown() override {
    server_.reset();
    // SP_KEEP_TEST_DIRS=1 keeps the server's files, the spool and the
    // processes' logs of a failed test for a look afterwards.
    const char* keep = std::getenv("SP_KEEP_TEST_DIRS");
    if (keep != nullptr && std::string(keep) == "1" && HasFailure()) {
      std::cerr << "kept " << dir_ << "\n";
      return;
    }
    std::filesystem::remove_all(dir_);
  }
  // The administrator, in `database` (created if missing).
  std::unique_ptr<DbConnection> Admin(const std::string& database = "simpartner") {
    std::unique_ptr<DbConnection> db = DbConnection::Open(server_->AdminTarget(database), false);
    db->UseDatabase(true);
    return db;
  }
  int64_t QueryInt(const std::string& sql, const std::string& database = "simpartner") {
    return Admin(database)->QueryInt(sql, sql, -1);
  }
  // Every row of the result as tab-separated text.
  std::vector<std::string> QueryRows(DbConnection* db, const std::string& sql) {
    std::unique_ptr<sql::ResultSet> rows = db->Query(sql, sql);
    std::vector<std::string> out;
    const unsigned columns = rows->getMetaData()->getColumnCount();
    while (rows->next()) {
      std::string line;
      for (unsigned c = 1; c <= columns; ++c) {
        if (c > 1) line += "\t";
        line += rows->isNull(c) ? std::string("NULL") : std::string(rows->getString(c));
      }
      out.push_back(line);
    }
    return out;
  }

  std::filesystem::path dir_;
  std::unique_ptr<PrivateServer> server_;
};

}  // namespace simpartner::logger::testing
