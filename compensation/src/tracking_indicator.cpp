#include "rpsd/compensation/tracking_indicator.h"

#include <stdexcept>
#include <string>

namespace rpsd::compensation {

void TrackingIndicator::reset() noexcept { *this = TrackingIndicator{}; }

void TrackingIndicator::reset(double command_m, double measured_m) noexcept {
  *this = TrackingIndicator{};
  has_previous_ = true;
  previous_command_m_ = command_m;
  previous_measured_m_ = measured_m;
}

namespace {
void require_equal_lengths(std::size_t a, std::size_t b, const char* what) {
  if (a != b) {
    throw std::invalid_argument(std::string("tracking indicator: ") + what + " lengths differ (" + std::to_string(a) +
                                " vs " + std::to_string(b) + ")");
  }
}
}  // namespace

double tracking_indicator(std::span<const double> command_m, std::span<const double> measured_m) {
  require_equal_lengths(command_m.size(), measured_m.size(), "command and measured");
  TrackingIndicator ti;
  for (std::size_t k = 0; k < command_m.size(); ++k) ti.update(command_m[k], measured_m[k]);
  return ti.value_m2();
}

void tracking_indicator_history(std::span<const double> command_m, std::span<const double> measured_m,
                                std::span<double> history_m2) {
  require_equal_lengths(command_m.size(), measured_m.size(), "command and measured");
  require_equal_lengths(command_m.size(), history_m2.size(), "input and history");
  TrackingIndicator ti;
  for (std::size_t k = 0; k < command_m.size(); ++k) {
    ti.update(command_m[k], measured_m[k]);
    history_m2[k] = ti.value_m2();
  }
}

}  // namespace rpsd::compensation
