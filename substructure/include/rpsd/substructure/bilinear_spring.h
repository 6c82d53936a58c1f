#pragma once
// Bilinear elastic-plastic spring with linear kinematic hardening.
//
// Elastic stiffness k0, yield force fy, post-yield stiffness α k0. The elastic range has a
// constant width 2 fy and translates with the back force q (kinematic hardening), so the
// loops are parallelograms: unloading and reloading have slope k0, yielding has slope α k0.
// The update is the 1-D return mapping with plastic modulus H = α k0 / (1 − α); it is exact
// for any increment size because every branch is linear.

#include <string_view>

#include "rpsd/config/source.h"

namespace rpsd::substructure {

class BilinearSpring;

struct BilinearSpringParameters {
  static constexpr std::string_view kName = "bilinear";
  static constexpr std::string_view kSummary = "elastic-plastic with linear kinematic hardening";
  using Spring = BilinearSpring;
  static BilinearSpringParameters read(config::Source& section);
  static BilinearSpringParameters example() { return {5.0e7, 5.0e5, 0.05}; }  // yields at 1 cm

  double stiffness_n_per_m = 0.0;  // k0 > 0
  double yield_force_n = 0.0;      // fy > 0
  double post_yield_ratio = 0.0;   // α in [0, 1); 0 is elastic-perfectly-plastic
};
using BilinearSpringConfig [[deprecated("renamed BilinearSpringParameters (docs/migration.md)")]] =
    BilinearSpringParameters;

class BilinearSpring {
 public:
  // Throws std::invalid_argument naming the bad parameter. Not real-time safe.
  explicit BilinearSpring(const BilinearSpringParameters& config);

  // Force at trial deformation u, from the committed state. Real-time safe.
  double trial(double deformation_m) noexcept;
  // Accepts the last trial. Real-time safe.
  void commit() noexcept;

  [[nodiscard]] double initial_stiffness() const noexcept { return k0_; }
  // k0 if the last trial stayed elastic, α k0 if it yielded. Real-time safe.
  [[nodiscard]] double tangent_stiffness() const noexcept { return trial_.tangent; }
  [[nodiscard]] double committed_deformation() const noexcept { return committed_.u; }
  [[nodiscard]] double committed_force() const noexcept { return committed_.force; }
  [[nodiscard]] double committed_plastic_deformation() const noexcept { return committed_.u_plastic; }

 private:
  struct State {
    double u = 0.0;
    double u_plastic = 0.0;
    double back_force = 0.0;
    double force = 0.0;
    double tangent = 0.0;
  };
  double k0_, fy_, alpha_, H_;
  State committed_, trial_;
};

}  // namespace rpsd::substructure
