// A servo node answered in the caller's thread: each command is accepted and, when the
// controller takes it, ticked at once. This is how `rpsd servo-node` answers in lock-step
// mode, and how the in-process link drives a node, so a test in one process runs the same
// controller, limits and watchdog as a test over DDS.
#pragma once

#include "rpsd/node/servo_node_controller.h"
#include "rpsd/transport/link.h"

namespace rpsd::node {

// One lock-step exchange: true with `feedback` filled when the controller accepted the
// command and ticked; false (feedback untouched) when it refused it. Real-time safe.
bool answer_lock_step(ServoNodeController& controller, const transport::CommandSample& command,
                      transport::FeedbackSample& feedback);

class LockStepNode final : public transport::CommandProcessor {
 public:
  // The controller must be started and outlive the node.
  explicit LockStepNode(ServoNodeController& controller) : controller_(controller) {}
  bool process(const transport::CommandSample& command, transport::FeedbackSample& feedback) override {
    return answer_lock_step(controller_, command, feedback);
  }

 private:
  ServoNodeController& controller_;
};

}  // namespace rpsd::node
