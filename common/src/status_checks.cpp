#include "message_rules.h"
#include "simpartner/message_checks.h"

namespace simpartner {

MessageCheck CheckStatus(const status_t& status) {
  const message_rules::MessageRules rules("status_t");
  if (auto bad = rules.Finite("sim_time", status.sim_time)) return bad;
  return rules.Finite("real_time_factor", status.real_time_factor);
}

}  // namespace simpartner
