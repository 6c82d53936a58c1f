#pragma once
// Bouc–Wen hysteretic spring, F = α k0 u + (1 − α) k0 z with dz/du = A − |z|ⁿ (β sgn(du·z) + γ)
// (z in units of displacement, β and γ in 1/mⁿ). Each increment is integrated by RK4 in sub-steps small
// enough that z approaches its bound z_max = (A/(β + γ))^(1/n) without overshooting it; max_substeps caps
// the work per trial for real-time use.
// Derivation and accuracy: docs/substructures.md

#include <string_view>

#include "rpsd/config/source.h"

namespace rpsd::substructure {

class BoucWenSpring;

struct BoucWenSpringParameters {
  static constexpr std::string_view kName = "bouc_wen";
  static constexpr std::string_view kSummary = "Bouc-Wen smooth hysteresis, integrated by RK4 in sub-steps";
  using Spring = BoucWenSpring;
  static BoucWenSpringParameters read(config::Source& section);
  static BoucWenSpringParameters example();  // z_max = 1 cm, n = 2

  double stiffness_n_per_m = 0.0;  // k0 > 0
  double post_yield_ratio = 0.0;   // α in [0, 1)
  double A = 1.0;                  // > 0
  double beta = 0.0;               // [1/mⁿ] ≥ 0
  double gamma = 0.0;              // [1/mⁿ] with β + γ > 0 (so z is bounded and loops dissipate)
  double n = 1.0;                  // ≥ 1 (keeps ∂g/∂z bounded at z = 0)
  double substep_ratio = 0.05;     // h_max · L, in (0, 1]
  int max_substeps = 100;          // ≥ 1
};
using BoucWenSpringConfig [[deprecated("renamed BoucWenSpringParameters (docs/migration.md)")]] =
    BoucWenSpringParameters;

class BoucWenSpring {
 public:
  // Throws std::invalid_argument naming the bad parameter. Not real-time safe.
  explicit BoucWenSpring(const BoucWenSpringParameters& config);

  // Force at trial deformation u, from the committed state. Real-time safe.
  double trial(double deformation_m) noexcept;
  // Accepts the last trial. Real-time safe.
  void commit() noexcept;

  // k0 (α + (1 − α) A).
  [[nodiscard]] double initial_stiffness() const noexcept;
  // dF/du = α k0 + (1 − α) k0 g(z; s) at the last trial, with s the direction of its
  // increment (of the last committed increment when the trial increment is zero).
  [[nodiscard]] double tangent_stiffness() const noexcept { return trial_.tangent; }
  // (A/(β + γ))^(1/n).
  [[nodiscard]] double z_max_m() const noexcept { return z_max_; }

  [[nodiscard]] double committed_deformation() const noexcept { return committed_.u; }
  [[nodiscard]] double committed_force() const noexcept { return committed_.force; }
  [[nodiscard]] double committed_z_m() const noexcept { return committed_.z; }
  [[nodiscard]] double trial_z_m() const noexcept { return trial_.z; }
  // Sub-steps used by the last trial.
  [[nodiscard]] int last_substeps() const noexcept { return last_substeps_; }

 private:
  struct State {
    double u = 0.0;
    double z = 0.0;
    double force = 0.0;
    double tangent = 0.0;
    double direction = 0.0;  // sign of the increment that led here
  };
  [[nodiscard]] double dz_du(double z, double s) const noexcept;

  double k0_, alpha_, A_, beta_, gamma_, n_;
  double z_max_, h_max_;
  int max_substeps_;
  State committed_, trial_;
  int last_substeps_ = 0;
};

}  // namespace rpsd::substructure
