// The description of a world and its robots as loaded from XML: what the
// files say, validated, in SI units. The physics process builds ODE objects
// from it; nothing here changes while the simulation runs.
#pragma once

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

namespace simpartner::model {

// Where an element was written, for messages that point at it later.
struct SourceLocation {
  std::string file;
  int line = 0;
};

enum class GeometryKind { kNone, kBox, kSphere, kCylinder, kCapsule };
enum class JointKind { kFixed, kHinge, kSlider, kBall, kUniversal, kHinge2 };
enum class SensorKind { kEcho, kPosition, kScanner, kVelocity, kForceTorque,
                        kImu, kGnss, kEncoder, kLidar, kContact, kCamera };
enum class ActuatorKind { kJointVelocity, kAngle, kLinearMotor };
enum class CollisionSpaceKind { kSimple, kHash, kQuadTree };

const char* ToString(GeometryKind kind);  // the XML type names: "Box", ...
const char* ToString(JointKind kind);
const char* ToString(SensorKind kind);
const char* ToString(ActuatorKind kind);
const char* ToString(CollisionSpaceKind kind);

// Axes a joint kind can be driven along (0 for fixed and ball joints).
int AxisCount(JointKind kind);

struct Geometry {
  GeometryKind kind = GeometryKind::kNone;
  // Box: lx, ly, lz. Sphere: radius, 0, 0. Cylinder/Capsule: radius, length, 0.
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
};

// Which way a contact's first friction direction (the one mu applies
// along) points; mu2 applies perpendicular to it (docs/contacts.md).
enum class FrictionDirection {
  kSlip,     // along the sliding velocity (the thesis's "tangential")
  kRolling,  // along the rolling direction of the body's spin axis (wheels)
};
const char* ToString(FrictionDirection direction);  // "slip", "rolling"

// Soil under a ground geom (a surface or heightfield whose material has
// <soil>, docs/soil.md): Bekker's pressure-sinkage law, Mohr-Coulomb shear
// strength reached over Janosi and Hanamoto's shear deformation, and the
// soil's rebound on unloading. Unlike the rest of this file, in the units
// of the sources (Wong, Theory of Ground Vehicles, 4th ed., Table 2.3), so
// that a library entry reads as its table does.
struct SoilParameters {
  std::string name;     // the library entry (or the material's name when inline)
  std::string source;   // where the figures come from, as the library says
  double n = 0.0;       // sinkage exponent [-], > 0
  double k_c = 0.0;     // cohesive modulus of deformation [kN/m^(n+1)], >= 0
  double k_phi = 0.0;   // frictional modulus of deformation [kN/m^(n+2)], >= 0
  double cohesion = 0.0;        // c [kPa], >= 0
  double friction_angle = 0.0;  // phi [deg], 0 <= phi < 90
  double shear_modulus = 0.0;   // K, shear deformation modulus [m], > 0
  // Unloading and reloading above the deepest sinkage z_max so far follow
  // a line, not Bekker's curve, losing k_u of pressure per metre of
  // rebound; Wong: k_u = k_0 + A_u z_max. k_0 [kPa/m], >= 0, and A_u
  // [kPa/m^2], >= 0 (0 when a file does not give it). The sim never takes
  // k_u shallower than Bekker's curve below z_max (the two never cross).
  double unloading_stiffness = 0.0;
  double unloading_growth = 0.0;
  // Pressure per unit sinkage rate where the soil is loaded [kPa s/m], >= 0.
  double viscosity = 0.0;
  SourceLocation where;  // the <soil> element (or the library entry) it came from
};

struct Material {
  std::string name;
  double mu = 1.0;                 // Coulomb friction along the first direction
  std::optional<double> mu2;       // across it; absent = isotropic (mu)
  FrictionDirection friction_direction = FrictionDirection::kSlip;
  double bounce = 0.0;             // restitution 0..1
  double bounce_velocity = 0.1;    // [m/s]
  // Softness per step (ODE's own numbers: the same values are another
  // stiffness at another step size) ...
  double soft_erp = 0.2;
  double soft_cfm = 1e-5;
  // ... or physical, turned into ERP/CFM for the step size in use. Both set
  // or neither; the loader refuses them beside softERP/softCFM.
  std::optional<double> stiffness; // [N/m] of the whole contact of two geoms
  std::optional<double> damping;   // [N s/m] of the whole contact
  double rolling_friction = 0.0;   // [m]
  std::optional<SoilParameters> soil;  // a ground of soft soil
  SourceLocation where;

  double Mu2() const { return mu2.value_or(mu); }
  bool HasStiffness() const { return stiffness.has_value(); }
};

struct Body {
  std::string name;
  Geometry geometry;
  std::string material;            // "" = default material
  bool is_static = false;          // world objects only
  double mass = 0.0;               // [kg]
  Eigen::Vector3d com = Eigen::Vector3d::Zero();  // [m] in the body frame
  // [kg m^2] about the com, body axes; from the geometry when not given.
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();
  bool inertia_given = false;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();  // in the parent frame
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();   // [m/s]
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  // [rad/s]
  SourceLocation where;
};

struct Joint {
  std::string name;
  JointKind kind = JointKind::kFixed;
  std::string body1;               // body name; "world" for the static world
  std::string body2;
  Eigen::Vector3d anchor = Eigen::Vector3d::Zero();  // [m] in the parent frame
  Eigen::Vector3d axis[2] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
  // Stops per axis [rad] or [m]; infinite when free.
  double lo_stop[3];
  double hi_stop[3];
  SourceLocation where;
  Joint();
};

// A Scanner casts rate x rays rays a second of sim time and puts a double
// per ray on the bus. The bound keeps one scanner at 1.6 MB/s of readings
// at real time (16 MB/s at 10x), within what LCM multicast carries without
// loss beside the states; 10000 Hz x 10000 rays once put 44 MB/s on the
// bus and halved the sim's speed. Checked in robot files and in commands.
inline constexpr double kMaxScannerRaysPerSecond = 200000;
// The most values one reading carries (sensor_reading_t.num_values): a
// Lidar's rays x layers.
inline constexpr double kMaxReadingValues = 100000;

// What a Camera puts beside its colour image (simpartner-camera renders
// it; the sim only announces the camera in SIM_MODEL).
enum class CameraDepth { kNone, kMetres, kMillimetres };
const char* ToString(CameraDepth depth);  // the XML words: "none", "metres", "millimetres"

// The largest camera image side [pixels]: what every OpenGL driver we run
// on can render offscreen (GL_MAX_RENDERBUFFER_SIZE is 16384 on llvmpipe
// and at least 4096 on desktop GPUs); simpartner-camera also checks the
// driver's own limit when it starts.
inline constexpr int kMaxCameraSide = 4096;
// Like the scanner's bound: a camera's images go over LCM multicast beside
// the states, and every pixel costs 3 bytes of colour plus 2 or 4 of depth.
// 2e7 pixels/s (640 x 480 at 60 Hz, 1280 x 720 at 20 Hz) is 140 MB/s with
// float depth, about what one local multicast group carries without loss.
inline constexpr double kMaxCameraPixelsPerSecond = 2e7;

// The nearest a camera draws [m]: nearer clip planes leave a 24-bit depth
// buffer no resolution (the depth step at distance z is about
// z^2 / (near 2^24)), and a robot's camera resolves nothing nearer.
inline constexpr double kMinCameraNear = 1e-3;

struct CameraSettings {
  int width = 640;                  // [pixels]
  int height = 480;                 // [pixels]
  double fov = 1.0471975511965976;  // [rad] horizontal field of view, (0, pi)
  double near = 0.05;               // [m] nearest distance drawn
  double far = 100.0;               // [m] farthest distance drawn
  CameraDepth depth = CameraDepth::kNone;
};

struct Sensor {
  std::string name;
  SensorKind kind = SensorKind::kEcho;
  std::string body;                // mounting body ("" for a joint sensor)
  std::string joint;               // force/torque: the measured joint
  int port = 0;                    // legacy port (> 1024), 0 if none
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();  // in the body frame
  double rate = 0.0;               // [Hz] readings on the bus; 0 = on request
  // Scanner: rays, half-span [rad], range [m].
  int rays = 11;
  double half_span = 0.1;
  double range = 10.0;
  // Imu, Gnss, Encoder, Lidar, Contact: one value per parameter of
  // SensorParameterSpecs(kind) (sensor_parameters.h), in its order.
  std::vector<double> parameters;
  CameraSettings camera;           // Camera only
  SourceLocation where;
};

struct Actuator {
  std::string name;
  ActuatorKind kind = ActuatorKind::kJointVelocity;
  std::string joint;
  int port = 0;
  SourceLocation where;
};

// The axis a body spins about as a wheel, in its body frame (unit), for a
// "rolling" material: the axis of the one Hinge that joins the body (or the
// axle, axis2, of a Hinge2 whose body2 it is); else the axis of its
// Cylinder or Capsule (body z); else none, and *why (when given) says why.
// joints are those of the body's scope (its robot, or the world's objects),
// whose axes are in the same frame as body.pose.
std::optional<Eigen::Vector3d> SpinAxis(const Body& body, const std::vector<Joint>& joints,
                                        std::string* why = nullptr);

// A robot as its file describes it, in the robot frame.
struct Robot {
  std::string model_name;          // the robot element's name attribute
  std::string file;
  std::string description;
  std::vector<Material> materials;
  std::vector<Body> bodies;
  std::vector<Joint> joints;
  std::vector<Sensor> sensors;
  std::vector<Actuator> actuators;

  double TotalMass() const;
  const Body* FindBody(const std::string& name) const;
  const Joint* FindJoint(const std::string& name) const;
};

// A robot placed in a world.
struct RobotInstance {
  std::string name;                // instance name (e.g. "WorkPartner")
  std::string file;                // as written in the world file
  std::string resolved_file;       // path the loader opened
  Eigen::Isometry3d placement = Eigen::Isometry3d::Identity();
  Robot robot;
  SourceLocation where;
};

struct Heightfield {
  int rows = 0;                    // samples along depth (z in a y-up world)
  int columns = 0;                 // samples along width (x)
  double width = 0.0;              // [m]
  double depth = 0.0;              // [m]
  double scale = 1.0;
  double offset = 0.0;             // [m]
  double thickness = 1.0;          // [m]
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  std::string material;
  std::vector<double> samples;     // row-major, rows * columns
  SourceLocation where;

  // Height at (x, z) in the field's frame, linearly interpolated; clamped
  // at the borders.
  double HeightAt(double x, double z) const;
};

// Where the world's origin is on the Earth (WGS-84), for GNSS sensors.
struct GeodeticOrigin {
  double latitude = 0.0;           // [deg] north positive
  double longitude = 0.0;          // [deg] east positive
  double altitude = 0.0;           // [m] above the ellipsoid
  SourceLocation where;
};

struct World {
  std::string name;
  std::string file;
  std::string description;
  Eigen::Vector3d gravity{0.0, -9.81, 0.0};
  bool has_plane = false;
  Eigen::Vector4d plane{0.0, 1.0, 0.0, 0.0};  // a, b, c (unit), d
  std::string plane_material;
  CollisionSpaceKind collision_space = CollisionSpaceKind::kHash;
  std::vector<Material> materials;
  std::optional<Heightfield> heightfield;
  std::vector<Body> objects;
  std::vector<Joint> joints;
  std::vector<RobotInstance> robots;
  std::optional<GeodeticOrigin> geodetic_origin;  // absent: GNSS refers to 0 N 0 E, 0 m

  // Unit vector opposite to gravity (+y when there is no gravity).
  Eigen::Vector3d Up() const;
  // Where the engines put the heightfield: its samples' y turned onto Up()
  // (the shortest turn), at its position. Identity without a heightfield.
  Eigen::Isometry3d HeightfieldPose() const;
  const Material* FindMaterial(const std::string& name) const;
  // The soil of material `name`; null when it is no soil or "" or absent.
  const SoilParameters* FindSoil(const std::string& material) const;
  // Whether the surface or the heightfield is of soil.
  bool HasSoilGround() const;
};

// What ODE can integrate in double precision with the sim's steppers: the
// loader refuses anything outside, so that what --check passes the sim
// runs. models/README.md ("Physical ranges") derives each number.
namespace limits {
inline constexpr double kMinMass = 1e-4;            // [kg] a moving body
inline constexpr double kMaxMass = 1e6;             // [kg]
inline constexpr double kMinSize = 1e-3;            // [m] box side, radius, length
inline constexpr double kMaxSize = 1e4;             // [m]
inline constexpr double kMaxCoordinate = 1e6;       // [m] |x|, |y|, |z| of anything placed
inline constexpr double kMaxLinearSpeed = 1e4;      // [m/s] initial velocity
inline constexpr double kMaxAngularSpeed = 1e4;     // [rad/s] initial rotation
inline constexpr double kMinMoment = 1e-11;         // [kg m^2] principal moment of inertia
inline constexpr double kMaxMoment = 1e14;          // [kg m^2]
inline constexpr double kMaxInertiaRatio = 1e6;     // largest / smallest principal moment
inline constexpr double kMaxJointMassRatio = 1e4;   // heavier / lighter body of a joint
inline constexpr double kMaxRobotMassRatio = 1e6;   // heaviest / lightest moving body of a robot
inline constexpr double kMaxContactStiffness = 1e12; // [N/m] material stiffness (above 0)
inline constexpr double kMaxContactDamping = 1e9;    // [N s/m] material damping
}  // namespace limits

// Inertia tensor of a uniform solid of the geometry's shape about its centre.
// A point mass (kNone) gets the inertia of a solid sphere of radius 0.1 m.
Eigen::Matrix3d SolidInertia(const Geometry& geometry, double mass);

}  // namespace simpartner::model
