#pragma once
#include <gtest/gtest.h>
#include <string>
// One type per scheme configuration, for the typed test suite that every scheme runs.
#include "rpsd/integrators/factory.h"

#include <cmath>
#include <limits>
#include <string>

namespace rpsd::integrators::test {

struct CentralDifferenceScheme {
  static constexpr const char* name = "central_difference";
  static IntegratorConfig config() { return CentralDifferenceParameters{}; }
  static constexpr double stability_limit = 2.0;
};
struct NewmarkAverageScheme {
  static constexpr const char* name = "newmark_average";
  static IntegratorConfig config() {
    auto p = NewmarkParameters::average_acceleration();
    p.fixed_iteration = {1, 1};
    return p;
  }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct NewmarkLinearScheme {
  static constexpr const char* name = "newmark_linear";
  static IntegratorConfig config() {
    auto p = NewmarkParameters::linear_acceleration();
    p.fixed_iteration = {2, 1};
    return p;
  }
  static inline const double stability_limit = 2.0 * std::sqrt(3.0);
};
struct HhtScheme {
  static constexpr const char* name = "hht_alpha";
  static IntegratorConfig config() { return HhtAlphaParameters{-0.1, {3, 2}}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct GeneralizedAlphaScheme {
  static constexpr const char* name = "generalized_alpha";
  static IntegratorConfig config() { return GeneralizedAlphaParameters{0.8, {2, 3}}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct AlphaOsScheme {
  static constexpr const char* name = "alpha_os";
  static IntegratorConfig config() { return AlphaOsParameters{-1.0 / 6.0}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct ChangScheme {
  static constexpr const char* name = "chang";
  static IntegratorConfig config() { return ChangParameters{}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct ChenRiclesScheme {
  static constexpr const char* name = "chen_ricles";
  static IntegratorConfig config() { return ChenRiclesParameters{}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};
struct KolayRiclesAlphaScheme {
  static constexpr const char* name = "kolay_ricles_alpha";
  static IntegratorConfig config() { return KolayRiclesAlphaParameters{0.5}; }
  static constexpr double stability_limit = std::numeric_limits<double>::infinity();
};

// Every scheme configuration the typed suites run, and readable test names for them.
using Schemes =
    ::testing::Types<CentralDifferenceScheme, NewmarkAverageScheme, NewmarkLinearScheme, HhtScheme,
                     GeneralizedAlphaScheme, AlphaOsScheme, ChangScheme, ChenRiclesScheme, KolayRiclesAlphaScheme>;

class SchemeNames {
 public:
  template <class T>
  static std::string GetName(int) {
    return T::name;
  }
};

}  // namespace rpsd::integrators::test
