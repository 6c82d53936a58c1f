// Steady-state frequency response of any Plant measured by simulation: a sine command at a
// given control rate, settling cycles discarded, amplitude and phase fitted over whole
// cycles. This is how the linear models are checked against the nonlinear simulation.
#pragma once

#include <complex>

#include "rpsd/servo/plant.h"

namespace rpsd::servo {

struct SineTest {
  double amplitude_m = 1e-3;
  double frequency_hz = 1.0;
  double control_rate_hz = 4096.0;  // command samples per second (linear between samples)
  double settling_time_s = 2.0;     // discarded before fitting
  int fitted_cycles = 4;
};

// Displacement response / command as a complex ratio (phase negative for a lag).
// Resets the plant to rest at zero first. Not real-time safe.
std::complex<double> simulated_frequency_response(Plant& plant, const SineTest& test);

}  // namespace rpsd::servo
