// The coordinator's side of the connection to a servo node. One interface, several
// transports: in-process (lock-step, deterministic; tests and rehearsals) and, later,
// Cyclone DDS between hosts. The coordinator loop cannot tell them apart.
#pragma once

#include "rpsd/transport/messages.h"

namespace rpsd::transport {

enum class LinkStatus : std::uint8_t {
  kOk,
  kTimeout,    // no feedback for this step before the deadline
  kStaleStep,  // feedback arrived for a different step
  kPeerLost,
  kRefused,  // the site's node serves another run (DdsLink::refusal says which)
};

class Link {
 public:
  virtual ~Link() = default;
  // Sends the command of one control step. Real-time safe.
  virtual LinkStatus send(const CommandSample& command) = 0;
  // Waits (within the link's deadline) for the feedback of the last command. Without it,
  // hands back the newest feedback the node sent, or leaves `feedback` untouched when the
  // node has sent none yet. Real-time safe.
  virtual LinkStatus receive(FeedbackSample& feedback) = 0;
};

// The node side as the in-process link sees it: turns one command into one feedback.
class CommandProcessor {
 public:
  virtual ~CommandProcessor() = default;
  // True with `feedback` filled when the node answered the command; false when it refused
  // it (feedback untouched). Real-time safe.
  virtual bool process(const CommandSample& command, FeedbackSample& feedback) = 0;
};

}  // namespace rpsd::transport
