#include "rpsd/hybrid_test/site_kinds.h"

namespace rpsd::hybrid_test {

std::unique_ptr<Site> make_site(const TestConfig& test, SiteSetup& setup, SiteResources& shared) {
  setup.complete(test);
  std::unique_ptr<Site> site;
  SiteKinds::for_each([&]<class Kind>(std::type_identity<Kind>) {
    if (!site && Kind::serves(test, setup)) site = Kind::make(test, setup, shared);
  });
  return site;
}

}  // namespace rpsd::hybrid_test
