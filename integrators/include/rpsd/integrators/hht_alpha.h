#pragma once
// HHT-alpha (Hilber, Hughes & Taylor) with a fixed number of iterations per step:
//   M a+ + (1+alpha)(C v+ + R+) - alpha (C v + R) = (1+alpha) F+ - alpha F,
//   alpha in [-1/3, 0], beta = (1-alpha)^2/4, gamma = (1-2 alpha)/2,
//   rho_inf = (1+alpha)/(1-alpha). Unconditionally stable on linear systems.
#include <string>

#include "rpsd/integrators/fixed_iteration_implicit_engine.h"
#include "rpsd/integrators/integrator_kind.h"

namespace rpsd::integrators {

class HhtAlpha;

struct HhtAlphaParameters {
  static constexpr std::string_view kName = "hht_alpha";
  static constexpr std::string_view kSummary = "HHT-alpha, fixed iterations per step";
  using Integrator = HhtAlpha;
  static HhtAlphaParameters read(config::Source& section);  // alpha
  static Aliases<HhtAlphaParameters> aliases() { return {{"hht", {}}}; }
  std::string describe() const;

  double alpha = -0.1;
  FixedIterationOptions fixed_iteration{};
};
using HhtAlphaParams [[deprecated("renamed HhtAlphaParameters (docs/migration.md)")]] = HhtAlphaParameters;

// Throws std::invalid_argument unless alpha in [-1/3, 0] and the options are valid.
void validate(const HhtAlphaParameters& p);

class HhtAlpha final : public FixedIterationImplicitEngine {
 public:
  explicit HhtAlpha(const HhtAlphaParameters& p = {});
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
