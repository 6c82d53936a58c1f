// The time-history CSVs are written by a fast formatter; it must write every number exactly
// as printf("%.10g") does.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>
#include <string>

#include "rpsd/output/csv_number.h"

namespace rpsd::output {
namespace {

std::string printf_g10(double v) {
  char text[64];
  std::snprintf(text, sizeof text, "%.10g", v);
  return text;
}

std::string fast_g10(double v) {
  char text[kG10MaxChars + 1];
  *format_g10(text, v) = '\0';
  return text;
}

TEST(CsvNumber, WritesWhatPrintfWritesForEdgeCases) {
  const double cases[] = {0.0,
                          -0.0,
                          1.0,
                          -1.0,
                          0.5,
                          100.0,
                          1e9,
                          9999999999.0,
                          9999999999.5,
                          9999999999.4,
                          1e10,
                          1e-13,
                          1e-4,
                          9.99999999995e-5,
                          0.0001,
                          0.00012345678905,
                          123456789.25,
                          123456789.75,
                          123456789.35,
                          1234567890.5,
                          1234567891.5,
                          2.5,
                          1.00000000005,
                          0.30000000000000004,
                          std::numeric_limits<double>::min(),
                          std::numeric_limits<double>::denorm_min(),
                          std::numeric_limits<double>::max(),
                          std::numeric_limits<double>::infinity(),
                          -std::numeric_limits<double>::infinity(),
                          std::nan(""),
                          700.8e3,
                          7080.0,
                          0.011,
                          -4.42693672067428e-05};
  for (double v : cases) EXPECT_EQ(fast_g10(v), printf_g10(v)) << v;
  // Every exact tie at the eleventh digit in [1e9, 1e10): round half to even.
  for (double base = 1e9; base < 1e10; base += 987654321.0) {
    for (double frac : {0.5, 1.5, 2.5})
      EXPECT_EQ(fast_g10(std::floor(base) + frac), printf_g10(std::floor(base) + frac));
  }
}

TEST(CsvNumber, WritesWhatPrintfWritesForMillionsOfSeededValues) {
  std::mt19937_64 random(20261121);
  std::uniform_real_distribution<double> mantissa(1.0, 10.0);
  std::uniform_int_distribution<int> decade(-16, 12);
  long mismatches = 0;
  for (int i = 0; i < 1000000; ++i) {
    double v = 0.0;
    switch (i % 4) {
      case 0:
        v = mantissa(random) * std::pow(10.0, decade(random));
        break;   // every decade
      case 1: {  // any bit pattern
        const std::uint64_t b = random();
        std::memcpy(&v, &b, sizeof v);
        break;
      }
      case 2:
        v = std::nextafter(std::pow(10.0, decade(random)), (i & 8) ? 0.0 : 1e300);
        break;  // around powers of ten
      default:
        v = std::round(mantissa(random) * 1e10) / 1e10 * std::pow(10.0, decade(random));
        break;  // short decimals
    }
    if (i & 16) v = -v;
    if (fast_g10(v) != printf_g10(v) && ++mismatches < 10)
      ADD_FAILURE() << printf_g10(v) << " written as " << fast_g10(v);
  }
  EXPECT_EQ(mismatches, 0);
}

}  // namespace
}  // namespace rpsd::output
