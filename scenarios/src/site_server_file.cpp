#include "rpsd/scenarios/site_server_file.h"

#include <algorithm>
#include <memory>
#include <set>

#include "hybrid_test_sections.h"
#include "physical_ranges.h"
#include "rpsd/config/input_log.h"
#include "rpsd/config/key_error.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/opensees/client_gate.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "site_server_sections.h"

namespace rpsd::scenarios {
namespace site_server_sections {

using config::Number;
using namespace ranges;

// More clients than a lab has OpenSees hosts is a list nobody checked.
constexpr std::size_t kMaxAllowedClients = 16;

void listen(config::Source& l, site_server::SiteServerConfig& c) {
  c.listen_address = l.optional_text("address",
                                     "the IPv4 address to listen on (default 127.0.0.1); any other than loopback "
                                     "needs allowed_clients")
                         .value_or(c.listen_address);
  c.listen_port = static_cast<std::uint16_t>(
      l.whole_number_or("port", 0, 65535, 0, "the TCP port of the element's -server (0: any free port, printed)"));
  c.allowed_clients = l.optional_texts("allowed_clients",
                                       "the only clients served, by IPv4 address (default: loopback only); any other "
                                       "peer is closed at once (genericClient has no authentication)",
                                       kMaxAllowedClients)
                          .value_or(std::vector<std::string>{});
  c.accept_timeout_s = l.number_or("accept_timeout_s", c.accept_timeout_s,
                                   Number{"s", "the longest wait for OpenSees to connect", 0.0, 86400.0, true});
  c.idle_timeout_s = l.number_or(
      "idle_timeout_s", c.idle_timeout_s,
      Number{"s", "the longest wait for OpenSees' next request, or for it to take a reply", 0.0, 86400.0, true});
  c.message_timeout_s = l.number_or("message_timeout_s", c.message_timeout_s,
                                    Number{"s", "the setup, or a request's rest once it has begun", 0.0, 600.0, true});
  // Anyone who reaches the port may command the actuators: a server others can reach
  // serves only the clients the file names.
  const auto address = opensees::parse_ipv4(c.listen_address);
  if (!address) l.fail("address", "expected an IPv4 address such as 127.0.0.1, got \"" + c.listen_address + "\"");
  for (const std::string& client : c.allowed_clients) {
    if (const std::string problem = opensees::client_address_problem(client); !problem.empty()) {
      l.fail("allowed_clients", problem);
    }
  }
  if (!opensees::is_loopback(*address) && c.allowed_clients.empty()) {
    l.fail("address", c.listen_address +
                          " is not a loopback address, and genericClient has no authentication: anyone who reaches "
                          "it could command the actuators. Name the OpenSees hosts in listen.allowed_clients "
                          "(e.g. allowed_clients: [198.18.0.1]), or listen on 127.0.0.1");
  }
  l.finish();
}

// experimental[i]: a test's channel keys, with basic_dof and relative_to for dof.
hybrid_test::ExperimentalChannel channel(config::Source& e, int dofs, std::size_t index, site_server::ChannelMap& map,
                                         std::unique_ptr<config::Source>& limits_section) {
  hybrid_test::ExperimentalChannel channel;
  map.basic_dof = static_cast<int>(
      e.whole_number("basic_dof", 0, dofs - 1, "the element's basic DOF the actuator follows (0-based, -dof order)"));
  map.relative_to = static_cast<int>(
      e.whole_number_or("relative_to", -1, dofs - 1, -1,
                        "a basic DOF whose displacement is subtracted (a spring's other end; -1: none)"));
  if (map.relative_to == map.basic_dof) e.fail("relative_to", "must differ from basic_dof");
  channel.dof.dof = map.basic_dof;
  test_sections::specimen_channel(e, index, channel, limits_section);
  e.finish();
  return channel;
}

void site_file(config::Source& root, site_server::SiteServerConfig& c,
               std::vector<std::unique_ptr<config::Source>>& limit_sections) {
  c.description = root.optional_text("description", "one line for titles and summaries").value_or("");
  hybrid_test::TestConfig& t = c.site;
  t.name = c.name;
  t.description = c.description;
  listen(*root.section("listen", "where OpenSees' genericClient element connects"), c);
  c.element_dofs = static_cast<int>(root.whole_number(
      "element_dofs", 1, 64, "the genericClient's basic DOFs: every -dof entry of every node, in order"));
  auto channels =
      root.sections("experimental", transport::kMaxChannels, "the actuator channels, each following a basic DOF");
  limit_sections.resize(channels.size());
  c.maps.resize(channels.size());
  std::set<long> used;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    site_server::ChannelMap map;
    std::unique_ptr<config::Source> limits;
    t.experimental.push_back(channel(*channels[i], c.element_dofs, i, map, limits));
    const auto ch = static_cast<long>(t.experimental.back().dof.actuator_channel);
    if (ch >= static_cast<long>(channels.size()) || !used.insert(ch).second) {
      channels[i]->fail("channel", "channels must be 0 to " + std::to_string(channels.size() - 1) + ", each once");
    }
    c.maps[static_cast<std::size_t>(ch)] = map;
    limit_sections[static_cast<std::size_t>(ch)] = std::move(limits);  // in channel order, as experimental will be
  }
  // Channel order, as the exchange wants it.
  std::sort(t.experimental.begin(), t.experimental.end(),
            [](const auto& a, const auto& b) { return a.dof.actuator_channel < b.dof.actuator_channel; });
  t.plant = servo::read_plant_config(
      *root.section("servo", "every channel's actuator (servo/)"),
      t.experimental.empty() ? 0.0 : t.experimental.front().dof.specimen_stiffness_estimate_n_per_m);
  test_sections::clock(*root.section("clock", "the control rate: one command per OpenSees step"), t);
  if (t.clock.mode != hybrid_test::ClockConfig::Mode::kAsFastAsPossible) {
    root.fail("clock", "OpenSees paces a site server's test: clock.mode must be as_fast_as_possible (lock-step)");
  }
  if (t.clock.loop_timing != coordinator::LoopTiming::kEndOfStep) {
    root.fail("clock",
              "OpenSees integrates a site server's test and times its own loop: clock.loop_timing must be "
              "end_of_step (or left out)");
  }
  if (auto transport = root.optional_section("transport", "how the sites are reached (default: in process)")) {
    test_sections::transport(*transport, t);
  }
  if (auto compensation = root.optional_section("compensation", "the delay compensator (default: none)")) {
    t.compensation = test_sections::compensation(*compensation, 1.0 / t.control_rate_hz);
    if (compensation::is_external(t.compensation)) {
      compensation->fail("kind",
                         "external is given only by a host program (rpsd.run(..., callables=...)); a site "
                         "server cannot run it");
    }
  }
  root.finish();
}

}  // namespace site_server_sections

bool is_site_server_file(const std::filesystem::path& file) {
  const YAML::Node document = load_yaml_document(file, {});
  return document.IsMap() && document["listen"] && !document["study"];
}

site_server::SiteServerConfig load_site_server(const std::filesystem::path& file,
                                               const std::vector<Override>& overrides) {
  config::InputLog inputs;
  config::InputLog::note(file);
  MappingReader root = load_root_reader(file, overrides);
  site_server::SiteServerConfig c;
  c.name = file.stem().string();
  std::vector<std::unique_ptr<config::Source>> limit_sections;
  site_server_sections::site_file(root, c, limit_sections);
  const hybrid_test::TestConfig& t = c.site;
  const double control_period_s = 1.0 / t.control_rate_hz;
  try {
    servo::check_control_period(t.plant, control_period_s);
  } catch (const std::invalid_argument& e) {
    throw ConfigError(file.string() + ": servo." + e.what());
  }
  for (std::size_t i = 0; i < t.experimental.size(); ++i) {
    try {
      // Inside the rig's envelope, and strictly inside what the converters can read.
      const coordinator::CoordinatorLimits& stated = t.experimental[i].limits;
      coordinator::require_readable(stated,
                                    coordinator::within_envelope(stated, servo::envelope_of(t.plant), control_period_s),
                                    servo::reading_ranges_of(t.plant), "servo.converters");
    } catch (const config::KeyError& e) {
      if (i < limit_sections.size() && limit_sections[i]) limit_sections[i]->fail(e.path(), e.problem());
      throw ConfigError(file.string() + ": experimental[" + std::to_string(i) + "].limits." + e.what());
    }
  }
  c.input_files = inputs.files();
  return c;
}

}  // namespace rpsd::scenarios
