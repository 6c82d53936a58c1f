#include "rpsd/hybrid_test/dds_site.h"

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

}  // namespace rpsd::hybrid_test
