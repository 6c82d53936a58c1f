// The one place where a module registers the kinds of one thing (compensators, plants,
// actuators): a list of parameter types, each naming itself and reading its own keys.
//
//   struct MyParameters {
//     static constexpr std::string_view kName = "my_kind";  // `kind:` in the file
//     static constexpr std::string_view kSummary = "one line for the reference";
//     static MyParameters read(config::Source& section, ...);  // the section's other keys
//   };
//   using MyConfig = config::KindList<A, B, MyParameters>::Variant;
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <variant>
#include <vector>

#include "rpsd/config/source.h"

namespace rpsd::config {

template <class... Kinds>
struct KindList {
  using Variant = std::variant<Kinds...>;

  static std::vector<std::string_view> names() { return {Kinds::kName...}; }

  // The kind named `name` read from `section` (extra arguments go to its read()); nullopt
  // when no kind has that name.
  template <class... Args>
  static std::optional<Variant> read(std::string_view name, Source& section, Args&&... args) {
    std::optional<Variant> result;
    ((name == Kinds::kName ? (void)(result.emplace(Kinds::read(section, args...))) : void()), ...);
    return result;
  }

  // f(std::type_identity<Kind>{}) for every kind, in order.
  template <class F>
  static void for_each(F&& f) {
    (f(std::type_identity<Kinds>{}), ...);
  }
};

// The name of the kind a variant holds.
template <class Variant>
std::string_view kind_name(const Variant& value) noexcept {
  return std::visit([](const auto& p) { return std::decay_t<decltype(p)>::kName; }, value);
}

// "a, b or c"
inline std::string listed(const std::vector<std::string_view>& names) {
  std::string text;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) text += i + 1 == names.size() ? " or " : ", ";
    text += names[i];
  }
  return text;
}

}  // namespace rpsd::config
