// Every integrator rpsd knows, registered in one place (the list below): a new scheme is its
// own header and source (its parameters naming themselves with kName, reading their keys with
// read(), describing themselves and naming the Integrator they configure) plus one entry here
// (CONTRIBUTING.md). The scenario reader, the studies, `rpsd analyze integrator`, the scenario
// reference and the summaries follow from the list.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/config/kind_list.h"
#include "rpsd/integrators/alpha_os.h"
#include "rpsd/integrators/central_difference.h"
#include "rpsd/integrators/chang.h"
#include "rpsd/integrators/chen_ricles.h"
#include "rpsd/integrators/generalized_alpha.h"
#include "rpsd/integrators/hht_alpha.h"
#include "rpsd/integrators/integrator.h"
#include "rpsd/integrators/kolay_ricles_alpha.h"
#include "rpsd/integrators/newmark.h"

namespace rpsd::integrators {

using IntegratorKinds =
    config::KindList<CentralDifferenceParameters, NewmarkParameters, HhtAlphaParameters, GeneralizedAlphaParameters,
                     AlphaOsParameters, ChangParameters, ChenRiclesParameters, KolayRiclesAlphaParameters>;
using IntegratorConfig = IntegratorKinds::Variant;

// The scheme's stable lower-case name (its kName): central_difference, newmark, ...
inline std::string_view integrator_name(const IntegratorConfig& config) noexcept { return config::kind_name(config); }

// The scheme named `name` with its default parameters; nullopt for no scheme of that name.
std::optional<IntegratorConfig> default_integrator_config(std::string_view name);

// The scheme a command-line spelling names, with the parameters the spelling stands for:
// a kName or an alias, - and _ alike, any case. nullopt for none.
std::optional<IntegratorConfig> integrator_from_spelling(std::string_view spelling);
// Every alias, in the list's order (for messages).
std::vector<std::string_view> integrator_aliases();

// Not real-time safe. Validates the parameters (throws std::invalid_argument).
std::unique_ptr<Integrator> make_integrator(const IntegratorConfig& config);

// Human-readable parameter summary, e.g. "rho_inf=0.8".
inline std::string describe(const IntegratorConfig& config) {
  return std::visit([](const auto& p) { return p.describe(); }, config);
}

}  // namespace rpsd::integrators
