// The checks every hardware adapter's parameters and every emulator's file share: a channel
// count the node's messages carry, the timing of a link with deadlines, and addresses that are
// dotted IPv4. One place, so that the adapters (UDP controller, Speedgoat, ...) agree.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>

#include "rpsd/config/source.h"

namespace rpsd::node {

// Throws std::invalid_argument naming the key. Not real-time safe.
void check_link_channels(int channels);
void check_link_timing(double reply_timeout_s, int max_missed_replies, double start_timeout_s,
                       double start_tolerance_m);

// A reader's check, once its keys are read: fails at the key whose text is not a dotted IPv4
// address. Not real-time safe.
void check_ipv4_keys(config::Source& section, std::initializer_list<std::pair<const char*, std::string>> keyed);

}  // namespace rpsd::node
