// What the parameters of every integrator kind share (the kinds are listed once, in
// factory.h): the ranges of the keys they read and how they name the other spellings
// `rpsd analyze integrator` takes.
#pragma once

#include <string_view>
#include <utility>
#include <vector>

#include "rpsd/config/source.h"

namespace rpsd::integrators {

// rho_inf: generalized-alpha's and KR-alpha's spectral radius at infinite frequency.
inline config::Number rho_inf_range() {
  return config::Number::between(0.0, 1.0, "", "spectral radius at infinite frequency");
}
// alpha: HHT-alpha's and alpha-OS's numerical damping.
inline config::Number alpha_range() { return config::Number::between(-1.0 / 3.0, 0.0, "", "numerical damping alpha"); }

// Other spellings of a kind (written with _; - is taken alike), each with the parameters it
// stands for: `static Aliases<P> aliases()` in a kind's parameters, when it has any.
template <class Parameters>
using Aliases = std::vector<std::pair<std::string_view, Parameters>>;

}  // namespace rpsd::integrators
