#include "rpsd/ground_motion/random.h"

#include <cmath>

#include "no_fp_contract.h"
#include "rpsd/ground_motion/deterministic_math.h"

namespace rpsd::ground_motion {
namespace {

constexpr std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

std::uint64_t SplitMix64::next() noexcept {
  std::uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

Xoshiro256StarStar::Xoshiro256StarStar(std::uint64_t seed) : s_{} {
  SplitMix64 seeder(seed);
  for (auto& word : s_) word = seeder.next();  // never all zero: SplitMix64 is a bijection
}

std::uint64_t Xoshiro256StarStar::next() noexcept {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Xoshiro256StarStar::uniform() noexcept { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double StandardNormal::next() noexcept {
  if (has_spare_) {
    has_spare_ = false;
    return spare_;
  }
  const double u1 = 1.0 - uniform_.uniform();  // (0, 1]: log(u1) is finite
  const double u2 = uniform_.uniform();
  const double radius = std::sqrt(-2.0 * deterministic::log(u1));  // sqrt is exact IEEE
  double sine = 0.0;
  double cosine = 0.0;
  deterministic::sincos_2pi(u2, sine, cosine);
  spare_ = radius * sine;
  has_spare_ = true;
  return radius * cosine;
}

}  // namespace rpsd::ground_motion
