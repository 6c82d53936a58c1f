// The "none" compensator: the command is the target.
#pragma once

#include <string_view>

#include "rpsd/config/source.h"

#include "rpsd/compensation/command_compensator.h"

namespace rpsd::compensation {

class PassThroughCompensator;

// No parameters; present so that "none" is a typed configuration like the others.

struct PassThroughParameters {
  static constexpr std::string_view kName = "none";
  static constexpr std::string_view kSummary = "no compensation: the command is the target";
  using Compensator = PassThroughCompensator;
  static PassThroughParameters read(config::Source&) { return {}; }
};

class PassThroughCompensator final : public CommandCompensator {
 public:
  PassThroughCompensator() = default;
  explicit PassThroughCompensator(const PassThroughParameters&) {}

  // Throws std::invalid_argument unless dt_s is positive and finite. Not real-time safe.
  void configure(double dt_s) override;
  void reset(double) noexcept override {}
  double command(double target_m) noexcept override { return target_m; }
  void observe(double, double) noexcept override {}
  double compensated_delay_s() const noexcept override { return 0.0; }
  std::string_view name() const noexcept override { return PassThroughParameters::kName; }
};

}  // namespace rpsd::compensation
