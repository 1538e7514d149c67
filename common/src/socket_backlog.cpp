#include "simpartner/socket_backlog.h"

#include <dirent.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

namespace simpartner {
namespace {

// The inodes of the sockets among this process's open files.
std::optional<std::set<unsigned long>> OwnSocketInodes() {
  DIR* dir = ::opendir("/proc/self/fd");
  if (dir == nullptr) return std::nullopt;
  std::set<unsigned long> inodes;
  while (const dirent* entry = ::readdir(dir)) {
    const std::string link = std::string("/proc/self/fd/") + entry->d_name;
    char target[64];
    const ssize_t n = ::readlink(link.c_str(), target, sizeof target - 1);
    if (n <= 0) continue;
    target[n] = '\0';
    unsigned long inode = 0;
    if (std::sscanf(target, "socket:[%lu]", &inode) == 1) inodes.insert(inode);
  }
  ::closedir(dir);
  return inodes;
}

// Adds to *bytes the rx_queue of each socket of table (/proc/net/udp's
// format) whose inode is in inodes; false when the table cannot be read.
bool AddBacklog(const char* table, const std::set<unsigned long>& inodes, size_t* bytes) {
  std::ifstream in(table);
  if (!in) return false;
  std::string line;
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    // sl local rem st tx_queue:rx_queue tr:when retrnsmt uid timeout inode
    std::istringstream fields(line);
    std::string sl, local, remote, state, queues, timer, retransmits, uid, timeout;
    unsigned long inode = 0;
    if (!(fields >> sl >> local >> remote >> state >> queues >> timer >> retransmits >> uid >>
          timeout >> inode))
      continue;
    const size_t colon = queues.find(':');
    if (inodes.count(inode) == 0 || colon == std::string::npos) continue;
    *bytes += std::stoul(queues.substr(colon + 1), nullptr, 16);
  }
  return true;
}

}  // namespace

std::optional<size_t> UnreadUdpBytes() {
  const std::optional<std::set<unsigned long>> inodes = OwnSocketInodes();
  if (!inodes) return std::nullopt;
  size_t bytes = 0;
  if (!AddBacklog("/proc/self/net/udp", *inodes, &bytes)) return std::nullopt;
  AddBacklog("/proc/self/net/udp6", *inodes, &bytes);  // absent without IPv6
  return bytes;
}

}  // namespace simpartner
