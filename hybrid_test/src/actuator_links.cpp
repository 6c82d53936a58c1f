#include "rpsd/hybrid_test/actuator_links.h"

#include <algorithm>
#include <map>
#include <sstream>
#include <stdexcept>

#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/site_kinds.h"

namespace rpsd::hybrid_test {

ActuatorLinks::~ActuatorLinks() { end_run(); }

ActuatorLinks::ActuatorLinks(const TestConfig& s, double control_period_s, bool perfect_actuator,
                             std::span<const double> hold_m, std::uint64_t run_id,
                             std::span<const double> stiffness_estimate_n_per_m) {
  // The structure's channels, then (not for the perfect-actuator reference, which is
  // numerical) the held forces' (held_forces.h): every link channel.
  const int structure_channels = static_cast<int>(s.experimental.size());
  const int held = perfect_actuator ? 0 : static_cast<int>(s.held_forces.size());
  const int channels = structure_channels + held;
  initial_force_n_.assign(static_cast<std::size_t>(channels), 0.0);
  initial_reading_m_.assign(static_cast<std::size_t>(channels), std::nullopt);
  initial_force_measured_.assign(static_cast<std::size_t>(channels), false);
  plant_of_channel_.assign(static_cast<std::size_t>(channels), nullptr);
  // Sites in order of first appearance; each site's channels in the test's channel order, its
  // held forces' after its structure's.
  std::map<std::uint32_t, std::size_t> index_of_site;
  std::vector<const ExperimentalChannel*> by_channel(static_cast<std::size_t>(structure_channels));
  for (const auto& e : s.experimental) by_channel[static_cast<std::size_t>(e.dof.actuator_channel)] = &e;
  for (int ch = 0; ch < channels; ++ch) {
    const std::uint32_t site = ch < structure_channels
                                   ? by_channel[static_cast<std::size_t>(ch)]->site_id
                                   : s.held_forces[static_cast<std::size_t>(ch - structure_channels)].site_id;
    auto [it, added] = index_of_site.emplace(site, sites_.size());
    if (added) sites_.push_back({site, {}});
    sites_[it->second].channels.push_back(ch);
  }

  std::vector<transport::SiteRoute> routes;
  for (const SiteSummary& site : sites_) {
    SiteSetup setup;
    setup.site_id = site.site_id;
    setup.channels = site.channels;
    for (int ch : site.channels) {
      if (ch >= structure_channels) {
        // A held force's actuator rests where it is (its piston's position at rest, 0) and is
        // sent forces, not positions.
        const int k = ch - structure_channels;
        setup.hold_m.push_back(0.0);
        setup.stiffness_estimate_n_per_m.push_back(
            s.held_forces[static_cast<std::size_t>(k)].specimen_stiffness_n_per_m);
        setup.held_force.resize(site.channels.size(), -1);
        setup.held_force[setup.hold_m.size() - 1] = k;
        continue;
      }
      setup.hold_m.push_back(hold_m[static_cast<std::size_t>(ch)]);
      setup.stiffness_estimate_n_per_m.push_back(
          stiffness_estimate_n_per_m.empty()
              ? by_channel[static_cast<std::size_t>(ch)]->dof.specimen_stiffness_estimate_n_per_m
              : stiffness_estimate_n_per_m[static_cast<std::size_t>(ch)]);
    }
    // What a node refusing a command's control mode is told by the test (node_fault_text).
    std::string modes;
    for (std::size_t j = 0; j < setup.held_force.size(); ++j) {
      if (setup.held_force[j] < 0) continue;
      modes += (modes.empty() ? "" : ", ") + std::string("channel ") + std::to_string(j) + " in force control for " +
               held_force_label(s.held_forces[static_cast<std::size_t>(setup.held_force[j])]);
    }
    held_modes_.push_back(modes);
    setup.control_period_s = control_period_s;
    setup.run_id = run_id;
    setup.perfect_actuator = perfect_actuator;
    built_.push_back(make_site(s, setup, shared_));
    Site& built = *built_.back();
    over_dds_ = over_dds_ || built.over_dds();
    routes.push_back({site.site_id, &built.link(), site.channels});
  }
  multi_site_ = std::make_unique<transport::MultiSiteLink>(std::move(routes));

  std::string missing;
  for (std::size_t i = 0; i < built_.size(); ++i) {
    if (!built_[i]->wait_for_node(s.transport.discovery_timeout_s)) {
      // A node that refuses the run ends it at once: the run reports why (refusal_text).
      if (built_[i]->refused()) break;
      missing += (missing.empty() ? "" : ", ") + std::to_string(sites_[i].site_id);
    }
  }
  // What each actuator reads at rest, asked once its node is found: over DDS, its heartbeat's.
  for (std::size_t k = 0; k < built_.size(); ++k) {
    const Site& built = *built_[k];
    for (std::size_t i = 0; i < sites_[k].channels.size(); ++i) {
      const auto ch = static_cast<std::size_t>(sites_[k].channels[i]);
      initial_force_n_[ch] = built.initial_force_n(i);
      initial_force_measured_[ch] = built.initial_force_measured(i);
      plant_of_channel_[ch] = built.simulated_plant(i);
      initial_reading_m_[ch] = plant_of_channel_[ch]
                                   ? std::optional<double>(plant_of_channel_[ch]->measure().displacement_m)
                                   : built.initial_displacement_m(i);
    }
  }
  if (refused()) return;
  if (!missing.empty()) {
    throw NoNodeAnswered("no servo node answered for site(s) " + missing + " of test " +
                         std::to_string(s.transport.test_id) + " within " +
                         (std::ostringstream() << s.transport.discovery_timeout_s).str() +
                         " s (is `rpsd servo-node` running with the same test_id, site_id and domain, and in mode " +
                         (s.clock.mode == ClockConfig::Mode::kRealTime ? "real_time" : "lock_step") + "?)");
  }
}

void ActuatorLinks::set_receive_deadline_ns(std::int64_t deadline_ns) {
  for (auto& site : built_) site->set_receive_deadline_ns(deadline_ns);
}

bool ActuatorLinks::refused() const {
  return std::any_of(built_.begin(), built_.end(), [](const auto& site) { return site->refused(); });
}

std::string ActuatorLinks::refusal_text() const {
  // The sites' failures first, then the nodes' refusals.
  std::string text;
  for (const auto& site : built_) {
    if (const std::string failure = site->failure(); !failure.empty()) text += (text.empty() ? "" : "; ") + failure;
  }
  for (const auto& site : built_) {
    if (const std::string refusal = site->refusal_text(); !refusal.empty())
      text += (text.empty() ? "" : "; ") + refusal;
  }
  return text;
}

std::string ActuatorLinks::node_fault_text() {
  std::string text;
  for (std::size_t i = 0; i < built_.size(); ++i) {
    const std::string said = built_[i]->node_fault_text();
    if (said.empty()) continue;
    text += (text.empty() ? "" : "; ") + ("site " + std::to_string(sites_[i].site_id) + ": ") + said;
    // A node refuses a command whose control mode is not the one its file declares: say which
    // held force the test sends there.
    if (!held_modes_[i].empty() && said.find("control mode") != std::string::npos) {
      text += " (this test puts its " + held_modes_[i] +
              ", every other channel in displacement control: the node file's actuator.control must say the same)";
    }
  }
  return text;
}

void ActuatorLinks::end_run() {
  if (ended_) return;
  ended_ = true;
  for (auto& site : built_) site->end_run();
}

void ActuatorLinks::keep_run_alive() {
  if (ended_) return;
  for (auto& site : built_) site->keep_run_alive();
}

std::vector<transport::DdsLinkCounters> ActuatorLinks::dds_counters() const {
  std::vector<transport::DdsLinkCounters> counters;
  for (const auto& site : built_) {
    if (const auto c = site->dds_counters()) counters.push_back(*c);
  }
  return counters;
}

}  // namespace rpsd::hybrid_test
