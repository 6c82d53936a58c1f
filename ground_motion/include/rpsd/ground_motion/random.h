// Seeded, portable random numbers for synthetic ground motions: SplitMix64 (seeding),
// xoshiro256** (Blackman & Vigna, the stream), Box-Muller on deterministic exp/log/sin/cos.
// The same seed gives the same bits on every IEEE-754 machine, unlike
// std::normal_distribution whose algorithm is left to the library.
#pragma once

#include <array>
#include <cstdint>

namespace rpsd::ground_motion {

// SplitMix64 (Steele, Lea, Flood 2014). Real-time safe.
class SplitMix64 {
 public:
  explicit SplitMix64(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next() noexcept;

 private:
  std::uint64_t state_;
};

// xoshiro256** 1.0; seeded from four SplitMix64 outputs as its authors recommend.
// Real-time safe.
class Xoshiro256StarStar {
 public:
  explicit Xoshiro256StarStar(std::uint64_t seed);
  // Direct state (for the published test vectors); must not be all zero.
  explicit Xoshiro256StarStar(const std::array<std::uint64_t, 4>& state) : s_(state) {}
  std::uint64_t next() noexcept;
  // Uniform in [0, 1): the top 53 bits times 2^-53.
  double uniform() noexcept;

 private:
  std::array<std::uint64_t, 4> s_;
};

// Standard normal numbers by the Box-Muller transform, both outputs of each pair used.
// Real-time safe.
class StandardNormal {
 public:
  explicit StandardNormal(std::uint64_t seed) : uniform_(seed) {}
  double next() noexcept;

 private:
  Xoshiro256StarStar uniform_;
  double spare_ = 0.0;
  bool has_spare_ = false;
};

}  // namespace rpsd::ground_motion
