#include "rpsd/node/hardware_link_checks.h"

#include <cmath>
#include <stdexcept>

#include "rpsd/node/udp_socket.h"
#include "rpsd/transport/messages.h"

namespace rpsd::node {

void check_link_channels(int channels) {
  if (channels < 1 || channels > transport::kMaxChannels) {
    throw std::invalid_argument("channels: must be between 1 and " + std::to_string(transport::kMaxChannels) +
                                ", got " + std::to_string(channels));
  }
}

void check_link_timing(double reply_timeout_s, int max_missed_replies, double start_timeout_s,
                       double start_tolerance_m) {
  if (!(reply_timeout_s > 0.0) || !std::isfinite(reply_timeout_s))
    throw std::invalid_argument("reply_timeout_s: must be positive");
  if (max_missed_replies < 0) throw std::invalid_argument("max_missed_replies: must be zero or positive");
  if (!(start_timeout_s > 0.0) || !std::isfinite(start_timeout_s))
    throw std::invalid_argument("start_timeout_s: must be positive");
  if (!(start_tolerance_m >= 0.0)) throw std::invalid_argument("start_tolerance_m: must be zero or positive");
}

void check_ipv4_keys(config::Source& section, std::initializer_list<std::pair<const char*, std::string>> keyed) {
  for (const auto& [key, text] : keyed) {
    try {
      Ipv4Endpoint::parse(text, 0, key);
    } catch (const std::invalid_argument& e) {
      section.fail(key, e.what());
    }
  }
}

}  // namespace rpsd::node
