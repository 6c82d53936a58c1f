#include "rpsd/commands.h"

#include "rpsd/commands/analysis_reports.h"
#include "rpsd/integrators/amplification.h"
#include "rpsd/integrators/factory.h"

#include <cmath>
#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

namespace rpsd::cli {
namespace {

namespace ri = rpsd::integrators;

struct Options {
  commands::IntegratorQueryOptions query;
  bool json = false;
};

void run(const Options& o) {
  const commands::IntegratorProperties p = commands::integrator_properties(o.query);
  if (o.json) {
    std::cout << commands::integrator_properties_json(p).dump(2) << '\n';
    return;
  }
  const ri::SchemeInfo& info = p.info;
  const ri::IntegratorConfig& config = p.config;
  const double numerical_limit = p.numerical_limit_omega_dt;
  const double search_max = p.searched_up_to;
  const auto& points = p.points;
  std::printf("integrator %s (%s), damping ratio %g\n", std::string(info.name).c_str(), ri::describe(config).c_str(),
              p.damping);
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
  cmd->add_option("name", opts->query.name, "scheme: " + commands::integrator_spellings())->required();
  auto* rho = cmd->add_option("--rho-inf", opts->query.rho_inf,
                              "spectral radius at infinity, [0, 1] (" +
                                  config::listed(commands::schemes_reading("rho_inf")) + "; default 0.8)");
  auto* alpha = cmd->add_option("--alpha", opts->query.alpha,
                                "alpha in [-1/3, 0] (" + config::listed(commands::schemes_reading("alpha")) +
                                    "; hht_alpha default -0.1, alpha_os default -1/6)");
  rho->excludes(alpha);
  alpha->excludes(rho);
  cmd->add_option("--omega-dt", opts->query.omega_dt, "comma-separated list of Omega = omega*dt")
      ->delimiter(',')
      ->required();
  cmd->add_option("--damping", opts->query.damping, "physical damping ratio xi of the SDOF (default 0)");
  cmd->add_flag("--json", opts->json, "print JSON instead of a table");
  cmd->callback([opts] { run(*opts); });
}

}  // namespace rpsd::cli
