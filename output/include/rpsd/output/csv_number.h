// Numbers in the time-history CSVs, as printf("%.10g") writes them, fast enough for the
// writer thread to keep up with a test running a thousand times faster than real time
// (timings: docs/realtime.md).
#pragma once

namespace rpsd::output {

// Room format_g10 needs: sign, 10 digits, point, exponent.
inline constexpr int kG10MaxChars = 24;

// Writes v exactly as std::printf("%.10g", v) does (round half to even on exact ties) at
// `out`, which has room for kG10MaxChars, and returns the end. Values from 1e-13 to 1e10 in
// magnitude take an exact integer path; others, zero and non-finite values go through
// std::to_chars, which is printf-exact. Real-time safe.
char* format_g10(char* out, double v);

}  // namespace rpsd::output
