#include "rpsd/servo/simulated_frequency_response.h"

#include <cmath>
#include <numbers>
#include <vector>

#include "rpsd/servo/harmonic_fit.h"

namespace rpsd::servo {

std::complex<double> simulated_frequency_response(Plant& plant, const SineTest& test) {
  const double omega = 2.0 * std::numbers::pi * test.frequency_hz;
  const double dt = 1.0 / test.control_rate_hz;
  const auto settling_steps = static_cast<long>(std::ceil(test.settling_time_s / dt));
  const auto fitted_steps = static_cast<long>(std::llround(test.fitted_cycles / test.frequency_hz / dt));
  std::vector<double> phase, response;
  phase.reserve(fitted_steps);
  response.reserve(fitted_steps);

  plant.reset(0.0);
  double command = 0.0;
  for (long step = 1; step <= settling_steps + fitted_steps; ++step) {
    const double next_command = test.amplitude_m * std::sin(omega * step * dt);
    plant.advance(command, next_command, dt);
    command = next_command;
    if (step > settling_steps) {
      phase.push_back(omega * step * dt);
      response.push_back(plant.measure().displacement_m);
    }
  }
  const HarmonicFit fit = fit_harmonic(phase, response);
  return std::polar(fit.amplitude / test.amplitude_m, fit.phase_rad);
}

}  // namespace rpsd::servo
