// Lock-step link to a node in the same process: send() runs the node's step at once and
// receive() returns its feedback (kTimeout when the node refused the command).
// Deterministic and bit-for-bit repeatable.
#pragma once

#include "rpsd/transport/link.h"

namespace rpsd::transport {

class InProcessLink final : public Link {
 public:
  explicit InProcessLink(CommandProcessor& node) : node_(node) {}

  LinkStatus send(const CommandSample& command) override {
    pending_ = node_.process(command, feedback_);
    return LinkStatus::kOk;
  }

  LinkStatus receive(FeedbackSample& feedback) override {
    if (!pending_) return LinkStatus::kTimeout;
    feedback = feedback_;
    pending_ = false;
    return LinkStatus::kOk;
  }

 private:
  CommandProcessor& node_;
  FeedbackSample feedback_;
  bool pending_ = false;
};

}  // namespace rpsd::transport
