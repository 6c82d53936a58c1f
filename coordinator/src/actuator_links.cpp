#include "rpsd/coordinator/actuator_links.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>

#include "rpsd/servo/simulated_actuator.h"
#include "rpsd/transport/in_process_link.h"

namespace rpsd::coordinator {

ActuatorLinks::~ActuatorLinks() { end_run(); }

ActuatorLinks::ActuatorLinks(const TestConfig& s, double control_period_s, bool perfect_actuator,
                             std::span<const double> hold_m, std::uint64_t run_id) {
  const int channels = static_cast<int>(s.experimental.size());
  initial_force_n_.assign(static_cast<std::size_t>(channels), 0.0);
  plant_of_channel_.assign(static_cast<std::size_t>(channels), nullptr);
  // Sites in order of first appearance; each site's channels in the test's channel order.
  std::map<std::uint32_t, std::size_t> index_of_site;
  std::vector<const ExperimentalChannel*> by_channel(static_cast<std::size_t>(channels));
  for (const auto& e : s.experimental) by_channel[static_cast<std::size_t>(e.dof.actuator_channel)] = &e;
  for (int ch = 0; ch < channels; ++ch) {
    const std::uint32_t site = by_channel[static_cast<std::size_t>(ch)]->site_id;
    auto [it, added] = index_of_site.emplace(site, sites_.size());
    if (added) sites_.push_back({site, {}});
    sites_[it->second].channels.push_back(ch);
  }

  const bool over_dds = s.transport.kind == TransportConfig::Kind::kDds && !perfect_actuator;
  const bool dds_sites = std::any_of(sites_.begin(), sites_.end(),
                                     [&s](const SiteSummary& site) { return !s.opensees_site(site.site_id); });
  if (over_dds && dds_sites) {
    participant_ = std::make_unique<transport::DdsParticipant>(
        transport::DdsDomainConfig{s.transport.domain_id, s.transport.dds_config.string()});
  }
  std::vector<transport::SiteRoute> routes;
  std::string missing;
  // A remote site's forces at rest, before any feedback: its stiffness estimate times the hold.
  const auto estimate_initial_forces = [&](const SiteSummary& site) {
    for (int ch : site.channels) {
      const auto& e = *by_channel[static_cast<std::size_t>(ch)];
      initial_force_n_[static_cast<std::size_t>(ch)] =
          e.dof.specimen_stiffness_estimate_n_per_m * hold_m[static_cast<std::size_t>(ch)];
    }
  };
  for (const SiteSummary& site : sites_) {
    if (const OpenSeesSite* remote = s.opensees_site(site.site_id)) {
      // A numerical site: its substructure answers every step in OpenSees (the reference its own).
      opensees::AdapterSiteConfig adapter = remote->adapter;
      if (perfect_actuator) adapter.port = remote->reference_port;
      auto link = std::make_unique<opensees::AdapterLink>(adapter);
      adapter_links_.push_back(link.get());
      site_links_.push_back(std::move(link));
      estimate_initial_forces(site);
    } else if (over_dds) {
      transport::DdsLinkConfig config;
      config.test_id = s.transport.test_id;
      config.site_id = site.site_id;
      config.run_id = run_id;
      config.channels = static_cast<int>(site.channels.size());
      config.qos.control_period_s = control_period_s;
      config.qos.newest_only = s.clock.mode == ClockConfig::Mode::kRealTime;
      config.feedback_timeout_s = s.transport.feedback_timeout_s;
      config.busy_wait_s = s.transport.busy_wait_s;
      auto link = std::make_unique<transport::DdsLink>(*participant_, config);
      dds_links_.push_back(link.get());
      site_links_.push_back(std::move(link));
      estimate_initial_forces(site);
    } else {
      // The site's node as `rpsd servo-node` runs it, answered in lock-step in this process.
      const int site_channels = static_cast<int>(site.channels.size());
      node::OwnedActuator simulated;
      for (int ch : site.channels) {
        const double k = by_channel[static_cast<std::size_t>(ch)]->dof.specimen_stiffness_estimate_n_per_m;
        simulated.plants.owned.push_back(servo::make_plant(
            perfect_actuator ? servo::PlantConfig{servo::PureDelayParameters{0.0, k, 8192.0, {}, {}}} : s.plant));
        simulated.plants.pointers.push_back(simulated.plants.owned.back().get());
      }
      simulated.actuator = std::make_unique<servo::SimulatedActuator>(simulated.plants.pointers);
      actuators_.push_back(std::move(simulated));
      node::ServoNodeConfig config;
      if (!perfect_actuator) {
        if (const auto found = s.site_nodes.find(site.site_id); found != s.site_nodes.end()) {
          config = found->second;  // its limits, limit actions and watchdog
        }
      }
      config.test_id = s.transport.test_id;
      config.site_id = site.site_id;
      config.channels = site_channels;
      config.control_period_s = control_period_s;
      if (!perfect_actuator) {
        // The rig's envelope is the node's default limit, and its force guard predicts with the
        // stiffest of the specimens' estimates.
        node::limit_to_envelope(config, servo::envelope_of(s.plant));
        // A reading at or beyond the rig's envelope, or on a converter's rail, faults the node
        // (the coordinator's limits were held inside the rails when the file was read).
        node::read_through_converters(config, servo::reading_ranges_of(s.plant));
        for (int i = 0; i < site_channels; ++i) {
          double& k = config.limits[static_cast<std::size_t>(i)].force_guard_stiffness_n_per_m;
          if (k == 0.0) {
            k = std::max(servo::specimen_stiffness_of(s.plant),
                         by_channel[static_cast<std::size_t>(site.channels[static_cast<std::size_t>(i)])]
                             ->dof.specimen_stiffness_estimate_n_per_m);
          }
        }
      }
      controllers_.push_back(std::make_unique<node::ServoNodeController>(config, *actuators_.back().actuator));
      std::vector<double> site_hold;
      for (int ch : site.channels) site_hold.push_back(hold_m[static_cast<std::size_t>(ch)]);
      controllers_.back()->start(site_hold);
      nodes_.push_back(std::make_unique<node::LockStepNode>(*controllers_.back()));
      for (std::size_t i = 0; i < site.channels.size(); ++i) {
        const auto ch = static_cast<std::size_t>(site.channels[i]);
        plant_of_channel_[ch] = actuators_.back().plants.pointers[i];
        initial_force_n_[ch] = plant_of_channel_[ch]->measure().force_n;
      }
      site_links_.push_back(std::make_unique<transport::InProcessLink>(*nodes_.back()));
    }
    routes.push_back({site.site_id, site_links_.back().get(), site.channels});
  }
  multi_site_ = std::make_unique<transport::MultiSiteLink>(std::move(routes));

  for (std::size_t i = 0; i < dds_links_.size(); ++i) {
    if (!dds_links_[i]->wait_for_node(s.transport.discovery_timeout_s)) {
      // A node that refuses the run ends it at once: the run reports why (refusal_text).
      if (dds_links_[i]->refusal().kind != transport::NodeRefusal::Kind::kNone) return;
      missing += (missing.empty() ? "" : ", ") + std::to_string(sites_[i].site_id);
    }
  }
  if (!missing.empty()) {
    throw NoNodeAnswered("no servo node answered for site(s) " + missing + " of test " +
                         std::to_string(s.transport.test_id) + " within " +
                         (std::ostringstream() << s.transport.discovery_timeout_s).str() +
                         " s (is `rpsd servo-node` running with the same test_id, site_id and domain, and in mode " +
                         (s.clock.mode == ClockConfig::Mode::kRealTime ? "real_time" : "lock_step") + "?)");
  }
}

void ActuatorLinks::set_receive_deadline_ns(std::int64_t deadline_ns) {
  for (auto* link : dds_links_) link->set_receive_deadline_ns(deadline_ns);
}

bool ActuatorLinks::refused() const {
  return std::any_of(dds_links_.begin(), dds_links_.end(), [](const transport::DdsLink* link) {
    return link->refusal().kind != transport::NodeRefusal::Kind::kNone;
  });
}

std::string ActuatorLinks::refusal_text() const {
  std::string text;
  for (const auto* link : adapter_links_) {
    if (!link->failure().empty()) text += (text.empty() ? "" : "; ") + link->failure();
  }
  for (const auto* link : dds_links_) {
    if (link->refusal().kind == transport::NodeRefusal::Kind::kNone) continue;
    text += (text.empty() ? "" : "; ") + link->refusal_text();
  }
  return text;
}

void ActuatorLinks::end_run() {
  if (ended_) return;
  ended_ = true;
  for (auto* link : dds_links_) link->end_run();
  for (auto* link : adapter_links_) link->end_run();
}

std::vector<transport::DdsLinkCounters> ActuatorLinks::dds_counters() const {
  std::vector<transport::DdsLinkCounters> counters;
  for (const auto* link : dds_links_) counters.push_back(link->counters());
  return counters;
}

}  // namespace rpsd::coordinator
