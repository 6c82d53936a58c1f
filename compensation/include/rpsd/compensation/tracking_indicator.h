// Tracking indicator (Mercan & Ricles 2007): the areas of the hysteresis loop of measured
// against commanded displacement, by the trapezoidal rule,
//   A+  = A  + 1/2 (d_c+ + d_c)(d_m+ - d_m)
//   TA+ = TA + 1/2 (d_m+ + d_m)(d_c+ - d_c)
//   TI  = 1/2 (A - TA).
// TI grows when the measured displacement lags the command and falls when it leads; for
// d_c = X sin(w t), d_m = X sin(w (t - tau)) it grows by pi X^2 sin(w tau) per cycle (with
// sampling, exactly 1/2 X^2 sin(w tau) sin(w dt) per step).
#pragma once

#include <span>

namespace rpsd::compensation {

// The online indicator: O(1) per sample, no buffers.
class TrackingIndicator {
 public:
  // Forgets everything; the next update() only records its sample. Real-time safe.
  void reset() noexcept;
  // Starts from a known previous sample (areas zero). Real-time safe.
  void reset(double command_m, double measured_m) noexcept;
  // Adds one sample of commanded (or target) and measured displacement. Real-time safe.
  // Inline: the exchange calls it for every channel on every step.
  void update(double command_m, double measured_m) noexcept {
    if (has_previous_) {
      area_a_m2_ += 0.5 * (command_m + previous_command_m_) * (measured_m - previous_measured_m_);
      area_ta_m2_ += 0.5 * (measured_m + previous_measured_m_) * (command_m - previous_command_m_);
    }
    has_previous_ = true;
    previous_command_m_ = command_m;
    previous_measured_m_ = measured_m;
  }

  double area_a_m2() const noexcept { return area_a_m2_; }
  double area_ta_m2() const noexcept { return area_ta_m2_; }
  // TI = 1/2 (A - TA), m^2. Real-time safe.
  double value_m2() const noexcept { return 0.5 * (area_a_m2_ - area_ta_m2_); }

 private:
  bool has_previous_ = false;
  double previous_command_m_ = 0.0;
  double previous_measured_m_ = 0.0;
  double area_a_m2_ = 0.0;
  double area_ta_m2_ = 0.0;
};

// TI after the whole record. Throws std::invalid_argument unless the spans have equal
// lengths. Not real-time safe (it may throw).
double tracking_indicator(std::span<const double> command_m, std::span<const double> measured_m);

// TI after each sample into history_m2 (same length as the inputs; TI[0] = 0). Throws
// std::invalid_argument on unequal lengths. Not real-time safe (it may throw).
void tracking_indicator_history(std::span<const double> command_m, std::span<const double> measured_m,
                                std::span<double> history_m2);

}  // namespace rpsd::compensation
