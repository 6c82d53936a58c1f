// The TCP waits' deadlines: seconds on the steady clock, which no clock change moves.
#pragma once

#include <chrono>

namespace rpsd::opensees {

inline double steady_now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

}  // namespace rpsd::opensees
