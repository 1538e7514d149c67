#include "model_rows.h"

#include <cppconn/exception.h>

#include <limits>
#include <string>

#include "row_sink.h"
#include "simpartner/logger/sql_text.h"
#include "simpartner/sim_engine.h"
#include "writer_text.h"

namespace simpartner::logger {
namespace {

void InsertRobots(DbConnection* db, const model_t& model, uint32_t simulation) {
  if (model.robots.empty()) return;
  RowSink robots(db, InsertMethod::kMultiRowInsert, "", "Robot",
                 "simulationID,busIndex,name,model,file,totalMass");
  for (size_t i = 0; i < model.robots.size(); ++i) {
    const robot_t& r = model.robots[i];
    robots.BeginRow();
    robots.Int(simulation);
    robots.Int(static_cast<int64_t>(i));
    robots.Text(r.name);
    robots.Text(r.model);
    robots.Text(r.file);
    robots.Double(r.total_mass);
    robots.EndRow();
  }
  robots.Finish();
}

void InsertMaterials(DbConnection* db, const model_t& model, uint32_t simulation) {
  if (model.materials.empty()) return;
  RowSink materials(db, InsertMethod::kMultiRowInsert, "", "Material",
                    "simulationID,busIndex,name,mu,mu2,frictionDirection,bounce,"
                    "bounceVelocity,softERP,softCFM,stiffness,damping,rollingFriction,soil,"
                    "soilN,soilKc,soilKphi,soilCohesion,soilFrictionAngle,soilShearModulus,"
                    "soilUnloadingStiffness,soilViscosity");
  constexpr double kNull = std::numeric_limits<double>::quiet_NaN();
  for (size_t i = 0; i < model.materials.size(); ++i) {
    const material_t& m = model.materials[i];
    // A physical material (stiffness and damping) has no ERP and CFM, and the reverse.
    const bool physical = m.stiffness > 0.0;
    materials.BeginRow();
    materials.Int(simulation);
    materials.Int(static_cast<int64_t>(i));
    materials.Text(m.name);
    materials.Double(m.mu);
    materials.Double(m.mu2);
    materials.Text(m.friction_direction == material_t::FRICTION_ROLLING ? "ROLLING" : "SLIP");
    materials.Double(m.bounce);
    materials.Double(m.bounce_velocity);
    materials.Double(physical ? kNull : m.soft_erp);
    materials.Double(physical ? kNull : m.soft_cfm);
    materials.Double(physical ? m.stiffness : kNull);
    materials.Double(physical ? m.damping : kNull);
    materials.Double(m.rolling_friction);
    // A material that is not a soil has NULL soil figures.
    if (m.is_soil)
      materials.Text(m.soil_name);
    else
      materials.Expression("NULL");
    for (double figure : {m.soil_n, m.soil_kc, m.soil_kphi, m.soil_cohesion, m.soil_friction_angle,
                          m.soil_shear_modulus, m.soil_unloading_stiffness, m.soil_viscosity})
      materials.Double(m.is_soil ? figure : kNull);
    materials.EndRow();
  }
  materials.Finish();
}

// The bus index of the material named `name`; -1 (NULL) for "", the default material.
int64_t MaterialIndex(const model_t& model, const std::string& name) {
  for (size_t i = 0; i < model.materials.size(); ++i)
    if (model.materials[i].name == name) return static_cast<int64_t>(i);
  return -1;
}

void InsertBodies(DbConnection* db, const model_t& model, uint32_t simulation,
                  const ModelIds& ids, const std::vector<int64_t>& material_ids) {
  if (model.bodies.empty()) return;
  RowSink bodies(db, InsertMethod::kMultiRowInsert, "", "Body",
                 "simulationID,robotID,busIndex,name,type,dimX,dimY,dimZ,mass,comX,comY,comZ,"
                 "Ixx,Iyy,Izz,Ixy,Ixz,Iyz,material,materialID,isStatic");
  for (size_t i = 0; i < model.bodies.size(); ++i) {
    const body_t& b = model.bodies[i];
    bodies.BeginRow();
    bodies.Int(simulation);
    bodies.Id(ids.robot_ids, b.robot);
    bodies.Int(static_cast<int64_t>(i));
    bodies.Text(b.name);
    bodies.Text(GeometryName(b.geometry.kind));
    for (double d : b.geometry.size) bodies.Double(d);
    bodies.Double(b.mass);
    for (double c : b.com) bodies.Double(c);
    for (double in : b.inertia) bodies.Double(in);
    bodies.Text(b.material);
    bodies.Id(material_ids, MaterialIndex(model, b.material));
    bodies.Int(b.is_static ? 1 : 0);
    bodies.EndRow();
  }
  bodies.Finish();
}

void InsertJoints(DbConnection* db, const model_t& model, uint32_t simulation, const ModelIds& ids) {
  if (model.joints.empty()) return;
  RowSink joints(db, InsertMethod::kMultiRowInsert, "", "`Joint`",
                 "simulationID,robotID,busIndex,name,type,body1ID,body2ID,numAxes,anchorX,"
                 "anchorY,anchorZ,axis1X,axis1Y,axis1Z,axis2X,axis2Y,axis2Z,axis3X,axis3Y,"
                 "axis3Z,loStop1,hiStop1,loStop2,hiStop2,loStop3,hiStop3");
  for (size_t i = 0; i < model.joints.size(); ++i) {
    const joint_t& j = model.joints[i];
    joints.BeginRow();
    joints.Int(simulation);
    joints.Id(ids.robot_ids, j.robot);
    joints.Int(static_cast<int64_t>(i));
    joints.Text(j.name);
    joints.Text(JointName(j.kind));
    joints.Id(ids.body_ids, j.body1);
    joints.Id(ids.body_ids, j.body2);
    joints.Int(j.num_axes);
    for (double a : j.anchor) joints.Double(a);
    for (const auto& axis : j.axis)
      for (double a : axis) joints.Double(a);
    for (int a = 0; a < 3; ++a) {
      joints.Double(j.lo_stop[a]);  // +-inf (free) becomes NULL
      joints.Double(j.hi_stop[a]);
    }
    joints.EndRow();
  }
  joints.Finish();
}

void InsertSensors(DbConnection* db, const model_t& model, uint32_t simulation, const ModelIds& ids) {
  if (model.sensors.empty()) return;
  RowSink sensors(db, InsertMethod::kMultiRowInsert, "", "Sensor",
                  "simulationID,robotID,busIndex,name,type,bodyID,jointID,port,rate,params");
  for (size_t i = 0; i < model.sensors.size(); ++i) {
    const sensor_t& s = model.sensors[i];
    sensors.BeginRow();
    sensors.Int(simulation);
    sensors.Id(ids.robot_ids, s.robot);
    sensors.Int(static_cast<int64_t>(i));
    sensors.Text(s.name);
    sensors.Text(SensorName(s.kind));
    sensors.Id(ids.body_ids, s.body);
    sensors.Id(ids.joint_ids, s.joint);
    sensors.Int(s.port);
    sensors.Double(s.rate);
    sensors.Text(JoinValues(s.params));
    sensors.EndRow();
  }
  sensors.Finish();
}

// Returns the actuators' ids (none without actuators).
std::vector<int64_t> InsertActuators(DbConnection* db, const model_t& model, uint32_t simulation,
                                     const ModelIds& ids) {
  if (model.actuators.empty()) return {};
  RowSink actuators(db, InsertMethod::kMultiRowInsert, "", "Actuator",
                    "simulationID,robotID,busIndex,name,type,jointID,port");
  for (size_t i = 0; i < model.actuators.size(); ++i) {
    const actuator_t& a = model.actuators[i];
    actuators.BeginRow();
    actuators.Int(simulation);
    actuators.Id(ids.robot_ids, a.robot);
    actuators.Int(static_cast<int64_t>(i));
    actuators.Text(a.name);
    actuators.Text(ActuatorName(a.kind));
    actuators.Id(ids.joint_ids, a.joint);
    actuators.Int(a.port);
    actuators.EndRow();
  }
  actuators.Finish();
  return LoadIds(db, "Actuator", "actuatorID", simulation, model.actuators.size());
}

// RobotComponent: what each robot is made of, by name.
void InsertComponents(DbConnection* db, const model_t& model, const ModelIds& ids,
                      const std::vector<int64_t>& actuator_ids) {
  RowSink components(db, InsertMethod::kMultiRowInsert, "", "RobotComponent",
                     "robotID,type,name,reference");
  auto component = [&](int16_t robot, const char* type, const std::string& name,
                       const std::vector<int64_t>& part_ids, size_t index) {
    if (robot < 0 || robot >= static_cast<int16_t>(ids.robot_ids.size())) return;
    components.BeginRow();
    components.Int(ids.robot_ids[static_cast<size_t>(robot)]);
    components.Text(type);
    components.Text(name);
    components.Int(part_ids[index]);
    components.EndRow();
  };
  for (size_t i = 0; i < model.bodies.size(); ++i)
    component(model.bodies[i].robot, "BODY", model.bodies[i].name, ids.body_ids, i);
  for (size_t i = 0; i < model.joints.size(); ++i)
    component(model.joints[i].robot, "JOINT", model.joints[i].name, ids.joint_ids, i);
  for (size_t i = 0; i < model.sensors.size(); ++i)
    component(model.sensors[i].robot, "SENSOR", model.sensors[i].name, ids.sensor_ids, i);
  for (size_t i = 0; i < model.actuators.size(); ++i)
    component(model.actuators[i].robot, "ACTUATOR", model.actuators[i].name, actuator_ids, i);
  components.Finish();
}

}  // namespace

uint32_t InsertSimulation(DbConnection* db, const model_t& model, const WriterOptions& options,
                          int64_t received_us) {
  std::string sql =
      "INSERT INTO Simulation (busSimulationID, host, lcmUrl, startTime, worldFile, worldName, "
      "engine, parameters, stepSize, stateEvery, logInterval, gravityX, gravityY, gravityZ, tag) "
      "VALUES (";
  AppendInt(&sql, model.simulation_id);
  sql += "," + Quoted(model.host) + "," + Quoted(options.lcm_url) + "," +
         UtcFromMicros(received_us) + "," + Quoted(model.world_file) + "," +
         Quoted(model.world_name) + "," + Quoted(SimEngine(model.engine)) + "," +
         Quoted(model.parameters) + ",";
  AppendDouble(&sql, model.step_size);
  sql += "," + std::to_string(model.state_every) + "," + std::to_string(options.log_interval);
  for (double g : model.gravity) {
    sql += ",";
    AppendDouble(&sql, g);
  }
  sql += "," + (options.tag.empty() ? std::string("NULL") : Quoted(options.tag)) + ")";
  db->Execute(sql, "INSERT INTO Simulation");
  return static_cast<uint32_t>(db->QueryInt("SELECT LAST_INSERT_ID()", "SELECT LAST_INSERT_ID()", 0));
}

ModelIds InsertModelRows(DbConnection* db, const model_t& model, uint32_t simulation) {
  ModelIds ids;
  InsertRobots(db, model, simulation);
  ids.robot_ids = LoadIds(db, "Robot", "robotID", simulation, model.robots.size());
  InsertMaterials(db, model, simulation);
  const std::vector<int64_t> material_ids =
      LoadIds(db, "Material", "materialID", simulation, model.materials.size());
  InsertBodies(db, model, simulation, ids, material_ids);
  ids.body_ids = LoadIds(db, "Body", "bodyID", simulation, model.bodies.size());
  InsertJoints(db, model, simulation, ids);
  ids.joint_ids = LoadIds(db, "`Joint`", "jointID", simulation, model.joints.size());
  InsertSensors(db, model, simulation, ids);
  ids.sensor_ids = LoadIds(db, "Sensor", "sensorID", simulation, model.sensors.size());
  const std::vector<int64_t> actuator_ids = InsertActuators(db, model, simulation, ids);
  InsertComponents(db, model, ids, actuator_ids);
  return ids;
}

std::vector<int64_t> LoadIds(DbConnection* db, const char* table, const char* id_column,
                             uint32_t simulation, size_t count) {
  std::vector<int64_t> ids(count, -1);
  std::unique_ptr<sql::ResultSet> rows =
      db->Query(std::string("SELECT busIndex, ") + id_column + " FROM " + table +
                    " WHERE simulationID = " + std::to_string(simulation),
                std::string("SELECT FROM ") + table);
  try {
    while (rows->next()) {
      const int64_t index = rows->getInt64(1);
      if (index >= 0 && index < static_cast<int64_t>(count))
        ids[static_cast<size_t>(index)] = rows->getInt64(2);
    }
  } catch (const sql::SQLException&) {
    db->Rethrow(std::string("read ") + table);
  }
  return ids;
}

}  // namespace simpartner::logger
