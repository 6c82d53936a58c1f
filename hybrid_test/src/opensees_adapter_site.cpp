#include "rpsd/hybrid_test/opensees_adapter_site.h"

#include <utility>

namespace rpsd::hybrid_test {

std::unique_ptr<Site> OpenSeesAdapterSite::make(const TestConfig& test, const SiteSetup& setup,
                                                SiteResources& /*shared*/) {
  const OpenSeesSite& remote = *test.opensees_site(setup.site_id);
  opensees::AdapterSiteConfig adapter = remote.adapter;
  if (setup.perfect_actuator) adapter.port = remote.reference_port;
  auto link = std::make_unique<opensees::AdapterLink>(adapter);
  return std::unique_ptr<Site>(new OpenSeesAdapterSite(std::move(link), estimated_initial_forces_n(setup)));
}

}  // namespace rpsd::hybrid_test
