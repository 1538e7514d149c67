// The parameters of a run: `key=value` lines in parameters.txt (the
// original's keys plus ours), any key overridden on the command line as
// --key=value. One struct for the whole system: every process reads the keys
// that apply to it, and every process refuses a key nobody knows.
#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "simpartner/diagnostic.h"

namespace simpartner {

inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";
inline constexpr const char* kDefaultParametersFile = "parameters.txt";

// The sections of parameters.txt. One file serves every program; each
// program's --help lists only the sections it reads.
namespace parameter_sections {
inline constexpr const char* kDatabase = "Database logging (simpartner-logger)";
inline constexpr const char* kWorld = "World";
inline constexpr const char* kStepping = "Stepping (ODE)";
inline constexpr const char* kContact = "Default contact material";
inline constexpr const char* kRunning = "Running";
inline constexpr const char* kTransport = "Transport";
}  // namespace parameter_sections

struct Parameters {
  // Database logging (logger).
  std::string dbname = "simpartner";
  std::string dbserver;  // "" = the private server the scripts start
  bool log = true;
  bool logEveryStep = true;
  int logInterval = 10;

  // World.
  std::string environment = "models/worlds/flat_ground.xml";

  // Stepping.
  double stepsize = 0.001;
  std::string engine = "ode";
  std::string stepper = "accurate";
  int quickStepIterations = 20;
  double quickStepW = 1.3;
  double globalERP = 0.2;
  double globalCFM = 1e-5;
  // The joints' rows as a spring and damper, the same at any step (ERP 0.2
  // and CFM 1e-5 at 1 ms); jointStiffness 0 = globalERP and globalCFM.
  double jointStiffness = 2e7;
  double jointDamping = 8e4;
  // A joint motor's velocity per force, its softness under load: the
  // same at any step (globalCFM's 1e-5 of the original).
  double motorCompliance = 1e-5;
  double contactMaxCorrectingVel = 0.2;
  double contactSurfaceLayer = 0.0;
  bool autoDisableFlag = false;
  bool soilSettle = true;
  int maxContacts = 8;

  // Default contact material (used where the world names none).
  double contactMu = 1.0;
  double contactBounce = 0.0;
  double contactBounceVelocity = 0.1;
  double contactSoftERP = 0.2;
  double contactSoftCFM = 1e-5;
  double rollingFriction = 0.0;
  double contactSlip = 1e-7;

  // Running.
  double speed = 1.0;
  double duration = 0.0;
  bool startPaused = false;
  int stateEvery = 1;
  double modelPeriod = 1.0;
  double statusPeriod = 1.0;
  double maxLinearVelocity = 1000.0;
  double maxAngularVelocity = 10000.0;
  double lockStepTimeout = 5.0;
  int sensorSeed = 0;

  // Transport.
  std::string lcmUrl = kDefaultLcmUrl;

  // The ERP and CFM of every joint row at this step size: from
  // jointStiffness and jointDamping, else globalERP and globalCFM.
  double JointERP() const {
    if (jointStiffness <= 0.0) return globalERP;
    return stepsize * jointStiffness / (stepsize * jointStiffness + jointDamping);
  }
  double JointCFM() const {
    if (jointStiffness <= 0.0) return globalCFM;
    return 1.0 / (stepsize * jointStiffness + jointDamping);
  }
  // The CFM of every joint motor's row: a velocity per force, so the
  // same number at any step (ODE's motor row has no spring, only this).
  double MotorCFM() const { return jointStiffness <= 0.0 ? globalCFM : motorCompliance; }

  // Lists every key with its type, range and documentation. The visitor has
  // Section(title), Bool, Int, Double, String, Path and Choice members.
  template <class Visitor>
  void Visit(Visitor& v) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    v.Section(parameter_sections::kDatabase);
    v.String("dbname", dbname, "database (schema) name");
    v.String("dbserver", dbserver,
             "server as host[:port] or a unix socket path; empty = the "
             "private server scripts/run starts");
    v.Bool("log", log, "write the run into the database");
    v.Bool("logEveryStep", logEveryStep,
           "log every step; when 0, log every logInterval-th step");
    v.Int("logInterval", logInterval, 1, 1000000,
          "steps between logged rows when logEveryStep=0");

    v.Section(parameter_sections::kWorld);
    v.Path("environment", environment,
           "world XML file (in a parameters file: relative to that file; on "
           "the command line: as given, else looked up as data: $SIMPARTNER_DATA, "
           "the shipped models/worlds)");

    v.Section(parameter_sections::kStepping);
    v.Double("stepsize", stepsize, 1e-5, 0.1,
             "fixed step [s]; stable range roughly 0.001 to 0.02");
    v.Choice("engine", engine, {"ode", "mujoco"},
             "physics engine: ode = ODE (the original's, the validated default), "
             "mujoco = MuJoCo 2.2 (docs/engines.md)");
    v.Choice("stepper", stepper, {"accurate", "quick"},
             "accurate = dWorldStep (exact LCP, slow), quick = "
             "dWorldQuickStep (iterative)");
    v.Int("quickStepIterations", quickStepIterations, 1, 100000,
          "iterations of dWorldQuickStep");
    v.Double("quickStepW", quickStepW, 0.01, 2.0,
             "successive over-relaxation factor of dWorldQuickStep");
    v.Double("globalERP", globalERP, 0.0, 1.0,
             "error reduction parameter of every joint row, per step (the original's); "
             "used only with jointStiffness=0");
    v.Double("globalCFM", globalCFM, 0.0, 1.0,
             "constraint force mixing of every joint row, per step; used only with "
             "jointStiffness=0");
    v.Double("jointStiffness", jointStiffness, 0.0, kInf,
             "[N/m; N m/rad on rotational rows] every joint row's (and stop's) stiffness: "
             "with jointDamping it gives each step's ERP = h k / (h k + c) and CFM = "
             "1 / (h k + c), the same spring at any step size; 0 = globalERP and globalCFM");
    v.Double("jointDamping", jointDamping, 0.0, kInf,
             "[N s/m; N m s/rad] every joint row's damping, with jointStiffness");
    v.Double("motorCompliance", motorCompliance, 0.0, 1.0,
             "[m/(N s); rad/(N m s)] every joint motor's velocity per force (how far a held "
             "or driven joint yields under load), the same at any step size; with "
             "jointStiffness=0 the motors take globalCFM");
    v.Double("contactMaxCorrectingVel", contactMaxCorrectingVel, 0.0, kInf,
             "[m/s] largest velocity a contact may use to correct penetration");
    v.Double("contactSurfaceLayer", contactSurfaceLayer, 0.0, 1.0,
             "[m] depth of penetration allowed before correction");
    v.Bool("autoDisableFlag", autoDisableFlag,
           "let ODE disable bodies at rest (off keeps runs comparable)");
    v.Int("maxContacts", maxContacts, 1, 256,
          "most contact points generated per touching pair of geoms");
    v.Bool("soilSettle", soilSettle,
           "set a robot on soil down before step 0, so that it starts at rest at its "
           "sinkage (docs/soil.md); 0 drops it from where the file puts it");

    v.Section(parameter_sections::kContact);
    v.Double("contactMu", contactMu, 0.0, kInf, "Coulomb friction coefficient");
    v.Double("contactBounce", contactBounce, 0.0, 1.0, "restitution");
    v.Double("contactBounceVelocity", contactBounceVelocity, 0.0, kInf,
             "[m/s] least impact speed that bounces");
    v.Double("contactSoftERP", contactSoftERP, 0.0, 1.0, "contact ERP");
    v.Double("contactSoftCFM", contactSoftCFM, 0.0, 1.0, "contact CFM");
    v.Double("rollingFriction", rollingFriction, 0.0, 1.0,
             "[m] rolling resistance length (0 = none, as the original)");
    v.Double("contactSlip", contactSlip, 1e-12, 1e-2,
             "[m/(N s)] tangential compliance of every contact: sliding speed per "
             "newton of friction force below mu N (ODE's force-dependent slip; "
             "step-independent; must be > 0 for ODE's solver)");

    v.Section(parameter_sections::kRunning);
    v.Double("speed", speed, 0.0, 1000.0,
             "real-time factor; 0 = as fast as possible");
    v.Double("duration", duration, 0.0, kInf,
             "[s] simulated time after which the sim quits; 0 = run until told");
    v.Bool("startPaused", startPaused, "start paused (resume over SIM_CONTROL)");
    v.Int("stateEvery", stateEvery, 1, 1000000,
          "publish SIM_STATE every N-th step");
    v.Double("modelPeriod", modelPeriod, 0.05, 3600.0,
             "[s] wall time between SIM_MODEL announcements");
    v.Double("statusPeriod", statusPeriod, 0.05, 3600.0,
             "[s] wall time between SIM_STATUS messages");
    v.Double("maxLinearVelocity", maxLinearVelocity, 0.0, kInf,
             "[m/s] a body faster than this is an explosion: the sim pauses");
    v.Double("maxAngularVelocity", maxAngularVelocity, 0.0, kInf,
             "[rad/s] likewise for rotation");
    v.Double("lockStepTimeout", lockStepTimeout, 0.01, 3600.0,
             "[s] wall time the sim waits for a synchronous (lock-step) controller's "
             "answer to a tick before it releases it and runs on without it");
    v.Int("sensorSeed", sensorSeed, 0, 2147483647,
          "seed of the sensors' noise: the same seed gives the same readings, bit for "
          "bit, at any speed (docs/sensors.md)");

    v.Section(parameter_sections::kTransport);
    v.String("lcmUrl", lcmUrl,
             "LCM URL (also --lcm-url); ttl=0 keeps traffic on this host");
  }
};

// Where each parameter value came from, so a later error can point at it.
struct ParameterOrigin {
  std::string file;  // parameters file, or "command line"
  int line = 0;
};

// Where the parameters of a run come from besides the defaults: a file and
// --key=value overrides (command_line.h reads them from a command line).
struct ParameterSources {
  std::string file = kDefaultParametersFile;  // --params FILE
  bool file_given = false;
  // Without --params: ./parameters.txt, else the shipped one (true), or no
  // file at all (false).
  bool default_file = true;
  std::vector<std::pair<std::string, std::string>> overrides;  // key, value; in order
};

// Parses `key=value` text into params. Problems go to diagnostics with file
// and line; the fields named by bad lines keep their previous values.
void ParseParametersText(const std::string& text, const std::string& file_name,
                         Parameters* params, DiagnosticList* diagnostics);

// Loads defaults, then the parameters file (the default one only if it
// exists), then the command-line overrides. Throws ConfigError listing every
// problem (file and line; "command line" for an override).
Parameters LoadParameters(const ParameterSources& sources);

// Effective parameters as `key=value` lines, in the documented order.
std::string FormatParameters(const Parameters& params);

// Documentation of every key (type, range, default, meaning) for --help and
// for checking that parameters.txt documents every key; with sections (of
// parameter_sections), only theirs. An unknown section is a programming
// error (std::invalid_argument).
std::string DescribeParameters(const std::vector<std::string>& sections = {});
std::vector<std::string> ParameterKeys();

}  // namespace simpartner
