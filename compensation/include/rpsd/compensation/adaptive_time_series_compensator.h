// Adaptive time-series compensation (ATS; Chae, Kazemibidokhti & Ricles, EESD 42(11):1697, 2013):
// the command u_c = a0 x_t + a1 D x_t + a2 D^2 x_t, with a0..a2 identified by bounded, rate-limited
// least squares over a sliding window of the measured response, so that a delay and gain that drift
// during a test are followed. O(1) per step, plus O(W) on every skip_samples-th step.
// Derivation and sources: docs/compensation.md
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include <array>
#include <vector>

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation {

class AdaptiveTimeSeriesCompensator;

struct AdaptiveTimeSeriesParameters {
  static constexpr std::string_view kName = "adaptive_time_series";
  static constexpr std::string_view kSummary =
      "adaptive time-series compensation (Chae, Kazemibidokhti and Ricles), coefficients by least squares";
  using Compensator = AdaptiveTimeSeriesCompensator;
  static AdaptiveTimeSeriesParameters read(config::Source&) { return {}; }

  std::array<double, 3> initial_coefficients{1.0, 0.025, 0.5 * 0.025 * 0.025};  // a0, a1 s, a2 s^2
  std::array<double, 3> lower_bounds{0.7, 0.0, 0.0};
  std::array<double, 3> upper_bounds{1.3, 0.08, 0.0032};
  std::array<double, 3> max_rate_per_s{2.0, 0.05, 0.001};  // per second of test time
  double window_s = 1.0;                                   // least-squares window
  int skip_samples = 16;                                   // update every this many steps
  double trigger_threshold_m = 0.01 * 0.0254;              // 0.01 in

  // Throws std::invalid_argument with the offending value unless lower <= initial <= upper,
  // the rates are positive, window_s > 0, skip_samples >= 1 and the threshold >= 0.
  // Not real-time safe.
  void validate() const;
};

class AdaptiveTimeSeriesCompensator final : public CommandCompensator {
 public:
  explicit AdaptiveTimeSeriesCompensator(const AdaptiveTimeSeriesParameters& parameters);

  // Also requires round(window_s / dt_s) >= 8 samples. Allocates the ring buffers.
  void configure(double dt_s) override;
  void reset(double initial_displacement_m) noexcept override;
  double command(double target_m) noexcept override;
  void observe(double target_m, double measured_m) noexcept override;
  // The law's low-frequency lead a1 / a0.
  double compensated_delay_s() const noexcept override { return coefficients_[1] / coefficients_[0]; }
  std::string_view name() const noexcept override { return AdaptiveTimeSeriesParameters::kName; }

  const std::array<double, 3>& coefficients() const { return coefficients_; }
  int window_samples() const { return window_samples_; }
  // Updates that changed the coefficients, and updates skipped by the trigger threshold.
  long accepted_updates() const { return accepted_updates_; }
  long untriggered_updates() const { return untriggered_updates_; }

 private:
  void update_coefficients() noexcept;
  double measured_at(long k) const { return measured_m_[static_cast<std::size_t>(k % capacity_)]; }
  double command_at(long k) const { return command_m_[static_cast<std::size_t>(k % capacity_)]; }

  AdaptiveTimeSeriesParameters parameters_;
  double dt_s_ = 1.0;
  int window_samples_ = 0;
  long capacity_ = 1;
  std::vector<double> measured_m_;  // ring buffers, sized in configure()
  std::vector<double> command_m_;
  long observed_ = 0;  // samples pushed since reset
  long accepted_updates_ = 0;
  long untriggered_updates_ = 0;
  std::array<double, 3> coefficients_{};  // applied now
  std::array<double, 3> ramp_from_{};     // applied at the last update
  std::array<double, 3> goal_{};          // reached skip_samples steps after it
  int ramp_step_ = 0;
  double previous_target_m_ = 0.0;         // x_t[n-1]
  double before_previous_target_m_ = 0.0;  // x_t[n-2]
  double last_command_m_ = 0.0;
};

}  // namespace rpsd::compensation
