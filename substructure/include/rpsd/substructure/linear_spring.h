#pragma once
// Linear elastic spring F = k u.

#include <string_view>

#include "rpsd/config/source.h"

namespace rpsd::substructure {

class LinearSpring;

struct LinearSpringParameters {
  static constexpr std::string_view kName = "linear";  // a story's kind in a scenario
  static constexpr std::string_view kSummary = "a linear elastic spring, F = k u";
  using Spring = LinearSpring;
  static LinearSpringParameters read(config::Source& section);
  // A typical story of a laboratory-scale building (the allocation tests run every kind's).
  static LinearSpringParameters example() { return {5.0e7}; }

  double stiffness_n_per_m = 0.0;  // > 0
};
using LinearSpringConfig [[deprecated("renamed LinearSpringParameters (docs/migration.md)")]] = LinearSpringParameters;

class LinearSpring {
 public:
  // Throws std::invalid_argument for a non-positive or non-finite stiffness. Not real-time safe.
  explicit LinearSpring(const LinearSpringParameters& config);

  // Force at trial deformation u (from the committed state). Real-time safe.
  double trial(double deformation_m) noexcept {
    trial_u_ = deformation_m;
    return k_ * deformation_m;
  }
  void commit() noexcept { committed_u_ = trial_u_; }

  [[nodiscard]] double initial_stiffness() const noexcept { return k_; }
  [[nodiscard]] double tangent_stiffness() const noexcept { return k_; }
  [[nodiscard]] double committed_deformation() const noexcept { return committed_u_; }
  [[nodiscard]] double committed_force() const noexcept { return k_ * committed_u_; }

 private:
  double k_;
  double trial_u_ = 0.0;
  double committed_u_ = 0.0;
};

}  // namespace rpsd::substructure
