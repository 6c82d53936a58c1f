#include "rpsd/studies/line_fit.h"

#include <cstddef>

namespace rpsd::studies {

double least_squares_slope(std::span<const double> x, std::span<const double> y) {
  if (x.size() < 2) return 0.0;
  const auto n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  const double d = n * sxx - sx * sx;
  return d != 0.0 ? (n * sxy - sx * sy) / d : 0.0;
}

}  // namespace rpsd::studies
