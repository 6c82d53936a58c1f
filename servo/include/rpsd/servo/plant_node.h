// A simulated servo node for the in-process link: a SimulatedActuator (one Plant per
// channel, first-order hold between commands) that turns each command into its feedback in
// lock step. The full node with limits and a watchdog is ServoNodeController.
#pragma once

#include <span>

#include "rpsd/servo/simulated_actuator.h"
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
  SimulatedActuator actuator_;
  ActuatorReading reading_;
  double control_period_s_;
};

}  // namespace rpsd::servo
