#include <cmath>

#include "message_rules.h"
#include "simpartner/message_checks.h"
#include "simpartner/text.h"

namespace simpartner {
namespace {

using message_rules::MessageRules;
using message_rules::Triple;

// origin, up and u_axis finite; up and u_axis unit and perpendicular.
MessageCheck CheckFrame(const soil_ruts_t& m, const MessageRules& rules) {
  for (const auto& [field, v] : {std::pair<const char*, const double*>{"origin", m.origin},
                                 {"up", m.up},
                                 {"u_axis", m.u_axis}})
    if (!(std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])))
      return rules.Problem(MessageFault::kNonFinite, field, " = " + Triple(v));
  if (auto bad = rules.UnitVector("up", m.up)) return bad;
  if (auto bad = rules.UnitVector("u_axis", m.u_axis)) return bad;
  const double dot = m.up[0] * m.u_axis[0] + m.up[1] * m.u_axis[1] + m.up[2] * m.u_axis[2];
  if (std::abs(dot) > message_rules::kUnitTolerance)
    return rules.Problem(MessageFault::kOutOfRange, "u_axis",
                         " = " + Triple(m.u_axis) + " is not along the surface of up = " +
                             Triple(m.up));
  return std::nullopt;
}

}  // namespace

MessageCheck CheckSoilRuts(const soil_ruts_t& m) {
  const MessageRules rules("soil_ruts_t");
  if (m.parts < 1 || m.part < 0 || m.part >= m.parts)
    return rules.Problem(MessageFault::kOutOfRange, "part",
                         " = " + std::to_string(m.part) + " of parts = " + std::to_string(m.parts));
  if (auto bad = CheckFrame(m, rules)) return bad;
  if (!(m.cell_size >= 0.001 && m.cell_size <= 1.0))
    return rules.Problem(MessageFault::kOutOfRange, "cell_size",
                         " = " + FormatNumber(m.cell_size) + " (1 mm to 1 m)");
  if (m.ground != soil_ruts_t::GROUND_PLANE && m.ground != soil_ruts_t::GROUND_HEIGHTFIELD)
    return rules.Problem(MessageFault::kUnknownValue, "ground",
                         " = " + std::to_string(m.ground) + " (0 the plane, 1 the heightfield)");
  for (size_t i = 0; i < m.depth.size(); ++i)
    if (!(m.depth[i] > 0.0f && m.depth[i] <= kMaxRutDepth))
      return rules.Problem(MessageFault::kOutOfRange, "depth[" + std::to_string(i) + "]",
                           " = " + FormatNumber(m.depth[i]) + " (cell " + std::to_string(m.u[i]) +
                               ", " + std::to_string(m.w[i]) + "; 0 < depth <= " +
                               FormatNumber(kMaxRutDepth) + " m)");
  return std::nullopt;
}

}  // namespace simpartner
