// A MariaDB data directory made once per build tree, which each test's
// private server copies (scripts/mariadb start --seed): making one with
// mariadb-install-db takes seconds, copying it a fraction of one, and
// about seventy tests start a server.
#pragma once

#include <string>

namespace simpartner::test_support {

// The seed directory (<build>/tests/mariadb-seed, holding data/): made by
// scripts/mariadb start and stop the first time, again when the script
// has changed since. Safe to call from tests running side by side (a file
// lock). Throws std::runtime_error with the script's output if it fails.
std::string MariaDbSeed();

}  // namespace simpartner::test_support
