#include "rpsd/ground_motion/deterministic_math.h"

#include <cmath>
#include <limits>

#include "no_fp_contract.h"

namespace rpsd::ground_motion::deterministic {
namespace {

// ln 2 split so that k * kLn2Hi is exact for |k| < 2^11 (fdlibm's constants).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kInvLn2 = 1.44269504088896338700e+00;
constexpr double kSqrtHalf = 0.70710678118654752440;
constexpr double kHalfPi = 1.57079632679489661923;

}  // namespace

double exp(double x) noexcept {
  if (std::isnan(x)) return x;
  if (x > 709.782712893384) return std::numeric_limits<double>::infinity();
  if (x < -745.1332191019412) return 0.0;
  // x = k ln2 + r with |r| <= ln2 / 2; e^r by its Taylor series to r^14 / 14!.
  const double k = std::floor(x * kInvLn2 + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  constexpr int terms = 14;
  double p = 1.0;
  for (int j = terms; j >= 1; --j) p = 1.0 + p * r / static_cast<double>(j);
  return std::ldexp(p, static_cast<int>(k));
}

double log(double x) noexcept {
  if (std::isnan(x) || x < 0.0) return std::numeric_limits<double>::quiet_NaN();
  if (x == 0.0) return -std::numeric_limits<double>::infinity();
  if (std::isinf(x)) return x;
  int e = 0;
  double m = std::frexp(x, &e);  // exact: x = m 2^e, m in [0.5, 1)
  if (m < kSqrtHalf) {
    m *= 2.0;
    --e;
  }
  // log m = 2 atanh(s), s = (m - 1) / (m + 1), |s| <= 0.1716: series to s^27.
  const double s = (m - 1.0) / (m + 1.0);
  const double s2 = s * s;
  constexpr int terms = 13;
  double p = 1.0 / (2.0 * terms + 1.0);
  for (int k = terms - 1; k >= 0; --k) p = p * s2 + 1.0 / (2.0 * k + 1.0);
  const double de = static_cast<double>(e);
  return de * kLn2Hi + (de * kLn2Lo + 2.0 * s * p);
}

void sincos_2pi(double u, double& sine, double& cosine) noexcept {
  // 2 pi u = q pi/2 + x with q the nearest integer to 4u (4u - q is exact), |x| <= pi/4.
  const double four_u = 4.0 * u;
  const double q = std::floor(four_u + 0.5);
  const double x = (four_u - q) * kHalfPi;
  const double x2 = x * x;
  // Taylor series to x^17 (sin) and x^16 (cos): remainder below 2e-18 for |x| <= pi/4.
  double s = 1.0;
  for (int j = 17; j >= 3; j -= 2) s = 1.0 - s * x2 / static_cast<double>(j * (j - 1));
  s *= x;
  double c = 1.0;
  for (int j = 16; j >= 2; j -= 2) c = 1.0 - c * x2 / static_cast<double>(j * (j - 1));
  switch (static_cast<long long>(q) & 3) {
    case 0:
      sine = s;
      cosine = c;
      break;
    case 1:
      sine = c;
      cosine = -s;
      break;
    case 2:
      sine = -s;
      cosine = -c;
      break;
    default:
      sine = -c;
      cosine = s;
      break;
  }
}

}  // namespace rpsd::ground_motion::deterministic
