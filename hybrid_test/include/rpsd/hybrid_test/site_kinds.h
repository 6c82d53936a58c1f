// The kinds of site a test reaches its channels through, registered in one place (the list
// below): a new kind (another controller protocol, a multi-actuator rig) is its own files (a
// Site naming itself with kName, saying which sites it serves() and building one with make())
// plus one entry here (docs/architecture.md, "Adding a site kind"). The first kind in the
// list that serves a site builds it, so a catch-all kind comes last.
#pragma once

#include <memory>

#include "rpsd/config/kind_list.h"
#include "rpsd/hybrid_test/dds_site.h"
#include "rpsd/hybrid_test/in_process_site.h"
#include "rpsd/hybrid_test/opensees_adapter_site.h"

namespace rpsd::hybrid_test {

using SiteKinds = config::KindList<OpenSeesAdapterSite, DdsSite, InProcessSite>;

// Completes the setup (SiteSetup::complete: the rig's defaults) and builds the site with the
// first kind that serves it. Not real-time safe; throws what completing or building throws.
std::unique_ptr<Site> make_site(const TestConfig& test, SiteSetup& setup, SiteResources& shared);

}  // namespace rpsd::hybrid_test
