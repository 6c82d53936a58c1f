// exp, log and sin/cos(2 pi u) from IEEE-754 +, -, *, / only, so that seeded synthetic
// records are bit-identical on every machine and C library (std::exp and friends may differ
// in the last bit between libm versions and between the FMA and non-FMA code paths glibc
// picks at run time). Accurate to a few units in the last place; not for general use.
#pragma once

namespace rpsd::ground_motion::deterministic {

// e^x; +inf above 709.78, 0 below -745.13. Real-time safe.
double exp(double x) noexcept;

// Natural logarithm for finite x > 0 (returns -inf for 0, NaN for negative). Real-time safe.
double log(double x) noexcept;

// sin(2 pi u) and cos(2 pi u) for u in [0, 1]. Real-time safe.
void sincos_2pi(double u, double& sine, double& cosine) noexcept;

}  // namespace rpsd::ground_motion::deterministic
