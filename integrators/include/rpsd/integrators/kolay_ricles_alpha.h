#pragma once
// KR-alpha, the Kolay-Ricles explicit method (2014), rho_inf in [0, 1]; same alpha_m,
// alpha_f, gamma, beta as generalized-alpha, whose eigenvalues it shares on linear systems.
#include <string>

#include "rpsd/integrators/integrator_kind.h"
#include "rpsd/integrators/model_based_explicit_engine.h"

namespace rpsd::integrators {

class KolayRiclesAlpha;

struct KolayRiclesAlphaParameters {
  static constexpr std::string_view kName = "kolay_ricles_alpha";
  static constexpr std::string_view kSummary = "KR-alpha, the Kolay-Ricles explicit method";
  using Integrator = KolayRiclesAlpha;
  static KolayRiclesAlphaParameters read(config::Source& section);  // rho_inf
  static Aliases<KolayRiclesAlphaParameters> aliases() { return {{"kr_alpha", {}}, {"kr", {}}}; }
  std::string describe() const;

  double rho_inf = 0.8;
};
using KolayRiclesAlphaParams [[deprecated("renamed KolayRiclesAlphaParameters (docs/migration.md)")]] =
    KolayRiclesAlphaParameters;

void validate(const KolayRiclesAlphaParameters& p);

class KolayRiclesAlpha final : public ModelBasedExplicitEngine {
 public:
  explicit KolayRiclesAlpha(const KolayRiclesAlphaParameters& p = {});
  SchemeInfo info() const override;
};

}  // namespace rpsd::integrators
