#include "rpsd/commands.h"

#include "rpsd/integrators/amplification.h"
#include "rpsd/integrators/factory.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace rpsd::cli {
namespace {

namespace ri = rpsd::integrators;

struct Options {
  std::string name;
  std::optional<double> rho_inf;
  std::optional<double> alpha;
  std::vector<double> omega_dt;
  double damping = 0.0;
  bool json = false;
};

// The scenario's names (integrator.scheme), with - or _ alike; newmark is newmark_average.
constexpr const char* kNames =
    "central_difference, newmark (newmark_average), newmark_linear, hht_alpha, generalized_alpha, alpha_os, "
    "chang, chen_ricles, kolay_ricles_alpha";

std::string normalized(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return c == '_' ? '-' : static_cast<char>(std::tolower(c)); });
  return s;
}

// Scheme names as researchers write them, with the parameters the options may set.
ri::IntegratorConfig config_from(const Options& o) {
  const std::string n = normalized(o.name);
  const bool takes_rho =
      n == "generalized-alpha" || n == "ga" || n == "kr-alpha" || n == "kolay-ricles-alpha" || n == "kr";
  const bool takes_alpha = n == "hht" || n == "hht-alpha" || n == "alpha-os";
  if (o.rho_inf && !takes_rho)
    throw std::invalid_argument("--rho-inf applies to generalized-alpha and kr-alpha, not '" + o.name + "'");
  if (o.alpha && !takes_alpha) throw std::invalid_argument("--alpha applies to hht and alpha-os, not '" + o.name + "'");
  if (n == "central-difference" || n == "cd") return ri::CentralDifferenceParams{};
  if (n == "newmark" || n == "newmark-average" || n == "average-acceleration")
    return ri::NewmarkParams::average_acceleration();
  if (n == "newmark-linear" || n == "linear-acceleration") return ri::NewmarkParams::linear_acceleration();
  if (n == "hht" || n == "hht-alpha") return ri::HhtAlphaParams{o.alpha.value_or(-0.1), {}};
  if (n == "alpha-os") return ri::AlphaOsParams{o.alpha.value_or(-1.0 / 6.0)};
  if (n == "generalized-alpha" || n == "ga") return ri::GeneralizedAlphaParams{o.rho_inf.value_or(0.8), {}};
  if (n == "chang") return ri::ChangParams{};
  if (n == "cr" || n == "chen-ricles") return ri::ChenRiclesParams{};
  if (n == "kr-alpha" || n == "kolay-ricles-alpha" || n == "kr")
    return ri::KolayRiclesAlphaParams{o.rho_inf.value_or(0.8)};
  throw std::invalid_argument("unknown integrator '" + o.name + "'; expected one of: " + kNames);
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
  cmd->add_option("name", opts->name, std::string("scheme: ") + kNames)->required();
  auto* rho = cmd->add_option("--rho-inf", opts->rho_inf,
                              "spectral radius at infinity, [0, 1] (generalized-alpha, kr-alpha; "
                              "default 0.8)");
  auto* alpha = cmd->add_option("--alpha", opts->alpha, "alpha in [-1/3, 0] (hht default -0.1, alpha-os default -1/6)");
  rho->excludes(alpha);
  alpha->excludes(rho);
  cmd->add_option("--omega-dt", opts->omega_dt, "comma-separated list of Omega = omega*dt")->delimiter(',')->required();
  cmd->add_option("--damping", opts->damping, "physical damping ratio xi of the SDOF (default 0)");
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace rpsd::cli
