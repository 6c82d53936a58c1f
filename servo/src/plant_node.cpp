#include "rpsd/servo/plant_node.h"

#include <stdexcept>

namespace rpsd::servo {

PlantNode::PlantNode(std::span<Plant* const> plants, double control_period_s)
    : channels_(static_cast<int>(plants.size())), control_period_s_(control_period_s) {
  if (plants.empty() || plants.size() > transport::kMaxChannels) {
    throw std::invalid_argument("PlantNode: between 1 and " + std::to_string(transport::kMaxChannels) + " channels");
  }
  if (!(control_period_s > 0.0)) throw std::invalid_argument("PlantNode: control period must be positive");
  for (int c = 0; c < channels_; ++c) {
    if (plants[c] == nullptr) throw std::invalid_argument("PlantNode: null plant");
    plants_[c] = plants[c];
  }
}

void PlantNode::reset(std::span<const double> displacements_m) {
  for (int c = 0; c < channels_; ++c) {
    const double x0 = c < static_cast<int>(displacements_m.size()) ? displacements_m[c] : 0.0;
    plants_[c]->reset(x0);
    last_command_m_[c] = x0;
  }
}

void PlantNode::process(const transport::CommandSample& command, transport::FeedbackSample& feedback) {
  feedback.test_id = command.test_id;
  feedback.site_id = command.site_id;
  feedback.step = command.step;
  feedback.time_s = command.time_s;
  feedback.channels = static_cast<std::uint8_t>(channels_);
  feedback.status = transport::kNodeOk;
  if (command.channels != channels_) {
    feedback.status = transport::kNodeFault;
    return;
  }
  for (int c = 0; c < channels_; ++c) {
    plants_[c]->advance(last_command_m_[c], command.displacement_m[c], control_period_s_);
    last_command_m_[c] = command.displacement_m[c];
    const PlantMeasurement m = plants_[c]->measure();
    feedback.displacement_m[c] = m.displacement_m;
    feedback.force_n[c] = m.force_n;
  }
}

}  // namespace rpsd::servo
