#include "rpsd/integrators/factory.h"

#include <algorithm>
#include <cctype>
#include <type_traits>

namespace rpsd::integrators {
namespace {

template <class P>
constexpr bool kHasAliases = requires {
  P::aliases();
};

std::string normalized(std::string_view spelling) {
  std::string s(spelling);
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return c == '-' ? '_' : static_cast<char>(std::tolower(c)); });
  return s;
}

}  // namespace

std::optional<IntegratorConfig> default_integrator_config(std::string_view name) {
  std::optional<IntegratorConfig> result;
  IntegratorKinds::for_each([&](auto kind) {
    using P = typename decltype(kind)::type;
    if (name == P::kName) result = P{};
  });
  return result;
}

std::optional<IntegratorConfig> integrator_from_spelling(std::string_view spelling) {
  const std::string n = normalized(spelling);
  std::optional<IntegratorConfig> result;
  IntegratorKinds::for_each([&](auto kind) {
    using P = typename decltype(kind)::type;
    if (result) return;
    if (n == P::kName) {
      result = P{};
      return;
    }
    if constexpr (kHasAliases<P>) {
      for (const auto& [alias, parameters] : P::aliases())
        if (n == alias) result = parameters;
    }
  });
  return result;
}

std::vector<std::string_view> integrator_aliases() {
  std::vector<std::string_view> names;
  IntegratorKinds::for_each([&](auto kind) {
    using P = typename decltype(kind)::type;
    if constexpr (kHasAliases<P>)
      for (const auto& alias : P::aliases()) names.push_back(alias.first);
  });
  return names;
}

std::unique_ptr<Integrator> make_integrator(const IntegratorConfig& config) {
  return std::visit(
      [](const auto& p) -> std::unique_ptr<Integrator> {
        return std::make_unique<typename std::decay_t<decltype(p)>::Integrator>(p);
      },
      config);
}

}  // namespace rpsd::integrators
