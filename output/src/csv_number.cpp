#include "rpsd/output/csv_number.h"

#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>

namespace rpsd::output {
namespace {

__extension__ typedef unsigned __int128 Uint128;

constexpr std::array<Uint128, 23> kPowersOfTen = [] {
  std::array<Uint128, 23> p{};
  p[0] = 1;
  for (std::size_t i = 1; i < p.size(); ++i) p[i] = p[i - 1] * 10;
  return p;
}();

constexpr std::uint64_t kTenDigitsLow = 1000000000;    // 10^9
constexpr std::uint64_t kTenDigitsHigh = 10000000000;  // 10^10

char* fallback(char* out, double v) {
  return std::to_chars(out, out + kG10MaxChars, v, std::chars_format::general, 10).ptr;
}

}  // namespace

char* format_g10(char* out, double v) {
  // |v| = m 2^e exactly. In range, the ten significant digits are N = round(|v| 10^q) with
  // q = 9 - E, E the decimal exponent: m 10^q < 2^53 10^22 < 2^127 and the shift 2^-e is at
  // most 2^96, so 128-bit integers hold every product and remainder exactly.
  const double magnitude = std::abs(v);
  if (!(magnitude >= 1e-13 && magnitude < 1e10)) return fallback(out, v);
  const auto bits = std::bit_cast<std::uint64_t>(magnitude);
  const std::uint64_t m = (bits & ((std::uint64_t{1} << 52) - 1)) | (std::uint64_t{1} << 52);
  const int shift = 1075 - static_cast<int>(bits >> 52);  // |v| = m / 2^shift, 20 <= shift <= 96
  // E is floor(log10 |v|); the binary exponent puts it at one of two values.
  const int binary_exponent = 52 - shift;  // floor(log2 |v|)
  int exponent = std::min(9, static_cast<int>(std::floor((binary_exponent + 1) * 0.30102999566398120)));
  int q = 9 - exponent;
  Uint128 scaled = static_cast<Uint128>(m) * kPowersOfTen[static_cast<std::size_t>(q)];
  if (scaled < (static_cast<Uint128>(kTenDigitsLow) << shift)) {
    --exponent;
    ++q;
    scaled = static_cast<Uint128>(m) * kPowersOfTen[static_cast<std::size_t>(q)];
  }
  auto digits = static_cast<std::uint64_t>(scaled >> shift);
  const Uint128 remainder = scaled - (static_cast<Uint128>(digits) << shift);
  const Uint128 half = static_cast<Uint128>(1) << (shift - 1);
  if (remainder > half || (remainder == half && (digits & 1) != 0)) ++digits;
  if (digits == kTenDigitsHigh) {
    digits = kTenDigitsLow;
    ++exponent;
  }

  char d[10];
  for (int i = 9; i >= 0; --i) {
    d[i] = static_cast<char>('0' + digits % 10);
    digits /= 10;
  }
  int significant = 10;  // %g drops trailing zeros
  while (significant > 1 && d[significant - 1] == '0') --significant;

  if (v < 0.0) *out++ = '-';
  if (exponent >= -4 && exponent < 10) {
    // Fixed notation with 9 - exponent decimals.
    if (exponent < 0) {
      *out++ = '0';
      *out++ = '.';
      for (int i = -1; i > exponent; --i) *out++ = '0';
      for (int i = 0; i < significant; ++i) *out++ = d[i];
    } else {
      for (int i = 0; i <= exponent; ++i) *out++ = d[i];
      if (significant > exponent + 1) {
        *out++ = '.';
        for (int i = exponent + 1; i < significant; ++i) *out++ = d[i];
      }
    }
    return out;
  }
  // Exponential notation: d.ddddddddde-XX (the range keeps the exponent to two digits).
  *out++ = d[0];
  if (significant > 1) {
    *out++ = '.';
    for (int i = 1; i < significant; ++i) *out++ = d[i];
  }
  *out++ = 'e';
  *out++ = exponent < 0 ? '-' : '+';
  const int e = exponent < 0 ? -exponent : exponent;
  *out++ = static_cast<char>('0' + e / 10);
  *out++ = static_cast<char>('0' + e % 10);
  return out;
}

}  // namespace rpsd::output
