#pragma once
// Rayleigh damping C = a0 M + a1 K, whose modal damping ratio is ζ(ω) = a0/(2ω) + a1 ω/2.

namespace rpsd::substructure {

struct RayleighCoefficients {
  double a0_per_s = 0.0;  // mass-proportional coefficient [1/s]
  double a1_s = 0.0;      // stiffness-proportional coefficient [s]
};

// ζ(ω) = a0/(2ω) + a1 ω/2. Real-time safe.
[[nodiscard]] double rayleigh_damping_ratio(const RayleighCoefficients& c, double omega_rad_s) noexcept;

// The coefficients that give ratio zeta_a at omega_a and zeta_b at omega_b:
//   a0 = 2 ωa ωb (ζa ωb − ζb ωa) / (ωb² − ωa²),  a1 = 2 (ζb ωb − ζa ωa) / (ωb² − ωa²).
// Throws std::invalid_argument for non-positive or equal frequencies, negative ratios, or
// ratios that would need a negative coefficient (negative damping in some frequency range).
// Not real-time safe (throws).
[[nodiscard]] RayleighCoefficients rayleigh_from_frequencies(double omega_a_rad_s, double omega_b_rad_s, double zeta_a,
                                                             double zeta_b);

}  // namespace rpsd::substructure
