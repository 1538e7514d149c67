// UnreadUdpBytes: what the kernel holds in this process's UDP sockets, read
// from /proc; the datagrams are sent here, to a socket of the test's own.
#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <string>

#include "simpartner/socket_backlog.h"

namespace simpartner {
namespace {

TEST(SocketBacklog, CountsWhatWaitsInOwnSocketsUntilItIsRead) {
  const int receiver = ::socket(AF_INET, SOCK_DGRAM, 0);
  const int sender = ::socket(AF_INET, SOCK_DGRAM, 0);
  ASSERT_GE(receiver, 0);
  ASSERT_GE(sender, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ASSERT_EQ(::bind(receiver, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
  socklen_t length = sizeof address;
  ASSERT_EQ(::getsockname(receiver, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const std::optional<size_t> before = UnreadUdpBytes();
  ASSERT_TRUE(before);
  const std::string datagram(1000, 'x');
  for (int k = 0; k < 3; ++k)
    ASSERT_EQ(::sendto(sender, datagram.data(), datagram.size(), 0,
                       reinterpret_cast<sockaddr*>(&address), sizeof address),
              static_cast<ssize_t>(datagram.size()));
  // The kernel counts each datagram's buffer, which is more than its bytes.
  const std::optional<size_t> waiting = UnreadUdpBytes();
  ASSERT_TRUE(waiting);
  EXPECT_GE(*waiting, *before + 3000);
  char buffer[2000];
  for (int k = 0; k < 3; ++k) ASSERT_EQ(::recv(receiver, buffer, sizeof buffer, 0), 1000);
  EXPECT_EQ(UnreadUdpBytes().value_or(1), *before);
  ::close(sender);
  ::close(receiver);
}

}  // namespace
}  // namespace simpartner
