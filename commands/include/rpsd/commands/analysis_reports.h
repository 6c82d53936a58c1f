// `rpsd analyze SERVO.yaml` and `rpsd analyze integrator NAME`: the linear analysis of a servo
// system's parameter file and the amplification-matrix properties of a time integrator, as
// numbers and as the JSON their `--json` prints (rpsd.analyze_servo and
// rpsd.integrator_properties in Python return the same). Not real-time safe.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/integrators/amplification.h"
#include "rpsd/integrators/factory.h"

namespace rpsd::commands {

// The servo file's analysis (servo::analyze) with its "servo" name (ConfigError on a bad file).
nlohmann::json servo_analysis_json(const std::filesystem::path& servo_parameters);

// What `rpsd analyze integrator` is asked.
struct IntegratorQueryOptions {
  std::string name;  // a scheme or one of its spellings (integrator_spellings)
  // As written, read by the scheme's own parameters like a scenario's integrator keys.
  std::optional<std::string> rho_inf;
  std::optional<std::string> alpha;
  std::vector<double> omega_dt;  // Omega = omega dt of each point
  double damping = 0.0;          // the SDOF's physical damping ratio, [0, 1)
};

struct IntegratorProperties {
  integrators::IntegratorConfig config;
  integrators::SchemeInfo info;
  double damping = 0.0;
  double numerical_limit_omega_dt = 0.0;  // from the amplification matrix at this damping
  double searched_up_to = 0.0;
  std::vector<integrators::AmplificationPoint> points;  // one per omega_dt
};

// Throws std::invalid_argument naming the option (unknown scheme, a parameter it does not
// take, a value out of range) and ConfigError from the scheme's reader.
IntegratorProperties integrator_properties(const IntegratorQueryOptions& query);
nlohmann::json integrator_properties_json(const IntegratorProperties& properties);

// "central_difference, newmark, ...; or: cd, newmark_average, ..." (- and _ alike).
std::string integrator_spellings();
// The schemes whose parameters read `key` (rho_inf, alpha), for help and messages.
std::vector<std::string_view> schemes_reading(std::string_view key);

}  // namespace rpsd::commands
