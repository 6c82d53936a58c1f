// Inverse compensation (Chen & Ricles 2009). The actuator is modelled as closing a fraction
// 1/alpha of the remaining error every control step, G_a(z) = 1 / (alpha z - (alpha - 1)),
// and the compensator is its inverse up to one step, G_c(z) = (alpha z - (alpha - 1)) / z:
//   x_c[k] = alpha x_d[k] - (alpha - 1) x_d[k-1],
// so that G_c G_a = 1/z. The one step 1/z is the step between sending a command and measuring
// its effect at the end of that step; in this module's pairing (command of step n with the
// displacement measured at the end of step n) it is no lag at all, and G_a's lag there is
// alpha - 1 steps. Hence alpha = 1 + delay_s / dt_s, and the law is a linear extrapolation by
// delay_s (the same as polynomial extrapolation of order 1).
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation {

class InverseCompensator;

struct InverseCompensationParameters {
  static constexpr std::string_view kName = "inverse";
  static constexpr std::string_view kSummary = "inverts a first-order lag of the given delay (Chen and Ricles)";
  using Compensator = InverseCompensator;
  static InverseCompensationParameters read(config::Source& section);

  double delay_s = 0.0;  // lag to compensate; alpha = 1 + delay_s / dt_s

  // Throws std::invalid_argument unless delay_s >= 0 and finite. Not real-time safe.
  void validate() const;
};

class InverseCompensator final : public CommandCompensator {
 public:
  explicit InverseCompensator(const InverseCompensationParameters& parameters);

  void configure(double dt_s) override;
  void reset(double initial_displacement_m) noexcept override { previous_target_m_ = initial_displacement_m; }
  double command(double target_m) noexcept override;
  void observe(double, double) noexcept override {}
  double compensated_delay_s() const noexcept override { return parameters_.delay_s; }
  std::string_view name() const noexcept override { return InverseCompensationParameters::kName; }

  // Chen & Ricles' alpha = 1 + delay_s / dt_s.
  double alpha() const { return alpha_; }

 private:
  InverseCompensationParameters parameters_;
  double alpha_ = 1.0;
  double previous_target_m_ = 0.0;
};

}  // namespace rpsd::compensation
