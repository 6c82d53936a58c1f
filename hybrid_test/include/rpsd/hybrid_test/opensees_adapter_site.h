// A numerical site: its substructure is a remote OpenSees model's, answering every step
// through its `adapter` element (the perfect-actuator reference asks its own process, on
// reference_port).
#pragma once

#include <memory>
#include <string_view>
#include <vector>

#include "rpsd/hybrid_test/site.h"
#include "rpsd/hybrid_test/site_setup.h"
#include "rpsd/opensees/adapter_link.h"

namespace rpsd::hybrid_test {

class OpenSeesAdapterSite final : public Site {
 public:
  static constexpr std::string_view kName = "opensees_adapter";
  static constexpr std::string_view kSummary = "a remote OpenSees model through its adapter element";
  // A site listed in the test's opensees_sites: first in the list, whatever the transport.
  static bool serves(const TestConfig& test, const SiteSetup& setup) {
    return test.opensees_site(setup.site_id) != nullptr;
  }
  // Not real-time safe.
  static std::unique_ptr<Site> make(const TestConfig& test, const SiteSetup& setup, SiteResources& shared);

  transport::Link& link() override { return *link_; }
  // Before any answer: the substructure's stiffness estimate times the hold position.
  double initial_force_n(std::size_t i) const override { return initial_force_n_[i]; }
  std::string failure() const override { return link_->failure(); }
  void end_run() override { link_->end_run(); }

 private:
  OpenSeesAdapterSite(std::unique_ptr<opensees::AdapterLink> link, std::vector<double> initial_force_n)
      : link_(std::move(link)), initial_force_n_(std::move(initial_force_n)) {}

  std::unique_ptr<opensees::AdapterLink> link_;
  std::vector<double> initial_force_n_;
};

}  // namespace rpsd::hybrid_test
