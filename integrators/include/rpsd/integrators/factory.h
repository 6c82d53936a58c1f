#pragma once
// Typed configuration of a scheme (which scheme plus its parameters) and the factory.
#include "rpsd/integrators/alpha_os.h"
#include "rpsd/integrators/central_difference.h"
#include "rpsd/integrators/chang.h"
#include "rpsd/integrators/chen_ricles.h"
#include "rpsd/integrators/generalized_alpha.h"
#include "rpsd/integrators/hht_alpha.h"
#include "rpsd/integrators/integrator.h"
#include "rpsd/integrators/kolay_ricles_alpha.h"
#include "rpsd/integrators/newmark.h"

#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace rpsd::integrators {

using IntegratorConfig = std::variant<CentralDifferenceParams, NewmarkParams, HhtAlphaParams, GeneralizedAlphaParams,
                                      AlphaOsParams, ChangParams, ChenRiclesParams, KolayRiclesAlphaParams>;

Scheme scheme_of(const IntegratorConfig& config);
// Stable lower-case name: central_difference, newmark, hht_alpha, ...
std::string_view scheme_name(Scheme scheme);
std::optional<Scheme> parse_scheme(std::string_view name);
// Every scheme's name, in the order above (for messages listing them).
std::vector<std::string_view> scheme_names();

// Not real-time safe. Validates the parameters (throws std::invalid_argument).
std::unique_ptr<Integrator> make_integrator(const IntegratorConfig& config);

// Human-readable parameter summary, e.g. "rho_inf=0.8".
std::string describe(const IntegratorConfig& config);

}  // namespace rpsd::integrators
