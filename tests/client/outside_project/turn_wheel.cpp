// Turns one wheel: turn_wheel LCM_URL MOTOR RAD_PER_S. Prints the reply.
#include <cstdio>
#include <string>

#include "simpartner/client/client.h"

int main(int argc, char** argv) {
  if (argc != 4) {
    std::fprintf(stderr, "usage: turn_wheel LCM_URL MOTOR RAD_PER_S\n");
    return 2;
  }
  using namespace simpartner::client;
  ClientOptions options;
  options.url = argv[1];
  options.program = "turn_wheel";
  try {
    Client client(options);
    const command_reply_t reply =
        client.Command(SetVelocity(client.Find(argv[2]), {std::stod(argv[3])}));
    std::printf("%s accepted at step %lld\n", reply.target.c_str(),
                static_cast<long long>(reply.applied_at_step));
    return 0;
  } catch (const ClientError& e) {
    std::fprintf(stderr, "turn_wheel: %s\n", e.what());
    return 1;
  }
}
