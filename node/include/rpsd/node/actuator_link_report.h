// What a hardware adapter tells the node's log and summary.json about its link to the lab's
// controller: one line at start (the peer, the protocol, what it authenticates, any offsets
// measured), and at the end its counters and, when the link failed, which side failed.
// serve_site() asks every actuator for it, so a new adapter needs no edit there.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace rpsd::node {

class ActuatorLinkReport {
 public:
  virtual ~ActuatorLinkReport() = default;
  // The summary.json key the link's figures go under ("udp_link").
  virtual std::string_view summary_key() const = 0;
  // One line for the node's log, after start(). Not real-time safe.
  virtual std::string describe_link() const = 0;
  // The link's figures for summary.json. Not real-time safe.
  virtual nlohmann::json link_summary() const = 0;
};

}  // namespace rpsd::node
