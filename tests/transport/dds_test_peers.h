// What the DDS transport tests share: a loopback domain of their own, the two sides' configs
// and the node's side of the start handshake.
#pragma once

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

#include "claimed_dds_domain.h"
#include "rpsd/transport/dds_link.h"
#include "rpsd/transport/dds_node_endpoint.h"

namespace rpsd::transport::testing {

inline DdsDomainConfig loopback() {
  // A domain no other live test holds (claimed_dds_domain.h) keeps parallel ctest processes apart.
  return {::rpsd::testing::claimed_dds_domain(), std::string(RPSD_TEST_SOURCE_DIR) + "/transport/config/loopback.xml"};
}

inline DdsLinkConfig link_config(std::uint32_t test, std::uint32_t site, int channels, double timeout_s = 1.0) {
  DdsLinkConfig c;
  c.test_id = test;
  c.site_id = site;
  c.channels = channels;
  c.feedback_timeout_s = timeout_s;
  return c;
}

inline DdsNodeEndpointConfig node_config(std::uint32_t test, std::uint32_t site) {
  DdsNodeEndpointConfig c;
  c.test_id = test;
  c.site_id = site;
  return c;
}

// The node's side of the start handshake: heartbeats, as a servo node sends them (serving
// run `serving_run_id`, 0: none, at `control_period_s`), while the link waits for the node;
// true once the link has found it and it serves no other run at the link's rate.
// The same with the heartbeat `h` (its own test, site, run and rate).
inline bool connect_with(DdsLink& link, DdsNodeEndpoint& node, const NodeHeartbeat& h, double timeout_s = 10.0) {
  std::atomic<bool> done{false};
  std::thread announcer([&] {
    while (!done) {
      node.publish_heartbeat(h);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
  });
  const bool found = link.wait_for_node(timeout_s);
  done = true;
  announcer.join();
  return found;
}

inline bool connect(DdsLink& link, DdsNodeEndpoint& node, std::uint32_t test, std::uint32_t site,
                    double timeout_s = 10.0, std::uint64_t serving_run_id = 0,
                    double control_period_s = DdsQosConfig{}.control_period_s) {
  NodeHeartbeat h;
  h.test_id = test;
  h.site_id = site;
  h.control_period_s = control_period_s;
  h.serving_run_id = serving_run_id;
  return connect_with(link, node, h, timeout_s);
}

}  // namespace rpsd::transport::testing
