// Seeded uniform random numbers for the Monte Carlo estimators. A stream is identified by
// (seed, stream index): the path tracer gives every batch of paths its own stream, so a result
// depends on the seed and the sample count, never on how many threads drew the batches.
#pragma once

#include <cstdint>
#include <random>

namespace welkin::clouds::reference {

class RandomStream {
 public:
  RandomStream(std::uint64_t seed, std::uint64_t stream) : engine_(mix(mix(seed) + stream)) {}
  // Uniform in [0, 1) with 53 random bits (std::mt19937_64 is specified bit for bit by the
  // standard; the conversion to double is done here because uniform_real_distribution is not).
  double uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }

 private:
  // MurmurHash3's 64-bit finaliser: neighbouring (seed, stream) pairs land far apart.
  static std::uint64_t mix(std::uint64_t k) {
    k ^= k >> 33;
    k *= 0xFF51AFD7ED558CCDull;
    k ^= k >> 33;
    k *= 0xC4CEB9FE1A85EC53ull;
    return k ^ (k >> 33);
  }
  std::mt19937_64 engine_;
};

}  // namespace welkin::clouds::reference
