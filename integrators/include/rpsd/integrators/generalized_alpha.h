#pragma once
// Generalized-alpha (Chung & Hulbert 1993) with a fixed number of iterations per step:
//   (1-am) M a+ + am M a + (1-af)(C v+ + R+) + af (C v + R) = (1-af) F+ + af F
//   am = (2 rho_inf - 1)/(rho_inf + 1), af = rho_inf/(rho_inf + 1),
//   gamma = 1/2 - am + af, beta = (1 - am + af)^2 / 4 = 1/(1 + rho_inf)^2.
#include <string>

#include "rpsd/integrators/fixed_iteration_implicit_engine.h"
#include "rpsd/integrators/integrator_kind.h"

namespace rpsd::integrators {

class GeneralizedAlpha;

struct GeneralizedAlphaParameters {
  static constexpr std::string_view kName = "generalized_alpha";
  static constexpr std::string_view kSummary = "generalized-alpha (Chung & Hulbert), fixed iterations per step";
  using Integrator = GeneralizedAlpha;
  static GeneralizedAlphaParameters read(config::Source& section);  // rho_inf
  static Aliases<GeneralizedAlphaParameters> aliases() { return {{"ga", {}}}; }
  std::string describe() const;

  double rho_inf = 0.8;
  FixedIterationOptions fixed_iteration{};
};
using GeneralizedAlphaParams [[deprecated("renamed GeneralizedAlphaParameters (docs/migration.md)")]] =
    GeneralizedAlphaParameters;

// The Chung-Hulbert parameter set for a spectral radius at infinity rho_inf.
struct AlphaParameters {
  double alpha_m, alpha_f, gamma, beta;
};
// Throws std::invalid_argument unless rho_inf in [0, 1].
AlphaParameters chung_hulbert_parameters(double rho_inf);

void validate(const GeneralizedAlphaParameters& p);

class GeneralizedAlpha final : public FixedIterationImplicitEngine {
 public:
  explicit GeneralizedAlpha(const GeneralizedAlphaParameters& p = {});
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
