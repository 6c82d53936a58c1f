#include "rpsd/integrators/factory.h"

#include <array>
#include <sstream>
#include <type_traits>
#include <utility>

namespace rpsd::integrators {
namespace {
template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

constexpr std::array<std::pair<Scheme, std::string_view>, 8> kNames{{
    {Scheme::kCentralDifference, "central_difference"},
    {Scheme::kNewmark, "newmark"},
    {Scheme::kHhtAlpha, "hht_alpha"},
    {Scheme::kGeneralizedAlpha, "generalized_alpha"},
    {Scheme::kAlphaOs, "alpha_os"},
    {Scheme::kChang, "chang"},
    {Scheme::kChenRicles, "chen_ricles"},
    {Scheme::kKolayRiclesAlpha, "kolay_ricles_alpha"},
}};
}  // namespace

Scheme scheme_of(const IntegratorConfig& config) {
  return std::visit(Overloaded{
                        [](const CentralDifferenceParams&) { return Scheme::kCentralDifference; },
                        [](const NewmarkParams&) { return Scheme::kNewmark; },
                        [](const HhtAlphaParams&) { return Scheme::kHhtAlpha; },
                        [](const GeneralizedAlphaParams&) { return Scheme::kGeneralizedAlpha; },
                        [](const AlphaOsParams&) { return Scheme::kAlphaOs; },
                        [](const ChangParams&) { return Scheme::kChang; },
                        [](const ChenRiclesParams&) { return Scheme::kChenRicles; },
                        [](const KolayRiclesAlphaParams&) { return Scheme::kKolayRiclesAlpha; },
                    },
                    config);
}

std::string_view scheme_name(Scheme scheme) {
  for (const auto& [s, name] : kNames)
    if (s == scheme) return name;
  return "unknown";
}

std::optional<Scheme> parse_scheme(std::string_view name) {
  for (const auto& [s, n] : kNames)
    if (n == name) return s;
  return std::nullopt;
}

std::vector<std::string_view> scheme_names() {
  std::vector<std::string_view> names;
  for (const auto& [s, name] : kNames) names.push_back(name);
  return names;
}

std::unique_ptr<Integrator> make_integrator(const IntegratorConfig& config) {
  return std::visit(
      [](const auto& p) -> std::unique_ptr<Integrator> {
        using P = std::decay_t<decltype(p)>;
        if constexpr (std::is_same_v<P, CentralDifferenceParams>)
          return std::make_unique<CentralDifference>(p);
        else if constexpr (std::is_same_v<P, NewmarkParams>)
          return std::make_unique<Newmark>(p);
        else if constexpr (std::is_same_v<P, HhtAlphaParams>)
          return std::make_unique<HhtAlpha>(p);
        else if constexpr (std::is_same_v<P, GeneralizedAlphaParams>)
          return std::make_unique<GeneralizedAlpha>(p);
        else if constexpr (std::is_same_v<P, AlphaOsParams>)
          return std::make_unique<AlphaOs>(p);
        else if constexpr (std::is_same_v<P, ChangParams>)
          return std::make_unique<Chang>(p);
        else if constexpr (std::is_same_v<P, ChenRiclesParams>)
          return std::make_unique<ChenRicles>(p);
        else
          return std::make_unique<KolayRiclesAlpha>(p);
      },
      config);
}

std::string describe(const IntegratorConfig& config) {
  std::ostringstream s;
  auto iter = [&s](const FixedIterationOptions& o) {
    s << " iterations=" << o.iterations << " poly_order=" << o.poly_order;
  };
  std::visit(Overloaded{
                 [&](const CentralDifferenceParams&) { s << "beta=0 gamma=0.5"; },
                 [&](const NewmarkParams& p) {
                   s << "beta=" << p.beta << " gamma=" << p.gamma;
                   iter(p.fixed_iteration);
                 },
                 [&](const HhtAlphaParams& p) {
                   s << "alpha=" << p.alpha;
                   iter(p.fixed_iteration);
                 },
                 [&](const GeneralizedAlphaParams& p) {
                   s << "rho_inf=" << p.rho_inf;
                   iter(p.fixed_iteration);
                 },
                 [&](const AlphaOsParams& p) { s << "alpha=" << p.alpha; },
                 [&](const ChangParams&) { s << "(none)"; },
                 [&](const ChenRiclesParams&) { s << "(none)"; },
                 [&](const KolayRiclesAlphaParams& p) { s << "rho_inf=" << p.rho_inf; },
             },
             config);
  return s.str();
}

}  // namespace rpsd::integrators
