// Which simulations a database holds and what they are made of: the list
// for people, a simulation named by id, "last" or "running", the names of
// its bodies and joints (with a did-you-mean for a wrong one), and the
// facts the readers need (engine, time between logged steps, stored
// continuous angles).
#pragma once

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

#include "simpartner/logger/db.h"

namespace simpartner::logger {

// A table of the simulations, newest last.
void ListSimulations(DbConnection* db, std::ostream& out);

// Simulation.simulationID of `which`: a simulationID, "last" (the newest)
// or "running" (the newest still open, i.e. without endTime). Throws Error
// saying which is missing.
uint32_t ResolveSimulation(DbConnection* db, const std::string& which);

enum class PartKind { kBody, kJoint, kSensor };

// The names of a simulation's bodies, joints or sensors, in bus order.
std::vector<std::string> PartNames(DbConnection* db, uint32_t simulation, PartKind kind);
// Throws Error when `name` is not one of `names` (the simulation's bodies,
// joints or sensors), with the nearest name or the list.
void RequirePartName(const std::vector<std::string>& names, uint32_t simulation, PartKind kind,
                     const std::string& name);
void RequirePartName(DbConnection* db, uint32_t simulation, PartKind kind, const std::string& name);

// The physics engine the simulation ran on (Simulation.engine): "ode" or
// "mujoco"; "ode" in a database from before schema 8, when only ODE ran.
std::string SimulationEngine(DbConnection* db, uint32_t simulation);

// The time between logged steps [s]: step size x stateEvery x logInterval.
double LoggedStepTime(DbConnection* db, uint32_t simulation);
// Whether the joints of the simulation were logged with the sim's
// continuous angle (schema 5 on, a sim that publishes it).
bool HasStoredContinuousAngle(DbConnection* db, uint32_t simulation);

}  // namespace simpartner::logger
