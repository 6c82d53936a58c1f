#pragma once
// A story spring of a shear building: one of the spring laws, held by value (no per-spring
// heap object, no virtual call). Every law is registered in one place, the list below: a new
// one is its own header and source (its config naming itself with kName, reading its keys
// with read() and naming the Spring it configures) plus one entry here (CONTRIBUTING.md).

#include "rpsd/config/kind_list.h"
#include "rpsd/substructure/bilinear_spring.h"
#include "rpsd/substructure/bouc_wen_spring.h"
#include "rpsd/substructure/linear_spring.h"

#include <variant>

namespace rpsd::substructure {

using StorySpringKinds = config::KindList<LinearSpringParameters, BilinearSpringParameters, BoucWenSpringParameters>;
using StorySpringConfig = StorySpringKinds::Variant;

// The spring laws of a list of configs, by value.
template <class List>
struct SpringLaws;
template <class... Configs>
struct SpringLaws<config::KindList<Configs...>> {
  using type = std::variant<typename Configs::Spring...>;
};
using StorySpringLaw = SpringLaws<StorySpringKinds>::type;

class StorySpring {
 public:
  // Throws std::invalid_argument on bad parameters. Not real-time safe.
  explicit StorySpring(const StorySpringConfig& config);

  // Real-time safe.
  double trial(double drift_m) noexcept {
    return std::visit([drift_m](auto& s) { return s.trial(drift_m); }, law_);
  }
  void commit() noexcept {
    std::visit([](auto& s) { s.commit(); }, law_);
  }
  [[nodiscard]] double initial_stiffness() const noexcept {
    return std::visit([](const auto& s) { return s.initial_stiffness(); }, law_);
  }
  [[nodiscard]] double tangent_stiffness() const noexcept {
    return std::visit([](const auto& s) { return s.tangent_stiffness(); }, law_);
  }
  [[nodiscard]] double committed_deformation() const noexcept {
    return std::visit([](const auto& s) { return s.committed_deformation(); }, law_);
  }
  [[nodiscard]] double committed_force() const noexcept {
    return std::visit([](const auto& s) { return s.committed_force(); }, law_);
  }
  // The concrete law, for recording its internal variables.
  [[nodiscard]] const StorySpringLaw& law() const noexcept { return law_; }

 private:
  StorySpringLaw law_;
};

}  // namespace rpsd::substructure
