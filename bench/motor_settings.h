// Velocity motors set before a benchmark's first step (--set), e.g. to
// measure a robot driving rather than standing.
#pragma once

#include <memory>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "simpartner/sim/simulation.h"

namespace simpartner::bench {

struct MotorSetting {
  std::string name;
  double fmax = 0.0, velocity = 0.0;
};

// NAME=FMAX,VELOCITY[;NAME=FMAX,VELOCITY...]; nullopt (said on err, with
// `program`) when a part is not of that form.
inline std::optional<std::vector<MotorSetting>> ReadMotorSettings(const std::string& text,
                                                                  const std::string& program,
                                                                  std::ostream& err) {
  std::vector<MotorSetting> out;
  std::stringstream parts(text);
  std::string part;
  while (std::getline(parts, part, ';')) {
    MotorSetting m;
    char equals = 0, comma = 0;
    std::stringstream in(part);
    if (!std::getline(in, m.name, '=') || m.name.empty() || !(in >> m.fmax >> comma >> m.velocity) ||
        comma != ',' || (in >> equals)) {
      err << program << ": --set: '" << part << "' is not NAME=FMAX,VELOCITY\n";
      return std::nullopt;
    }
    out.push_back(m);
  }
  return out;
}

// A simulation of `world` with the motors set; a motor the sim refuses is
// said on err and clears *ok.
inline std::unique_ptr<sim::Simulation> MakeSim(const model::World& world, const Parameters& params,
                                                const std::vector<MotorSetting>& motors,
                                                const std::string& program, std::ostream& err,
                                                bool* ok) {
  auto sim = std::make_unique<sim::Simulation>(world, params, 1);
  for (const MotorSetting& m : motors) {
    command_t c{};
    c.sender = program;
    c.target = m.name;
    c.action = command_t::ACTION_SET;
    c.apply_at_step = -1;
    c.values = {m.fmax, m.velocity};
    c.num_values = 2;
    if (const auto reply = sim->Submit(c); reply && !reply->accepted) {
      err << program << ": --set " << m.name << ": " << reply->reason << "\n";
      *ok = false;
    }
  }
  return sim;
}

}  // namespace simpartner::bench
