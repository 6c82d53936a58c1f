// Routh-Hurwitz stability of a characteristic polynomial, and the largest gain that keeps
// a gain-parametrised characteristic polynomial stable. Not real-time safe.
#pragma once

#include <functional>

#include "rpsd/servo/polynomial.h"

namespace rpsd::servo {

// True when every root has a strictly negative real part (the first column of the Routh
// array has no sign change and no zero).
bool routh_hurwitz_stable(const Polynomial& characteristic);

// Largest g in (0, upper_bound] with `stable(g)` true, assuming stability for small g and a
// single crossing; bisection to a relative tolerance. Returns upper_bound if never unstable.
double largest_stable_gain(const std::function<bool(double)>& stable, double upper_bound,
                           double relative_tolerance = 1e-9);

}  // namespace rpsd::servo
