// Private helpers for configure-time checks with precise messages.
#pragma once

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rpsd::compensation::detail {

// A number as the user would write it (1e-06, not 0.000001; std::to_string prints 0.000000).
inline std::string number(double value) {
  std::ostringstream s;
  s.precision(15);
  s << value;
  return s.str();
}

// Throws std::invalid_argument("<what>: <requirement>, got <value>").
[[noreturn]] inline void fail(const std::string& what, const std::string& requirement, double value) {
  std::ostringstream s;
  s.precision(17);
  s << what << ": " << requirement << ", got " << value;
  throw std::invalid_argument(s.str());
}

inline void require_positive(const std::string& what, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) fail(what, "must be positive and finite", value);
}

inline void require_non_negative(const std::string& what, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) fail(what, "must be >= 0 and finite", value);
}

inline void require_finite(const std::string& what, double value) {
  if (!std::isfinite(value)) fail(what, "must be finite", value);
}

}  // namespace rpsd::compensation::detail
