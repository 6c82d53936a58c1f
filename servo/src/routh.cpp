#include "rpsd/servo/routh.h"

#include <stdexcept>
#include <vector>

namespace rpsd::servo {

bool routh_hurwitz_stable(const Polynomial& characteristic) {
  const int n = characteristic.degree();
  if (n < 1) return true;
  // Rows of the Routh array in descending powers.
  std::vector<double> above, current;
  for (int p = n; p >= 0; p -= 2) above.push_back(characteristic.coefficient(p));
  for (int p = n - 1; p >= 0; p -= 2) current.push_back(characteristic.coefficient(p));
  const double leading_sign = characteristic.coefficient(n) > 0.0 ? 1.0 : -1.0;
  if (above[0] * leading_sign <= 0.0) return false;
  for (int row = 1; row <= n; ++row) {
    if (current.empty() || current[0] * leading_sign <= 0.0) return false;
    std::vector<double> next;
    for (std::size_t j = 0; j + 1 < above.size(); ++j) {
      const double b = j + 1 < current.size() ? current[j + 1] : 0.0;
      next.push_back((current[0] * above[j + 1] - above[0] * b) / current[0]);
    }
    above = std::move(current);
    current = std::move(next);
  }
  return true;
}

double largest_stable_gain(const std::function<bool(double)>& stable, double upper_bound, double relative_tolerance) {
  double low = upper_bound * 1e-9;
  if (!stable(low)) throw std::domain_error("largest_stable_gain: unstable even at a vanishing gain");
  double high = upper_bound;
  if (stable(high)) return upper_bound;
  while ((high - low) > relative_tolerance * high) {
    const double middle = 0.5 * (low + high);
    (stable(middle) ? low : high) = middle;
  }
  return low;
}

}  // namespace rpsd::servo
