#include "rpsd/commands/analysis_reports.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <tuple>

#include "rpsd/config/key_table.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/servo/linear_analysis.h"

namespace rpsd::commands {
namespace {

namespace ri = rpsd::integrators;

// The scheme a spelling names, with --rho-inf and --alpha read by its parameters' read()
// (their range checked there), as if they were its scenario keys.
ri::IntegratorConfig config_from(const IntegratorQueryOptions& o) {
  std::optional<ri::IntegratorConfig> spelled = ri::integrator_from_spelling(o.name);
  if (!spelled)
    throw std::invalid_argument("unknown integrator '" + o.name + "'; expected one of: " + integrator_spellings());
  const std::string_view scheme = ri::integrator_name(*spelled);
  YAML::Node keys(YAML::NodeType::Map);
  auto overrides = std::make_shared<std::vector<scenarios::OverrideNode>>();
  for (const auto& [option, key, value] :
       {std::tuple{"--rho-inf", "rho_inf", o.rho_inf}, {"--alpha", "alpha", o.alpha}}) {
    if (!value) continue;
    const std::vector<std::string_view> takers = schemes_reading(key);
    if (std::find(takers.begin(), takers.end(), scheme) == takers.end())
      throw std::invalid_argument(std::string(option) + " applies to " + config::listed(takers) + ", not '" + o.name +
                                  "'");
    keys[key] = *value;
    overrides->push_back({keys[key], std::string(option) + " " + *value});
  }
  if (keys.size() == 0) return *spelled;  // an alias's own parameters (newmark_linear)
  scenarios::MappingReader reader(keys, "rpsd analyze integrator", "", overrides);
  ri::IntegratorConfig config = *ri::IntegratorKinds::read(scheme, reader);
  reader.finish();
  return config;
}

nlohmann::json number_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

}  // namespace

nlohmann::json servo_analysis_json(const std::filesystem::path& servo_parameters) {
  const auto p = scenarios::load_servo_parameters(servo_parameters);
  const servo::ServoAnalysis a = servo::analyze(p);
  return {{"cutoff_frequency_hz", a.cutoff_frequency_hz},
          {"response_delay_ms", a.response_delay_ms},
          {"amplitude_reduction_at_2hz", a.amplitude_reduction_at_2hz},
          {"oil_column_frequency_hz", a.oil_column_frequency_hz},
          {"max_stable_p_gain", a.max_stable_p_gain},
          {"max_stable_p_gain_full_model", a.max_stable_p_gain_full_model},
          {"p_gain", a.p_gain},
          {"static_gain", a.static_gain},
          {"specimen_natural_frequency_hz", a.specimen_natural_frequency_hz},
          {"servovalve_natural_frequency_hz", a.servovalve_natural_frequency_hz},
          {"servovalve_damping_ratio", a.servovalve_damping_ratio},
          {"servo", p.name}};
}

std::string integrator_spellings() {
  return config::listed(ri::IntegratorKinds::names()) + "; or: " + config::listed(ri::integrator_aliases());
}

std::vector<std::string_view> schemes_reading(std::string_view key) {
  std::vector<std::string_view> names;
  ri::IntegratorKinds::for_each([&](auto kind) {
    using Kind = typename decltype(kind)::type;
    config::KeyTable table;
    (void)Kind::read(table);
    for (const auto& row : table.rows())
      if (row.path == key) names.push_back(Kind::kName);
  });
  return names;
}

IntegratorProperties integrator_properties(const IntegratorQueryOptions& o) {
  IntegratorProperties p;
  p.config = config_from(o);
  // Constructing the scheme validates its parameters (alpha range, rho_inf range).
  p.info = ri::make_integrator(p.config)->info();
  if (!(o.damping >= 0.0 && o.damping < 1.0))
    throw std::invalid_argument("--damping must be in [0, 1), got " + std::to_string(o.damping));
  for (double w : o.omega_dt)
    if (!(w > 0.0) || !std::isfinite(w))
      throw std::invalid_argument("--omega-dt values must be positive, got " + std::to_string(w));
  p.damping = o.damping;
  p.searched_up_to = 1000.0;
  p.numerical_limit_omega_dt = ri::numerical_stability_limit(p.config, o.damping, p.searched_up_to);
  for (double w : o.omega_dt) p.points.push_back(ri::analyze_amplification(p.config, w, o.damping));
  return p;
}

nlohmann::json integrator_properties_json(const IntegratorProperties& p) {
  nlohmann::json j;
  j["scheme"] = std::string(p.info.name);
  j["parameters"] = ri::describe(p.config);
  j["damping_ratio"] = p.damping;
  j["explicit_in_displacement"] = p.info.explicit_in_displacement;
  j["stability_limit_omega_dt"] = {{"analytic_undamped", number_or_null(p.info.stability_limit_omega_dt)},
                                   {"numerical", number_or_null(p.numerical_limit_omega_dt)},
                                   {"searched_up_to", p.searched_up_to}};
  j["conventions"] =
      "amplification matrix on (x, v, a) of an SDOF, built by stepping the implementation; "
      "principal roots lambda = exp(Omega_bar(-xi_bar +- i)); period_ratio = Omega/Omega_bar; "
      "numerical_damping_ratio = -ln|lambda|/Omega_bar (includes physical damping); "
      "algorithmic = numerical - xi/sqrt(1-xi^2)";
  j["points"] = nlohmann::json::array();
  for (const auto& point : p.points) {
    nlohmann::json e;
    e["omega_dt"] = point.omega_dt;
    e["spectral_radius"] = point.spectral_radius;
    e["stable"] = point.spectral_radius <= 1.0 + 1e-7;
    e["period_ratio"] = number_or_null(point.period_ratio);
    e["numerical_damping_ratio"] = number_or_null(point.numerical_damping_ratio);
    e["algorithmic_damping_ratio"] = number_or_null(point.algorithmic_damping_ratio);
    e["eigenvalues"] = nlohmann::json::array();
    for (const auto& l : point.eigenvalues) e["eigenvalues"].push_back({l.real(), l.imag()});
    j["points"].push_back(e);
  }
  return j;
}

}  // namespace rpsd::commands
