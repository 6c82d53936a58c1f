#pragma once
// Implicit Newmark beta-gamma with a fixed number of iterations per step.
// Unconditionally stable for 2 beta >= gamma >= 1/2; otherwise (gamma >= 1/2) stable
// for omega dt <= (gamma/2 - beta)^(-1/2), e.g. 2 sqrt(3) for linear acceleration.
#include <string>

#include "rpsd/integrators/fixed_iteration_implicit_engine.h"
#include "rpsd/integrators/integrator_kind.h"

namespace rpsd::integrators {

class Newmark;

struct NewmarkParameters {
  static constexpr std::string_view kName = "newmark";
  static constexpr std::string_view kSummary = "implicit Newmark (average acceleration), fixed iterations per step";
  using Integrator = Newmark;
  static NewmarkParameters read(config::Source&) { return {}; }
  static Aliases<NewmarkParameters> aliases();
  std::string describe() const;

  double beta = 0.25;
  double gamma = 0.5;
  FixedIterationOptions fixed_iteration{};

  static NewmarkParameters average_acceleration() { return {0.25, 0.5, {}}; }
  static NewmarkParameters linear_acceleration() { return {1.0 / 6.0, 0.5, {}}; }
};
using NewmarkParams [[deprecated("renamed NewmarkParameters (docs/migration.md)")]] = NewmarkParameters;

// Throws std::invalid_argument unless beta > 0, gamma >= 1/2 and the options are valid.
void validate(const NewmarkParameters& p);
// (gamma/2 - beta)^(-1/2) when 2 beta < gamma, +infinity otherwise.
double newmark_stability_limit(double beta, double gamma);

class Newmark final : public FixedIterationImplicitEngine {
 public:
  explicit Newmark(const NewmarkParameters& p = {});
  SchemeInfo info() const override;

 private:
  NewmarkParameters p_;
};

}  // namespace rpsd::integrators
