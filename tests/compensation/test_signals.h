// Shared helpers for the compensation tests: steady-state frequency response of a
// compensator by simulation, and window-periodic multi-sine signals.
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation::testing {

// The compensator's response to e^{j theta n}, measured by running it on cos and on sin
// (it is linear with real coefficients) for `steps` samples and reading the last one.
inline std::complex<double> simulated_response(CommandCompensator& c, double theta, int steps) {
  double yc = 0.0, ys = 0.0;
  c.reset(1.0);  // cos(0) = 1: starts at rest on the first sample
  for (int n = 0; n < steps; ++n) yc = c.command(std::cos(theta * n));
  c.reset(0.0);
  for (int n = 0; n < steps; ++n) ys = c.command(std::sin(theta * n));
  return std::complex<double>(yc, ys) / std::polar(1.0, theta * (steps - 1));
}

// Records a measured figure in the test's XML output (--gtest_output=xml:FILE).
inline void record(const std::string& key, double value) {
  std::ostringstream s;
  s.precision(10);
  s << value;
  ::testing::Test::RecordProperty(key, s.str());
}

// sum_i amplitude_i sin(2 pi f_i t + phase_i).
struct MultiSine {
  std::vector<double> amplitude, frequency_hz, phase_rad;
  double operator()(double t) const {
    double x = 0.0;
    for (std::size_t i = 0; i < amplitude.size(); ++i) {
      x += amplitude[i] * std::sin(2.0 * std::numbers::pi * frequency_hz[i] * t + phase_rad[i]);
    }
    return x;
  }
};

}  // namespace rpsd::compensation::testing
