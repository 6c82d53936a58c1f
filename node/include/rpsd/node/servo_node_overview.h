// What `rpsd validate NODE.yaml` prints: the node's identity and pace, its actuator kind, and
// every channel's effective limits (the file's, else the rig's) — read from the file alone,
// never by reaching the controller.
#pragma once

#include <ostream>

#include "rpsd/node/servo_node_setup.h"

namespace rpsd::node {

// Not real-time safe.
void print_node_overview(const ServoNodeSetup& setup, std::ostream& out);

}  // namespace rpsd::node
