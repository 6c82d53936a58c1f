#include "rpsd/studies/pretest_checks.h"

#include <cmath>
#include <cstdio>
#include <numbers>

#include "rpsd/servo/linear_analysis.h"

namespace rpsd::studies {
namespace {

// A mode this many times above the cut-off is no design: the masses' unit is asked about.
constexpr double kFarAboveCutoff = 10.0;

}  // namespace

LimitMargin margin_to(std::string limit, double peak, double bound, bool rail) {
  LimitMargin m{std::move(limit), std::abs(peak), bound, 1.0, rail};
  if (std::isfinite(bound) && bound > 0.0) m.margin = 1.0 - m.peak / bound;
  return m;
}

std::string describe(const LimitMargin& m, double scale, const char* unit) {
  char text[160];
  std::snprintf(text, sizeof text, "%s %.3g / %.3g %s: margin %.0f %%%s", m.limit.c_str(), m.peak * scale,
                m.bound * scale, unit, 100.0 * m.margin,
                m.reached() ? (m.rail ? " (at the rail: clamped)" : " (reached)")
                : m.low()   ? " (below 10 %)"
                            : "");
  return text;
}

std::optional<double> actuator_cutoff_hz(const servo::PlantConfig& plant) {
  if (const auto* p = std::get_if<servo::ServoSystemParameters>(&plant)) {
    return servo::cutoff_frequency_rad_s(*p) / (2.0 * std::numbers::pi);
  }
  return std::nullopt;
}

std::string mass_key(const hybrid_test::TestConfig& test) {
  if (std::holds_alternative<substructure::ShearBuildingParameters>(test.structure)) return "structure.floor_masses_kg";
  const auto* external = std::get_if<substructure::ExternalStructureParameters>(&test.structure);
  const auto& linear = external ? external->matrices : std::get<substructure::LinearMdofParameters>(test.structure);
  return linear.mass_source.empty() ? "structure.mass_kg" : "structure.mass_file (" + linear.mass_source + ")";
}

std::vector<std::string> modes_beyond_bandwidth(const std::vector<double>& frequencies_hz, double cutoff_hz,
                                                const std::string& masses_key) {
  std::vector<std::string> warnings;
  for (std::size_t i = 0; i < frequencies_hz.size(); ++i) {
    if (!(frequencies_hz[i] > cutoff_hz)) continue;
    // Far above it, the likeliest cause is a unit: tonnes give modes sqrt(1000) = 32 times too high.
    const bool far = frequencies_hz[i] > kFarAboveCutoff * cutoff_hz;
    char text[400];
    std::snprintf(text, sizeof text,
                  "mode %zu at %.4g Hz lies above the actuator's cut-off frequency of %.4g Hz (servo linear "
                  "analysis, Eq. 9): the rig cannot follow it; the masses in %s set it%s",
                  i + 1, frequencies_hz[i], cutoff_hz, masses_key.c_str(),
                  far ? " (are they in kg? masses in tonnes give modes about 32 times too high)" : "");
    warnings.emplace_back(text);
  }
  return warnings;
}

}  // namespace rpsd::studies
