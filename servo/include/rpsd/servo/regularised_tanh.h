// tanh for the friction law of the plant, which evaluates it 32 times per control step on the
// longest chain of dependent operations of each RK4 stage: std::tanh costs about twice the
// exponential it is built on. Within 2 ulps of std::tanh (tested). Real-time safe.
#pragma once

#include <cmath>

namespace rpsd::servo {

/// tanh(x): exactly +-1 where tanh rounds to +-1 in double precision (|x| > 19.07),
/// 1 - 2 / (e^{2|x|} + 1) from 0.55 on, and std::tanh below that, where the exponential form
/// would cancel (rarely reached: the friction's regularisation band is narrow).
inline double regularised_tanh(double x) {
  const double a = std::abs(x);
  if (a > 19.1) return std::copysign(1.0, x);
  if (a < 0.55) return std::tanh(x);
  return std::copysign(1.0 - 2.0 / (std::exp(2.0 * a) + 1.0), x);
}

}  // namespace rpsd::servo
