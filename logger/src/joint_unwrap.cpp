#include "joint_unwrap.h"

#include <cppconn/exception.h>

#include <memory>

namespace simpartner::logger {
namespace {

constexpr double kPi = 3.14159265358979323846;

}  // namespace

int RotationalAxes(const std::string& type) {
  if (type == "HINGE") return 1;
  if (type == "UNIVERSAL" || type == "HINGE2") return 2;
  return 0;
}

std::map<std::string, int> JointRotationalAxes(DbConnection* db, uint32_t simulation) {
  std::map<std::string, int> axes;
  std::unique_ptr<sql::ResultSet> r =
      db->Query("SELECT name, type FROM `Joint` WHERE simulationID = " + std::to_string(simulation),
                "SELECT type FROM `Joint`");
  try {
    while (r->next()) axes[r->getString(1)] = RotationalAxes(r->getString(2));
  } catch (const sql::SQLException&) {
    db->Rethrow("read the joint types");
  }
  return axes;
}

void AngleUnwrapper::Unwrap(double* angles, int axes) {
  for (int k = 0; k < axes; ++k) {
    double& angle = angles[k];
    if (seen_) {
      const double jump = angle - previous_[k];
      if (jump > kPi)
        offset_[k] -= 2 * kPi;
      else if (jump < -kPi)
        offset_[k] += 2 * kPi;
    }
    previous_[k] = angle;
    angle += offset_[k];
  }
  seen_ = true;
}

}  // namespace simpartner::logger
