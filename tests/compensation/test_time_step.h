// The time step most compensation tests sample at (1024 Hz), defined once: a unity build
// compiles all of compensation_tests' files as one translation unit.
#pragma once

namespace rpsd::compensation {

inline constexpr double kDt = 1.0 / 1024.0;

}  // namespace rpsd::compensation
