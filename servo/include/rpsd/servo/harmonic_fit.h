// Least-squares fit of a sinusoid of known phase history to a sampled signal: the way a
// lab measures amplitude ratio and phase lag from a sine or sine-sweep test.
#pragma once

#include <span>

namespace rpsd::servo {

// y(t_i) ~ a sin(phi_i) + b cos(phi_i) + offset; returns amplitude sqrt(a^2 + b^2) and the
// phase atan2(b, a) (radians, positive = y leads the reference sin(phi)). Not real-time safe.
struct HarmonicFit {
  double amplitude = 0.0;
  double phase_rad = 0.0;
};

HarmonicFit fit_harmonic(std::span<const double> reference_phase_rad, std::span<const double> signal);

}  // namespace rpsd::servo
