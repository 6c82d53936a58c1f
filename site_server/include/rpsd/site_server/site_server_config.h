// What `rpsd site-server SITE.yaml` serves: where it listens, the OpenSees element's basic
// DOFs and which actuator channel follows which, and the experimental half of a test (its
// channels, rig, compensator, control rate, transport and nodes), typed as a test's.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::site_server {

// An actuator channel follows displacement_scale x (d[basic_dof] - d[relative_to]) of the
// element's basic DOFs (relative_to -1: none), and its specimen's force f goes back as
// force_scale x f on basic_dof and its opposite on relative_to: a storey spring between two
// nodes is {1, 0}.
struct ChannelMap {
  int basic_dof = 0;
  int relative_to = -1;
};

struct SiteServerConfig {
  std::string name;
  std::string description;
  std::string listen_address = "127.0.0.1";  // loopback unless allowed_clients names the clients
  std::uint16_t listen_port = 0;             // 0: a free port, printed at the start
  // The only peers served (dotted IPv4); none: loopback peers only. genericClient has no
  // authentication, so the peer's address is the only check there is.
  std::vector<std::string> allowed_clients;
  double accept_timeout_s = 600.0;  // the longest wait for OpenSees to connect
  double idle_timeout_s = 60.0;     // the longest wait for OpenSees' next request
  double message_timeout_s = 2.0;   // a request's rest, once it has begun
  int element_dofs = 1;             // the genericClient's basic DOFs (its -dof entries)
  std::vector<ChannelMap> maps;     // per actuator channel, in channel order
  // The experimental half of a test: experimental (the channels' scales, sites, limits),
  // plant, compensation, control_rate_hz (one command per OpenSees step), clock, transport,
  // run_away, site_nodes. The structure is OpenSees'.
  hybrid_test::TestConfig site;
  std::vector<std::filesystem::path> input_files;  // what was read, for the summary
};

}  // namespace rpsd::site_server
