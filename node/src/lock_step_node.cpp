#include "rpsd/node/lock_step_node.h"

namespace rpsd::node {

bool answer_lock_step(ServoNodeController& controller, const transport::CommandSample& command,
                      transport::FeedbackSample& feedback) {
  if (controller.accept(command) != CommandVerdict::kAccepted) return false;
  controller.tick(feedback);
  return true;
}

}  // namespace rpsd::node
