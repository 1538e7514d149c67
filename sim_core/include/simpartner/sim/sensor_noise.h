// Counter-based sensor noise: each number is a hash of (seed, sensor,
// step, component), so a reading depends on nothing but its own step -
// not on how many readings were taken before, on-request reads, the speed
// or the wall clock. The same seed gives the same readings bit for bit.
#pragma once

#include <cmath>
#include <cstdint>

namespace simpartner::sim {

class SensorNoise {
 public:
  explicit SensorNoise(uint64_t seed) : seed_(seed) {}

  // Uniform in [0, 1).
  double Uniform(int sensor, int64_t step, int component) const {
    return static_cast<double>(Key(sensor, step, component) >> 11) * 0x1.0p-53;
  }
  // Standard normal (Box-Muller on two uniforms of the key).
  double Gaussian(int sensor, int64_t step, int component) const {
    const uint64_t key = Key(sensor, step, component);
    const double u1 = (static_cast<double>(key >> 11) + 0.5) * 0x1.0p-53;  // (0, 1)
    const double u2 = static_cast<double>(Mix(key) >> 11) * 0x1.0p-53;
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
  }

 private:
  // SplitMix64's finaliser: every input bit reaches every output bit.
  static uint64_t Mix(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  uint64_t Key(int sensor, int64_t step, int component) const {
    uint64_t h = Mix(seed_);
    h = Mix(h ^ static_cast<uint64_t>(sensor));
    h = Mix(h ^ static_cast<uint64_t>(step));
    return Mix(h ^ static_cast<uint64_t>(component));
  }

  uint64_t seed_;
};

}  // namespace simpartner::sim
