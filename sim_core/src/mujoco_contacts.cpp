// The MuJoCo engine's contacts: each point's softness and coefficients
// from its pair's material under ODE's per-step law, its friction frame,
// and whether it slides or rolls, in which case its friction is applied
// rather than solved (docs/engines.md, "Contacts").
#include <mujoco/mujoco.h>

#include <algorithm>
#include <cmath>

#include "contact_rules.h"
#include "mujoco_world.h"

namespace simpartner::sim {
namespace {

// MuJoCo's cone needs a positive torsional friction where ODE has none,
// and positive coefficients where one of ours is 0.
constexpr double kTorsionalFriction = 1e-9;  // [m]
constexpr double kLeastFriction = 1e-9;

Eigen::Vector3d Vec(const mjtNum* v) { return Eigen::Vector3d(v[0], v[1], v[2]); }

}  // namespace

void MujocoWorld::StepLaw(double erp, double cfm, double inverse_inertia, double solref[2],
                          double solimp[5]) const {
  // ODE: (A + CFM / h) f = -v / h - ERP r / h^2 - a0 for a row of inverse
  // inertia A. MuJoCo: (A + R) f = aref - a0 with R = (1 - d) / d A and, in
  // its direct form, aref = -(b / d) v - (k / d) r. So d = A / (A + CFM /
  // h), b = d / h, k = d ERP / h^2, with MuJoCo's own estimate of A.
  const double h = params_.stepsize;
  const double a = std::max(inverse_inertia, 1e-12);
  const double d = std::clamp(a / (a + cfm / h), 1e-4, 0.9999);
  solref[0] = -d * erp / (h * h);
  solref[1] = -d / h;
  solimp[0] = solimp[1] = d;
  solimp[2] = 0.001;
  solimp[3] = 0.5;
  solimp[4] = 2.0;
}

Eigen::Vector3d MujocoWorld::PointVelocity(int mj_body, const Eigen::Vector3d& point) const {
  if (mj_body <= 0) return Eigen::Vector3d::Zero();
  const mjtNum* cvel = d_->cvel + 6 * mj_body;  // [angular, linear] at the root's subtree com
  const Eigen::Vector3d at = Vec(d_->subtree_com + 3 * m_->body_rootid[mj_body]);
  return Vec(cvel + 3) + Vec(cvel).cross(point - at);
}

std::optional<Eigen::Vector3d> MujocoWorld::WorldSpinAxis(int geom) const {
  const GeomInfo& info = geoms_[static_cast<size_t>(geom)];
  if (!info.has_spin_axis) return std::nullopt;
  Eigen::Matrix3d r;
  for (int row = 0; row < 3; ++row)
    for (int col = 0; col < 3; ++col) r(row, col) = d_->geom_xmat[9 * geom + 3 * row + col];
  return Eigen::Vector3d(r * info.spin_axis);
}

void MujocoWorld::SetUpContacts() {
  // Points per pair of geoms: a physical stiffness is shared among them,
  // as the ODE side shares it.
  std::vector<int>& points = scratch_.points;
  points.assign(static_cast<size_t>(d_->ncon), 1);
  for (int i = 0; i < d_->ncon; ++i)
    for (int k = 0; k < d_->ncon; ++k)
      if (k != i && d_->contact[k].geom1 == d_->contact[i].geom1 &&
          d_->contact[k].geom2 == d_->contact[i].geom2)
        ++points[static_cast<size_t>(i)];
  contact_surface_.assign(static_cast<size_t>(d_->ncon), model::SurfaceProperties{});
  contact_rolling_.assign(static_cast<size_t>(d_->ncon), Eigen::Vector3d::Zero());
  applied_.clear();
  for (int i = 0; i < d_->ncon; ++i) {
    mjContact& contact = d_->contact[i];
    model::SurfaceProperties combined = model::CombineSurfaces(
        geoms_[static_cast<size_t>(contact.geom1)].surface,
        geoms_[static_cast<size_t>(contact.geom2)].surface);
    // mu2 is read across a rolling direction only (as on ODE): a contact
    // without one is isotropic, mu against the slip (Coulomb's cone, which
    // needs no frame of its own when mu2 = mu).
    const std::optional<Eigen::Vector3d> rolling = RollingDirection(
        combined, Vec(contact.frame), WorldSpinAxis(contact.geom1), WorldSpinAxis(contact.geom2));
    if (rolling) contact_rolling_[static_cast<size_t>(i)] = *rolling;
    const bool rolls = rolling && combined.mu2 != combined.mu;
    if (!rolls) combined.mu2 = combined.mu;
    contact_surface_[static_cast<size_t>(i)] = combined;
    SetUpMaterial(combined, points[static_cast<size_t>(i)], &contact);
    if (contact.dim > 1) SetUpFriction(i, combined, rolls ? &*rolling : nullptr);
  }
}

void MujocoWorld::SetUpMaterial(const model::SurfaceProperties& combined, int points,
                                mjContact* contact) const {
  const double cfm = combined.HasStiffness() ? combined.soft_cfm * points : combined.soft_cfm;
  const double inverse_inertia = m_->body_invweight0[2 * m_->geom_bodyid[contact->geom1]] +
                                 m_->body_invweight0[2 * m_->geom_bodyid[contact->geom2]];
  StepLaw(combined.soft_erp, cfm, inverse_inertia, contact->solref, contact->solimp);
  // MuJoCo's cone divides by each coefficient: none may be 0. A contact
  // without friction has no friction rows.
  contact->friction[0] = std::max(combined.mu, kLeastFriction);
  contact->friction[1] = std::max(combined.mu2, kLeastFriction);
  contact->friction[2] = kTorsionalFriction;
  contact->friction[3] = contact->friction[4] = std::max(combined.rolling_friction, kLeastFriction);
  contact->dim = combined.mu == 0 && combined.mu2 == 0 ? 1 : combined.rolling_friction > 0 ? 6 : 3;
}

void MujocoWorld::SetUpFriction(int index, const model::SurfaceProperties& combined,
                                const Eigen::Vector3d* rolling) {
  mjContact& contact = d_->contact[index];
  if (rolling != nullptr) {
    const Eigen::Vector3d normal = Vec(contact.frame);
    const Eigen::Vector3d across = normal.cross(*rolling);
    for (int k = 0; k < 3; ++k) {
      contact.frame[3 + k] = (*rolling)[k];
      contact.frame[6 + k] = across[k];
    }
  }
  AppliedFriction applied;
  applied.contact = index;
  const Slide slide = combined.mu2 == combined.mu ? Slides(contact, combined, &applied)
                                                  : SlidesBox(&contact, combined, &applied);
  const bool slides = slide == Slide::kBothWays;
  const bool rolls = combined.rolling_friction > 0 && Rolls(contact, combined, slides, &applied);
  // Rows MuJoCo solves: none for what is applied (ApplyFriction).
  if (slides) contact.dim = 1;
  else if (rolls) contact.dim = 3;
  if (slide != Slide::kHolds || rolls) applied_.push_back(applied);
}

MujocoWorld::Slide MujocoWorld::Slides(const mjContact& contact,
                                       const model::SurfaceProperties& surface,
                                       AppliedFriction* sliding) const {
  // The point's relative motion: Jacobian rows of geom1's body less
  // geom2's at the contact.
  const int nv = m_->nv;
  const Jacobian& jac = RelativeJacobian(contact);
  const Eigen::Map<const Eigen::VectorXd> qvel(d_->qvel, nv), qacc(d_->qacc_smooth, nv);
  const Eigen::Vector3d normal = Vec(contact.frame);
  // The slip the step would end with if friction did nothing: the smooth
  // forces' (motors, gravity, applied) acceleration added to today's.
  Eigen::Vector3d slip = jac * qvel + params_.stepsize * (jac * qacc);
  slip -= slip.dot(normal) * normal;
  const double speed = slip.norm();
  if (speed <= kSlipDirectionSpeed) return Slide::kHolds;
  // Coulomb's force: mu per newton of load against the slip, on geom1.
  sliding->force_per_newton = -surface.mu * slip / speed;
  // It slides when that force cannot stop that slip within the step
  // (Brake): what it takes off is the force over the point's effective
  // mass along the slip (with the holding servos' armature: a servo-held
  // wheel resists a change of its spin).
  const double brake = Brake(contact, surface.mu, InverseInertia(jac, slip / speed));
  return speed > brake ? Slide::kBothWays : Slide::kHolds;
}

MujocoWorld::Slide MujocoWorld::SlidesBox(mjContact* contact,
                                          const model::SurfaceProperties& surface,
                                          AppliedFriction* sliding) const {
  // ODE's anisotropic friction (docs/contacts.md) bounds each direction on
  // its own: mu N along the first (frame row 1), mu2 N across (row 2).
  // Each direction slides when its bound at the last load cannot stop its
  // slip within the step, and is then pushed back with the bound; the
  // other holds as a friction row of its own coefficient, the sliding
  // one's row given a negligible one (MuJoCo's cone then leaves it free).
  const int nv = m_->nv;
  const Jacobian& jac = RelativeJacobian(*contact);
  const Eigen::Map<const Eigen::VectorXd> qvel(d_->qvel, nv), qacc(d_->qacc_smooth, nv);
  const Eigen::Vector3d slip = jac * qvel + params_.stepsize * (jac * qacc);
  const double mu[2] = {surface.mu, surface.mu2};
  bool slides[2] = {false, false};
  Eigen::Vector3d direction[2] = {Vec(contact->frame + 3), Vec(contact->frame + 6)};
  for (int k = 0; k < 2; ++k) {
    const double v = slip.dot(direction[k]);
    if (std::abs(v) <= kSlipDirectionSpeed) continue;
    slides[k] = std::abs(v) > Brake(*contact, mu[k], InverseInertia(jac, direction[k]));
    if (slides[k]) sliding->force_per_newton -= std::copysign(mu[k], v) * direction[k];
  }
  if (slides[0] && slides[1]) return Slide::kBothWays;
  if (!slides[0] && !slides[1]) return Slide::kHolds;
  // The holding direction first, with its coefficient; the sliding one
  // second, free.
  const int holds = slides[0] ? 1 : 0;
  for (int k = 0; k < 3; ++k) {
    contact->frame[3 + k] = direction[holds][k];
    contact->frame[6 + k] = direction[1 - holds][k];
  }
  // Swapping the tangents turns the frame over: the normal stays, so the
  // second tangent must change sign for a right-handed frame.
  if (holds == 1)
    for (int k = 0; k < 3; ++k) contact->frame[6 + k] = -contact->frame[6 + k];
  contact->friction[0] = std::max(mu[holds], kLeastFriction);
  contact->friction[1] = kLeastFriction;
  return Slide::kOneWay;
}

bool MujocoWorld::Rolls(const mjContact& contact, const model::SurfaceProperties& surface,
                        bool slides, AppliedFriction* applied) const {
  // ODE's rolling resistance holds the rolling when rho N can stop it
  // within the step, and resists it with rho N otherwise; asked of MuJoCo's
  // rolling rows, the second raised the normal force (a sphere rolling at
  // 10 rad/s hopped). As for sliding: the turn the step would end with
  // without resistance, and what rho N at the last load takes off it.
  const int nv = m_->nv;
  const Jacobian& jac = RelativeJacobian(contact, /*rotation=*/true);
  const Eigen::Map<const Eigen::VectorXd> qvel(d_->qvel, nv), qacc(d_->qacc_smooth, nv);
  const Eigen::Vector3d normal = Vec(contact.frame);
  Eigen::Vector3d turn = jac * qvel + params_.stepsize * (jac * qacc);
  turn -= turn.dot(normal) * normal;
  const double speed = turn.norm();
  if (speed <= kSlipDirectionSpeed) return false;
  const Eigen::Vector3d axis = turn / speed;
  const double inverse_inertia = InverseInertia(jac, axis);
  applied->torque_per_newton = -surface.rolling_friction * axis;
  // Without friction rows the rolling rows go too: resist at most what
  // stops it.
  applied->stop_torque = speed / (inverse_inertia * params_.stepsize);
  const std::optional<double> load = LastLoad(contact);
  return slides || !load ||
         speed > surface.rolling_friction * *load * inverse_inertia * params_.stepsize;
}

const MujocoWorld::Jacobian& MujocoWorld::RelativeJacobian(const mjContact& contact,
                                                           bool rotation) const {
  Jacobian& jac1 = scratch_.jac1;
  Jacobian& jac2 = scratch_.jac2;
  jac1.resize(3, m_->nv);
  jac2.resize(3, m_->nv);
  const int body1 = m_->geom_bodyid[contact.geom1], body2 = m_->geom_bodyid[contact.geom2];
  if (body1 > 0)
    mj_jac(m_, d_, rotation ? nullptr : jac1.data(), rotation ? jac1.data() : nullptr, contact.pos,
           body1);
  else
    jac1.setZero();
  if (body2 > 0)
    mj_jac(m_, d_, rotation ? nullptr : jac2.data(), rotation ? jac2.data() : nullptr, contact.pos,
           body2);
  else
    jac2.setZero();
  scratch_.jac.noalias() = jac1 - jac2;
  return scratch_.jac;
}

double MujocoWorld::InverseInertia(const Jacobian& jac, const Eigen::Vector3d& direction) const {
  scratch_.row.noalias() = jac.transpose() * direction;
  scratch_.solved.resize(m_->nv);
  mj_solveM(m_, d_, scratch_.solved.data(), scratch_.row.data(), 1);
  return scratch_.row.dot(scratch_.solved);
}

double MujocoWorld::Brake(const mjContact& contact, double mu, double inverse_inertia) const {
  // What mu N takes off a slip in one step, N the load of the point at the
  // last step; for a new point, the ODE side's test: mu g h.
  const std::optional<double> load = LastLoad(contact);
  if (!load) return mu * gravity_ * params_.stepsize;
  return mu * *load * inverse_inertia * params_.stepsize;
}

std::optional<double> MujocoWorld::LastLoad(const mjContact& contact) const {
  // The nearest point of the same pair at the last step (a few per pair).
  std::optional<double> load;
  double nearest = INFINITY;
  const Eigen::Vector3d at = Vec(contact.pos);
  for (const LastLoad_& last : last_loads_) {
    if (last.geom1 != contact.geom1 || last.geom2 != contact.geom2) continue;
    const double distance = (last.position - at).squaredNorm();
    if (distance < nearest) {
      nearest = distance;
      load = last.load;
    }
  }
  return load;
}

void MujocoWorld::ApplyFriction() {
  // ODE's friction of a sliding contact is mu N against the slip, N what
  // the normal needs. MuJoCo's contacts are not complementary: a friction
  // row asking for more than its cone gives raises the normal force
  // instead (a box sliding at 2 m/s took 38 times its weight and hopped).
  // So a sliding contact goes into MuJoCo's solve without friction rows
  // (and a rolling one without rolling rows); a first solve gives its load
  // N, and mu N against the slip and rho N against the rolling are applied
  // to both bodies before the solve that counts.
  if (applied_.empty()) return;
  mj_fwdConstraint(m_, d_);
  mju_zero(d_->qfrc_applied, m_->nv);
  for (AppliedFriction& a : applied_) {
    const mjContact& contact = d_->contact[a.contact];
    const double load = std::max(d_->efc_force[contact.efc_address], 0.0);
    a.force = load * a.force_per_newton;  // on geom1
    a.torque = load * a.torque_per_newton;
    if (a.torque.norm() > a.stop_torque) a.torque *= a.stop_torque / a.torque.norm();
    mjtNum point[3] = {contact.pos[0], contact.pos[1], contact.pos[2]};
    for (int side = 0; side < 2; ++side) {
      const int body = m_->geom_bodyid[side == 0 ? contact.geom1 : contact.geom2];
      if (body == 0) continue;
      const double sign = side == 0 ? 1.0 : -1.0;
      const mjtNum force[3] = {sign * a.force.x(), sign * a.force.y(), sign * a.force.z()};
      const mjtNum torque[3] = {sign * a.torque.x(), sign * a.torque.y(), sign * a.torque.z()};
      mj_applyFT(m_, d_, force, torque, point, body, d_->qfrc_applied);
    }
  }
  mj_fwdAcceleration(m_, d_);
}

void MujocoWorld::SetUpNormals() {
  // ODE's contact asks the normal to separate, after the step, at the
  // correcting velocity ERP depth / h, depth beyond the surface layer and
  // the velocity at most contactMaxCorrectingVel; with bounce, a contact
  // closing faster than the bounce velocity leaves at bounce times its
  // closing speed if that is more. The normal row's reference
  // acceleration asks the same: (target - v) / h, v its velocity now.
  const double h = params_.stepsize;
  for (int i = 0; i < d_->ncon; ++i) {
    const model::SurfaceProperties& surface = contact_surface_[static_cast<size_t>(i)];
    const int row = d_->contact[i].efc_address;
    if (row < 0) continue;
    const double v = d_->efc_vel[row];
    const double depth =
        std::max(0.0, d_->efc_margin[row] - d_->efc_pos[row] - params_.contactSurfaceLayer);
    double target = std::min(surface.soft_erp * depth / h, params_.contactMaxCorrectingVel);
    if (surface.bounce > 0.0 && v < -surface.bounce_velocity)
      target = std::max(target, -surface.bounce * v);
    d_->efc_aref[row] = (target - v) / h;
  }
}

}  // namespace simpartner::sim
