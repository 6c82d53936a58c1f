// The "none" compensator: the command is the target.
#pragma once

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation {

/// No parameters; present so that "none" is a typed configuration like the others.
struct PassThroughParameters {};

class PassThroughCompensator final : public CommandCompensator {
 public:
  PassThroughCompensator() = default;
  explicit PassThroughCompensator(const PassThroughParameters&) {}

  /// Throws std::invalid_argument unless dt_s is positive and finite. Not real-time safe.
  void configure(double dt_s) override;
  void reset(double) noexcept override {}
  double command(double target_m) noexcept override { return target_m; }
  void observe(double, double) noexcept override {}
  double compensated_delay_s() const noexcept override { return 0.0; }
  std::string_view name() const noexcept override { return "none"; }
};

}  // namespace rpsd::compensation
