// The MuJoCo engine's soil (docs/soil.md): each wheel on a ground of
// soil meets the engine-neutral rows of soil_contact.h, as on ODE. MuJoCo
// has no row whose force is a law of its own velocity (its contacts'
// reference accelerations are springs and dampers towards the surface),
// so the rows are solved here, before MuJoCo's constraint solve, with the
// step's own inertia: for the rows' velocities after the step
//   v+ = v_free + h A f,  A = J M^-1 J^T,
// v_free what the smooth forces and the soil's plain forces give, each
// row's law
//   normal:  f = -k h v+           (k times the step's sinking; with
//                                   the plain force, at least 0)
//   shear:   f = T0 + T' (v+ - v0)  (|f| <= the shear strength)
// is a box-bounded linear problem with a symmetric positive definite
// matrix D^-1 + h A (D the laws' slopes), solved directly, or by
// projected Gauss-Seidel where a bound holds. ODE solves the same rows
// with the rest of its constraints; here the other contacts and the
// joint stops are solved after them, with the soil's forces applied.
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "mujoco_mjcf.h"
#include "mujoco_world.h"

namespace simpartner::sim {
namespace {

// Projected Gauss-Seidel: sweeps at most, and the change [N] of a sweep
// below which it stops.
constexpr int kMostSweeps = 200;
constexpr double kSweepTolerance = 1e-9;

Eigen::Vector3d At(const mjtNum* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

// Solves Q f = q for f within [lo, hi], Q symmetric positive definite:
// the direct solution when it is inside, projected Gauss-Seidel from its
// projection else. `ldlt` is working space.
void SolveBoxed(const Eigen::MatrixXd& Q, const Eigen::VectorXd& q, const Eigen::VectorXd& lo,
                const Eigen::VectorXd& hi, Eigen::LDLT<Eigen::MatrixXd>* ldlt,
                Eigen::VectorXd* f) {
  ldlt->compute(Q);
  *f = ldlt->solve(q);
  if (((f->array() >= lo.array()) && (f->array() <= hi.array())).all()) return;
  *f = f->cwiseMax(lo).cwiseMin(hi);
  for (int sweep = 0; sweep < kMostSweeps; ++sweep) {
    double change = 0.0;
    for (Eigen::Index r = 0; r < f->size(); ++r) {
      const double rest = Q.row(r).dot(*f) - Q(r, r) * (*f)[r];
      const double next = std::clamp((q[r] - rest) / Q(r, r), lo[r], hi[r]);
      change = std::max(change, std::abs(next - (*f)[r]));
      (*f)[r] = next;
    }
    if (change < kSweepTolerance) return;
  }
}

}  // namespace

void MujocoWorld::MapSoil() {
  const model::World& world = *model_.world;
  soil_ground_.assign(static_cast<size_t>(m_->ngeom), -1);
  if (world.has_plane)
    if (const model::SoilParameters* soil = world.FindSoil(world.plane_material)) {
      if (!soil_) soil_ = std::make_unique<SoilContacts>(params_.stepsize);
      soil_ground_[static_cast<size_t>(mj_name2id(m_, mjOBJ_GEOM, kMjcfPlane))] =
          soil_->AddPlane(world.plane, *soil);
    }
  if (world.heightfield)
    if (const model::SoilParameters* soil = world.FindSoil(world.heightfield->material)) {
      if (!soil_) soil_ = std::make_unique<SoilContacts>(params_.stepsize);
      soil_ground_[static_cast<size_t>(mj_name2id(m_, mjOBJ_GEOM, kMjcfField))] =
          soil_->AddHeightfield(*soil, *world.heightfield, world.HeightfieldPose());
    }
  if (!soil_) return;
  soil_met_.assign(static_cast<size_t>(m_->ngeom), 0u);
  soil_scratch_.qfrc = Eigen::VectorXd::Zero(m_->nv);
  soil_scratch_.qacc = Eigen::VectorXd::Zero(m_->nv);
  soil_scratch_.vel = Eigen::VectorXd::Zero(m_->nv);
  soil_scratch_.point_jac.resize(3, m_->nv);
  // The grounds of soil and the geoms that may press them: both lists are
  // the model's, found once; a step evaluates the pairs MuJoCo's
  // collision found (soil_met_).
  for (int g = 0; g < m_->ngeom; ++g) {
    if (soil_ground_[static_cast<size_t>(g)] >= 0) soil_ground_geoms_.push_back(g);
    if (IsWheel(g) || IsPlate(g)) soil_pressers_.push_back(g);
  }
}

bool MujocoWorld::IsWheel(int geom) const {
  return m_->geom_type[geom] == mjGEOM_CYLINDER && m_->geom_bodyid[geom] > 0;
}

bool MujocoWorld::IsPlate(int geom) const {
  const int type = m_->geom_type[geom];
  return (type == mjGEOM_BOX || type == mjGEOM_SPHERE || type == mjGEOM_CAPSULE) &&
         m_->geom_bodyid[geom] > 0;
}

void MujocoWorld::DropSoilContacts() {
  if (!soil_) return;
  std::fill(soil_met_.begin(), soil_met_.end(), 0u);
  int kept = 0;
  for (int i = 0; i < d_->ncon; ++i) {
    const mjContact& contact = d_->contact[i];
    const int g1 = contact.geom1, g2 = contact.geom2;
    const int ground1 = soil_ground_[static_cast<size_t>(g1)];
    const int ground2 = soil_ground_[static_cast<size_t>(g2)];
    if (ground2 >= 0 && (IsWheel(g1) || IsPlate(g1))) {  // the soil answers it
      soil_met_[static_cast<size_t>(g1)] |= 1u << ground2;
    } else if (ground1 >= 0 && (IsWheel(g2) || IsPlate(g2))) {
      soil_met_[static_cast<size_t>(g2)] |= 1u << ground1;
    } else {
      if (kept != i) d_->contact[kept] = contact;
      ++kept;
    }
  }
  d_->ncon = kept;
}

WheelState MujocoWorld::WheelStateOf(int geom) const {
  WheelState wheel;
  wheel.radius = m_->geom_size[3 * geom];
  wheel.width = 2.0 * m_->geom_size[3 * geom + 1];
  wheel.centre = At(d_->geom_xpos + 3 * geom);
  const mjtNum* r = d_->geom_xmat + 9 * geom;  // row-major: column 2 is the axis
  wheel.axle = Eigen::Vector3d(r[2], r[5], r[8]).normalized();
  const int body = m_->geom_bodyid[geom];
  wheel.velocity = PointVelocity(body, wheel.centre);
  wheel.angular_velocity = At(d_->cvel + 6 * body);
  return wheel;
}

PlateState MujocoWorld::PlateOf(int geom) const {
  PlateState plate;
  const mjtNum* size = m_->geom_size + 3 * geom;
  switch (m_->geom_type[geom]) {
    case mjGEOM_BOX:
      plate.kind = model::GeometryKind::kBox;
      plate.size = 2.0 * At(size);
      break;
    case mjGEOM_SPHERE:
      plate.kind = model::GeometryKind::kSphere;
      plate.size.x() = size[0];
      break;
    default:
      plate.kind = model::GeometryKind::kCapsule;
      plate.size = Eigen::Vector3d(size[0], 2.0 * size[1], 0.0);
  }
  plate.pose.translation() = At(d_->geom_xpos + 3 * geom);
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) plate.pose.linear()(row, col) = d_->geom_xmat[9 * geom + 3 * row + col];
  const int body = m_->geom_bodyid[geom];
  plate.velocity = PointVelocity(body, plate.pose.translation());
  plate.angular_velocity = At(d_->cvel + 6 * body);
  return plate;
}

void MujocoWorld::ApplySoil() {
  if (!soil_) return;
  on_soil_.clear();
  SoilScratch& s = soil_scratch_;
  s.qfrc.setZero();
  for (int g : soil_pressers_) CollectSoilContacts(g);
  if (on_soil_.empty()) return;
  // The plain forces, then the rows solved with the acceleration they give.
  for (const SoilBody& wheel : on_soil_) {
    mjtNum centre[3] = {wheel.rows.centre.x(), wheel.rows.centre.y(), wheel.rows.centre.z()};
    mj_applyFT(m_, d_, wheel.rows.force.data(), wheel.rows.torque.data(), centre,
               m_->geom_bodyid[wheel.geom], s.qfrc.data());
  }
  mj_solveM(m_, d_, s.qacc.data(), s.qfrc.data(), 1);
  SolveSoilRows();
  // As Cartesian forces on the bodies (xfrc_applied, at their centres of
  // mass), not generalized ones: MuJoCo's joint reactions
  // (mj_rnePostConstraint, the joints' force readouts) count only these.
  for (SoilBody& wheel : on_soil_) {
    const int body = m_->geom_bodyid[wheel.geom];
    const Eigen::Vector3d com = At(d_->xipos + 3 * body);
    const SoilContactRows& r = wheel.rows;
    wheel.force = r.force + wheel.row_force;
    wheel.torque =
        r.torque + (r.centre - com).cross(r.force) + (r.point - com).cross(wheel.row_force);
    for (int k = 0; k < 3; ++k) {
      d_->xfrc_applied[6 * body + k] += wheel.force[k];
      d_->xfrc_applied[6 * body + 3 + k] += wheel.torque[k];
    }
  }
  mj_fwdAcceleration(m_, d_);
}

void MujocoWorld::CollectSoilContacts(int geom) {
  const int body = geoms_[static_cast<size_t>(geom)].body;
  for (int ground_geom : soil_ground_geoms_) {
    const int ground = soil_ground_[static_cast<size_t>(ground_geom)];
    // Only where MuJoCo's collision found the geom below the ground's
    // surface: every geom above the soil is passed over at once.
    if (!(soil_met_[static_cast<size_t>(geom)] & (1u << ground))) continue;
    const std::optional<SoilContactRows> rows =
        IsWheel(geom) ? soil_->Contact(ground, body, WheelStateOf(geom))
                      : soil_->PlateContact(ground, PlateOf(geom));
    if (rows) on_soil_.push_back(SoilBody{geom, *rows});
  }
}

void MujocoWorld::SolveSoilRows() {
  const int nv = m_->nv;
  const auto rows = static_cast<Eigen::Index>(3 * on_soil_.size());
  const double h = params_.stepsize;
  SoilScratch& s = soil_scratch_;
  // J: each wheel's rows (up, forward, across) at its lowest rim point.
  s.J.resize(rows, nv);
  s.X.resize(rows, nv);
  for (size_t w = 0; w < on_soil_.size(); ++w) {
    const SoilContactRows& r = on_soil_[w].rows;
    mjtNum point[3] = {r.point.x(), r.point.y(), r.point.z()};
    mj_jac(m_, d_, s.point_jac.data(), nullptr, point, m_->geom_bodyid[on_soil_[w].geom]);
    const Eigen::Vector3d directions[3] = {r.up, r.forward, r.across};
    for (int k = 0; k < 3; ++k)
      s.J.row(static_cast<Eigen::Index>(3 * w + k)).noalias() =
          directions[k].transpose() * s.point_jac;
  }
  // A = J M^-1 J^T = X X^T with X = D^-1/2 L^-T J^T: half MuJoCo's solve.
  mj_solveM2(m_, d_, s.X.data(), s.J.data(), static_cast<int>(rows));
  const Eigen::Map<const Eigen::VectorXd> qvel(d_->qvel, nv), qacc(d_->qacc_smooth, nv);
  s.vel.noalias() = qvel + h * (qacc + s.qacc);  // without the rows
  s.v_free.noalias() = s.J * s.vel;
  // Each row's law f = c - d v+ (d > 0), bounds lo..hi; then
  // (D^-1 + h A) f = D^-1 c - v_free.
  for (Eigen::VectorXd* v : {&s.c, &s.d, &s.lo, &s.hi}) v->resize(rows);
  for (size_t w = 0; w < on_soil_.size(); ++w) {
    const SoilContactRows& r = on_soil_[w].rows;
    const auto i = static_cast<Eigen::Index>(3 * w);
    s.c[i] = 0.0;
    s.d[i] = r.stiffness * h;
    // The row adds to the plain force; their sum, not the row, is >= 0:
    // a rising wheel sheds load implicitly too (else the step would push
    // it up with the force of where it started, and pump the bounce).
    s.lo[i] = -std::max(0.0, r.force.dot(r.up));
    s.hi[i] = INFINITY;
    const double slopes[2] = {r.thrust_slope, r.side_slope};
    const double at[2] = {r.slip_velocity, r.side_velocity};
    const double force[2] = {r.thrust, r.side_force};
    for (int k = 0; k < 2; ++k) {
      s.d[i + 1 + k] = -slopes[k];
      s.c[i + 1 + k] = force[k] - slopes[k] * at[k];
      s.lo[i + 1 + k] = -r.shear_strength;
      s.hi[i + 1 + k] = r.shear_strength;
    }
  }
  s.Q.resize(rows, rows);
  s.Q.noalias() = h * s.X.lazyProduct(s.X.transpose());
  s.Q.diagonal() += s.d.cwiseInverse();
  s.q.noalias() = s.c.cwiseQuotient(s.d) - s.v_free;
  SolveBoxed(s.Q, s.q, s.lo, s.hi, &s.ldlt, &s.f);
  for (size_t w = 0; w < on_soil_.size(); ++w) {
    SoilBody& wheel = on_soil_[w];
    const auto i = static_cast<Eigen::Index>(3 * w);
    wheel.row_force = s.f[i] * wheel.rows.up + s.f[i + 1] * wheel.rows.forward +
                      s.f[i + 2] * wheel.rows.across;
  }
}

void MujocoWorld::CollectSoilForces() {
  if (!soil_) return;
  for (const SoilBody& wheel : on_soil_) soil_->RowForce(wheel.rows, wheel.row_force);
  soil_->AfterStep(&messages_);
  contact_count_ += static_cast<int>(on_soil_.size());
  for (const SoilBody& wheel : on_soil_) {
    const int mj_body = m_->geom_bodyid[wheel.geom];
    const auto b = static_cast<size_t>(flat_body_[static_cast<size_t>(mj_body)]);
    contact_force_[b] += wheel.force;
    contact_torque_[b] += wheel.torque;
  }
}

std::vector<WheelSoilReadout> MujocoWorld::ReadWheelSoil() const {
  if (!soil_) return {};
  return soil_->LastStep();
}

}  // namespace simpartner::sim
