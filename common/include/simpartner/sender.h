// Who sends a bus message and when: "program@host:pid", the form every
// request, command and lock-step mark carries (command_t.sender) so that
// a reply finds its asker and a log says who did what, and the wall clock
// of its utime field.
#pragma once

#include <cstdint>
#include <string>

namespace simpartner {

// This machine's host name, "unknown" when the system will not say.
std::string HostName();

// "program@host:pid" for this process.
std::string SenderName(const std::string& program);

// [us] since the Unix epoch, the wall clock: a message's utime.
int64_t WallMicros();

}  // namespace simpartner
