#include "rpsd/hybrid_test/dds_site.h"

#include <cmath>
#include <utility>

namespace rpsd::hybrid_test {

std::unique_ptr<Site> DdsSite::make(const TestConfig& test, const SiteSetup& setup, SiteResources& shared) {
  if (!shared.participant) {
    shared.participant = std::make_unique<transport::DdsParticipant>(
        transport::DdsDomainConfig{test.transport.domain_id, test.transport.dds_config.string()});
  }
  transport::DdsLinkConfig config;
  config.test_id = test.transport.test_id;
  config.site_id = setup.site_id;
  config.run_id = setup.run_id;
  config.channels = static_cast<int>(setup.channels.size());
  config.qos.control_period_s = setup.control_period_s;
  config.qos.newest_only = test.clock.mode == ClockConfig::Mode::kRealTime;
  config.feedback_timeout_s = test.transport.feedback_timeout_s;
  config.busy_wait_s = test.transport.busy_wait_s;
  auto link = std::make_unique<transport::DdsLink>(*shared.participant, config);
  return std::unique_ptr<Site>(new DdsSite(std::move(link), estimated_initial_forces_n(setup)));
}

namespace {

// The node's newest heartbeat, when it carries a measurement.
const transport::NodeHeartbeat* measured_heartbeat(const transport::DdsLink& link) {
  const auto& heartbeat = link.node_heartbeat();
  return heartbeat && heartbeat->measured ? &*heartbeat : nullptr;
}

}  // namespace

std::optional<double> DdsSite::initial_displacement_m(std::size_t i) const {
  const transport::NodeHeartbeat* h = measured_heartbeat(*link_);
  return h ? std::optional<double>(h->displacement_m[i]) : std::nullopt;
}

bool DdsSite::initial_force_measured(std::size_t i) const {
  const transport::NodeHeartbeat* h = measured_heartbeat(*link_);
  return h != nullptr && std::isfinite(h->force_n[i]);
}

double DdsSite::initial_force_n(std::size_t i) const {
  return initial_force_measured(i) ? measured_heartbeat(*link_)->force_n[i] : initial_force_n_[i];
}

}  // namespace rpsd::hybrid_test
