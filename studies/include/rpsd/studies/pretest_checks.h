// What the pre-test checks (`rpsd validate` and the dry run) say beyond pass or fail: the
// margin left to each limit, warned about below kMarginWarning, and structural modes beyond the
// actuator's bandwidth (a mass in tonnes where kilograms were meant gives one). Not real-time
// safe.
#pragma once

#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::studies {

// Below this margin to a limit a check warns (docs/safety.md).
inline constexpr double kMarginWarning = 0.10;

// One quantity against one bound: margin = 1 - |peak| / bound (1 untouched, 0 at the bound,
// negative beyond it; 1 when there is no bound).
struct LimitMargin {
  std::string limit;  // "stroke", "force", "D/A rail", ...
  double peak = 0.0;
  double bound = std::numeric_limits<double>::infinity();
  double margin = 1.0;
  bool rail = false;  // a converter's rail: reaching it is not ready (the signal is clamped)
  bool reached() const { return margin <= 0.0; }
  bool low() const { return margin < kMarginWarning; }
};
LimitMargin margin_to(std::string limit, double peak, double bound, bool rail = false);

// "stroke 24.7 / 25.4 mm: margin 3 % (below 10 %)": scale and unit for the numbers.
std::string describe(const LimitMargin& m, double scale, const char* unit);

// The servo model's cut-off frequency omega_c / 2 pi (its linear analysis, Eq. 9); none for
// the other plant kinds.
std::optional<double> actuator_cutoff_hz(const servo::PlantConfig& plant);

// The key that sets the structure's masses, for messages: structure.mass_kg,
// structure.floor_masses_kg or structure.mass_file.
std::string mass_key(const hybrid_test::TestConfig& test);

// One warning per mode above the actuator's cut-off: the rig cannot follow it, and a mode far
// above it usually means masses in the wrong unit. Names the mode, its frequency, the cut-off
// and the key of the masses.
std::vector<std::string> modes_beyond_bandwidth(const std::vector<double>& frequencies_hz, double cutoff_hz,
                                                const std::string& masses_key);

}  // namespace rpsd::studies
