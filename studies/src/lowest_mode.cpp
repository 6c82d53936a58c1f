#include "rpsd/studies/lowest_mode.h"

#include <cmath>
#include <exception>

#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/studies/dry_run.h"
#include "rpsd/substructure/modal.h"

namespace rpsd::studies {

telemetry::LowestMode lowest_mode_for_identification(const hybrid_test::TestConfig& original) {
  if (!original.opensees_sites.empty() || !original.setups.empty()) return {};
  try {
    const hybrid_test::TestConfig s = simulated_in_process(original);
    const hybrid_test::TestAssembly test(s, {});
    const auto& numerical = test.numerical();
    const auto k = test.partition().with_specimen_stiffness(numerical.initial_stiffness());
    const substructure::ModalSolution modal = substructure::lowest_modes(numerical.mass(), k, 1);
    if (modal.omega_rad_s.size() == 0) return {};
    const Eigen::VectorXd phi = modal.modes.col(0);
    Eigen::VectorXd product(phi.size());
    telemetry::LowestMode mode;
    mode.frequency_hz = modal.omega_rad_s[0] / (2.0 * M_PI);
    numerical.initial_stiffness().multiply(phi, product);
    mode.numerical_stiffness_n_per_m = phi.dot(product);
    numerical.damping().multiply(phi, product);
    mode.numerical_damping_n_s_per_m = phi.dot(product);
    mode.channel_weight.assign(s.experimental.size(), 0.0);
    for (const auto& e : s.experimental) {
      const auto channel = static_cast<std::size_t>(e.dof.actuator_channel);
      if (channel >= mode.channel_weight.size()) return {};
      mode.channel_weight[channel] = phi[e.dof.dof] * phi[e.dof.dof] * e.dof.force_scale * e.dof.displacement_scale;
    }
    return mode;
  } catch (const std::exception&) {
    return {};  // the run itself says what is wrong
  }
}

}  // namespace rpsd::studies
