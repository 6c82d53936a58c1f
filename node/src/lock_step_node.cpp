#include "rpsd/node/lock_step_node.h"

namespace rpsd::node {

bool answer_lock_step(ServoNodeController& controller, const transport::CommandSample& command,
                      transport::FeedbackSample& feedback) {
  return controller.answer(command, feedback);
}

}  // namespace rpsd::node
