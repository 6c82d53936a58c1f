#include "rpsd/commands/validate_report.h"

#include <cmath>
#include <sstream>
#include <string>
#include <type_traits>
#include <variant>

#include "rpsd/node/servo_node_overview.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/site_server/site_summary.h"
#include "rpsd/studies/scenario_overview.h"

namespace rpsd::commands {
namespace {

nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

nlohmann::json lines_of(const std::string& text) {
  nlohmann::json lines = nlohmann::json::array();
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  return lines;
}

nlohmann::json node_json(const node::ServoNodeSetup& setup) {
  const node::ServoNodeConfig& n = setup.node;
  nlohmann::json channels = nlohmann::json::array();
  for (int c = 0; c < n.channels; ++c) {
    const node::ChannelLimits& l = n.limits[static_cast<std::size_t>(c)];
    channels.push_back({{"channel", c},
                        {"initial_displacement_m", setup.initial_displacement_m[static_cast<std::size_t>(c)]},
                        {"max_stroke_m", finite_or_null(l.max_stroke_m)},
                        {"max_velocity_m_per_s", finite_or_null(l.max_velocity_m_per_s)},
                        {"max_force_n", finite_or_null(l.max_force_n)},
                        {"max_increment_m", finite_or_null(l.max_increment_m)}});
  }
  const std::string actuator =
      std::visit([](const auto& kind) { return std::string(std::decay_t<decltype(kind)>::kName); }, setup.actuator);
  return {{"kind", "servo_node"},
          {"test_id", n.test_id},
          {"site_id", n.site_id},
          {"mode", setup.mode == node::ServoNodeSetup::Mode::kRealTime ? "real_time" : "lock_step"},
          {"control_rate_hz", 1.0 / n.control_period_s},
          {"actuator", actuator},
          {"channels", channels}};
}

nlohmann::json site_json(const site_server::SiteServerConfig& c) {
  nlohmann::json channels = nlohmann::json::array();
  for (std::size_t ch = 0; ch < c.maps.size(); ++ch) {
    channels.push_back(
        {{"channel", ch},
         {"basic_dof", c.maps[ch].basic_dof},
         {"relative_to", c.maps[ch].relative_to < 0 ? nlohmann::json(nullptr) : nlohmann::json(c.maps[ch].relative_to)},
         {"site_id", c.site.experimental[ch].site_id}});
  }
  return {{"kind", "site_server"},
          {"name", c.name},
          {"listen_address", c.listen_address},
          {"listen_port", c.listen_port},
          {"allowed_clients", c.allowed_clients},
          {"element_dofs", c.element_dofs},
          {"control_rate_hz", c.site.control_rate_hz},
          {"channels", channels}};
}

}  // namespace

nlohmann::json validate_file(const std::filesystem::path& file, const std::vector<scenarios::Override>& overrides,
                             std::ostream& text, const hybrid_test::ExternalParts& external) {
  std::ostringstream overview;
  nlohmann::json report;
  if (scenarios::is_site_server_file(file)) {
    const auto site = scenarios::load_site_server(file, overrides);
    text << file.string() << ": ok (a site-server file)\n";
    site_server::print_site_overview(site, overview);
    report = site_json(site);
  } else if (scenarios::is_servo_node_file(file)) {
    const auto node = scenarios::load_servo_node(file, overrides);
    text << file.string() << ": ok (a servo node's file)\n";
    node::print_node_overview(node, overview);
    report = node_json(node);
  } else {
    const auto study = scenarios::load_study(file, overrides, external);
    text << file.string() << ": ok\n";
    report = {{"kind", "study"}, {"scenario", study.name}};
    if (const auto* test = std::get_if<hybrid_test::TestConfig>(&study.study)) {
      report["kind"] = "rpsd_test";
      if (!study.sweep.empty()) {
        overview << "  sweep: " << study.sweep_cases.size() << " cases; the first:\n";
        report["kind"] = "sweep";
        report["cases"] = study.sweep_cases.size();
      }
      if (study.monte_carlo) {
        overview << "  monte_carlo: " << study.sweep_cases.size() << " runs (seed " << study.monte_carlo->seed
                 << "), each read and checked; " << study.monte_carlo->parameters.size()
                 << " keys drawn; the first run:\n";
        report["kind"] = "monte_carlo";
        report["runs"] = study.sweep_cases.size();
        report["seed"] = study.monte_carlo->seed;
        report["keys_drawn"] = study.monte_carlo->parameters.size();
      }
      const studies::ScenarioOverview o = studies::overview_of(*test);
      studies::print_overview(o, overview);
      report["test"] = studies::overview_json(o);
    }
  }
  text << overview.str();
  report["file"] = file.string();
  report["ok"] = true;
  report["overview"] = lines_of(overview.str());
  return report;
}

}  // namespace rpsd::commands
