#include "rpsd/servo/plant_node.h"

#include <stdexcept>

namespace rpsd::servo {

PlantNode::PlantNode(std::span<Plant* const> plants, double control_period_s)
    : actuator_(plants), control_period_s_(control_period_s) {
  if (!(control_period_s > 0.0)) throw std::invalid_argument("PlantNode: control period must be positive");
}

void PlantNode::reset(std::span<const double> displacements_m) { actuator_.reset(displacements_m); }

void PlantNode::process(const transport::CommandSample& command, transport::FeedbackSample& feedback) {
  const int channels = actuator_.channels();
  feedback.test_id = command.test_id;
  feedback.site_id = command.site_id;
  feedback.step = command.step;
  feedback.time_s = command.time_s;
  feedback.channels = static_cast<std::uint8_t>(channels);
  feedback.status = transport::kNodeOk;
  if (command.channels != channels ||
      actuator_.exchange(std::span<const double>(command.displacement_m.data(), static_cast<std::size_t>(channels)),
                         control_period_s_, reading_) != ActuatorStatus::kOk) {
    feedback.status = transport::kNodeFault;
    return;
  }
  for (int c = 0; c < channels; ++c) {
    feedback.displacement_m[c] = reading_.displacement_m[c];
    feedback.force_n[c] = reading_.force_n[c];
  }
}

}  // namespace rpsd::servo
