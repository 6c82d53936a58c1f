#include "rpsd/commands.h"

#include "rpsd/config/key_table.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/integrators/amplification.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/scenarios/yaml_reader.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace rpsd::cli {
namespace {

namespace ri = rpsd::integrators;

struct Options {
  std::string name;
  // As written, read by the scheme's own parameters like a scenario's integrator keys.
  std::optional<std::string> rho_inf;
  std::optional<std::string> alpha;
  std::vector<double> omega_dt;
  double damping = 0.0;
  bool json = false;
};

// "central_difference, newmark, ...; or: cd, newmark_average, ..." (- and _ alike).
std::string every_spelling() {
  return config::listed(ri::IntegratorKinds::names()) + "; or: " + config::listed(ri::integrator_aliases());
}

// The schemes whose parameters read `key` (from their listing), for a message.
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

// The scheme a spelling names, with --rho-inf and --alpha read by its parameters' read()
// (their range checked there), as if they were its scenario keys.
ri::IntegratorConfig config_from(const Options& o) {
  std::optional<ri::IntegratorConfig> spelled = ri::integrator_from_spelling(o.name);
  if (!spelled)
    throw std::invalid_argument("unknown integrator '" + o.name + "'; expected one of: " + every_spelling());
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

void run(const Options& o) {
  const ri::IntegratorConfig config = config_from(o);
  // Constructing the scheme validates its parameters (alpha range, rho_inf range).
  const ri::SchemeInfo info = ri::make_integrator(config)->info();
  if (!(o.damping >= 0.0 && o.damping < 1.0))
    throw std::invalid_argument("--damping must be in [0, 1), got " + std::to_string(o.damping));
  for (double w : o.omega_dt)
    if (!(w > 0.0) || !std::isfinite(w))
      throw std::invalid_argument("--omega-dt values must be positive, got " + std::to_string(w));

  constexpr double search_max = 1000.0;
  const double numerical_limit = ri::numerical_stability_limit(config, o.damping, search_max);
  std::vector<ri::AmplificationPoint> points;
  for (double w : o.omega_dt) points.push_back(ri::analyze_amplification(config, w, o.damping));

  if (o.json) {
    nlohmann::json j;
    j["scheme"] = std::string(info.name);
    j["parameters"] = ri::describe(config);
    j["damping_ratio"] = o.damping;
    j["explicit_in_displacement"] = info.explicit_in_displacement;
    j["stability_limit_omega_dt"] = {{"analytic_undamped", number_or_null(info.stability_limit_omega_dt)},
                                     {"numerical", number_or_null(numerical_limit)},
                                     {"searched_up_to", search_max}};
    j["conventions"] =
        "amplification matrix on (x, v, a) of an SDOF, built by stepping the implementation; "
        "principal roots lambda = exp(Omega_bar(-xi_bar +- i)); period_ratio = Omega/Omega_bar; "
        "numerical_damping_ratio = -ln|lambda|/Omega_bar (includes physical damping); "
        "algorithmic = numerical - xi/sqrt(1-xi^2)";
    j["points"] = nlohmann::json::array();
    for (const auto& p : points) {
      nlohmann::json e;
      e["omega_dt"] = p.omega_dt;
      e["spectral_radius"] = p.spectral_radius;
      e["stable"] = p.spectral_radius <= 1.0 + 1e-7;
      e["period_ratio"] = number_or_null(p.period_ratio);
      e["numerical_damping_ratio"] = number_or_null(p.numerical_damping_ratio);
      e["algorithmic_damping_ratio"] = number_or_null(p.algorithmic_damping_ratio);
      e["eigenvalues"] = nlohmann::json::array();
      for (const auto& l : p.eigenvalues) e["eigenvalues"].push_back({l.real(), l.imag()});
      j["points"].push_back(e);
    }
    std::cout << j.dump(2) << '\n';
    return;
  }

  std::printf("integrator %s (%s), damping ratio %g\n", std::string(info.name).c_str(), ri::describe(config).c_str(),
              o.damping);
  std::printf("explicit in displacement: %s\n", info.explicit_in_displacement ? "yes" : "no");
  if (std::isfinite(info.stability_limit_omega_dt))
    std::printf("stability limit (undamped, analytic): Omega = %.6g\n", info.stability_limit_omega_dt);
  else
    std::printf("stability limit (undamped, analytic): none (unconditionally stable)\n");
  if (std::isfinite(numerical_limit))
    std::printf("stability limit (this damping, from the amplification matrix): Omega = %.6g\n", numerical_limit);
  else
    std::printf(
        "stability limit (this damping, from the amplification matrix): none up to "
        "Omega = %g\n",
        search_max);
  std::printf("\n%10s  %15s  %12s  %15s  %15s\n", "Omega", "spectral_radius", "T_bar/T", "xi_bar", "xi_algorithmic");
  for (const auto& p : points) {
    if (p.oscillatory)
      std::printf("%10.4g  %15.6f  %12.6f  %15.6f  %15.6f%s\n", p.omega_dt, p.spectral_radius, p.period_ratio,
                  p.numerical_damping_ratio, p.algorithmic_damping_ratio,
                  p.spectral_radius > 1.0 + 1e-7 ? "  UNSTABLE" : "");
    else
      std::printf("%10.4g  %15.6f  %12s  %15s  %15s%s\n", p.omega_dt, p.spectral_radius, "-", "-", "-",
                  p.spectral_radius > 1.0 + 1e-7 ? "  UNSTABLE (real roots)" : "  (real roots)");
  }
}

}  // namespace

void add_analyze_integrator_command(CLI::App& analyze) {
  auto opts = std::make_shared<Options>();
  auto* cmd = analyze.add_subcommand("integrator",
                                     "Spectral radius, period ratio, numerical damping and stability limit of a "
                                     "time integrator (amplification matrix of an SDOF)");
  cmd->add_option("name", opts->name, "scheme: " + every_spelling())->required();
  auto* rho = cmd->add_option(
      "--rho-inf", opts->rho_inf,
      "spectral radius at infinity, [0, 1] (" + config::listed(schemes_reading("rho_inf")) + "; default 0.8)");
  auto* alpha = cmd->add_option("--alpha", opts->alpha,
                                "alpha in [-1/3, 0] (" + config::listed(schemes_reading("alpha")) +
                                    "; hht_alpha default -0.1, alpha_os default -1/6)");
  rho->excludes(alpha);
  alpha->excludes(rho);
  cmd->add_option("--omega-dt", opts->omega_dt, "comma-separated list of Omega = omega*dt")->delimiter(',')->required();
  cmd->add_option("--damping", opts->damping, "physical damping ratio xi of the SDOF (default 0)");
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace rpsd::cli
