#include "message_rules.h"
#include "simpartner/message_checks.h"

namespace simpartner {

using message_rules::kNameBytes;
using message_rules::kTextBytes;

MessageCheck CheckCommand(const command_t& command) {
  const message_rules::MessageRules rules("command_t");
  if (auto bad = rules.Text("sender", command.sender, kNameBytes)) return bad;
  if (auto bad = rules.Text("robot", command.robot, kNameBytes)) return bad;
  if (auto bad = rules.Text("target", command.target, kNameBytes)) return bad;
  return rules.Text("text", command.text, kTextBytes);
}

MessageCheck CheckCommandReply(const command_reply_t& reply) {
  const message_rules::MessageRules rules("command_reply_t");
  if (auto bad = rules.Text("sender", reply.sender, kNameBytes)) return bad;
  if (auto bad = rules.Text("target", reply.target, kNameBytes)) return bad;
  if (auto bad = rules.Text("reason", reply.reason, kTextBytes)) return bad;
  return rules.Text("previous_text", reply.previous_text, kTextBytes);
}

}  // namespace simpartner
