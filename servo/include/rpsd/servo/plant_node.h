// A simulated servo node: one Plant per actuator channel, advanced over one control period
// per command. Between two commands each channel's command ramps linearly from the previous
// value to the new one (first-order hold), as a ramp generator in front of the servo
// controller does: the actuator sees a continuous path and the derivative gain no steps.
#pragma once

#include <array>
#include <span>

#include "rpsd/servo/plant.h"
#include "rpsd/transport/link.h"

namespace rpsd::servo {

class PlantNode final : public transport::CommandProcessor {
 public:
  /// `plants` are not owned and must outlive the node; at most transport::kMaxChannels.
  /// Not real-time safe (throws std::invalid_argument on bad sizes or period).
  PlantNode(std::span<Plant* const> plants, double control_period_s);

  /// Resets every plant to rest at its initial displacement. Real-time safe.
  void reset(std::span<const double> displacements_m);

  /// Real-time safe.
  void process(const transport::CommandSample& command, transport::FeedbackSample& feedback) override;

 private:
  std::array<Plant*, transport::kMaxChannels> plants_{};
  std::array<double, transport::kMaxChannels> last_command_m_{};
  int channels_ = 0;
  double control_period_s_;
};

}  // namespace rpsd::servo
