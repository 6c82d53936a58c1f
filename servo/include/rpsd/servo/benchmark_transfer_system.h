// The RTHS benchmark's transfer system (Silva et al. 2020, F1_input_file.m) by its physical
// parameters, so that a Monte Carlo run can perturb a3, beta1, beta2 and k_e as the benchmark
// does: servovalve and inner loop Gs = a1b0 / (s^2 + beta1 s + beta2), actuator Ga = 1/(s + a3),
// specimen Gest = 1/(m_e s^2 + c_e s + k_e), G0 = feedback(Ga Gest, a2 s) and
// G_xu = gain feedback(Gs G0, 1): from the controller's output u to the displacement x_m.
#pragma once

#include "rpsd/config/source.h"
#include "rpsd/servo/polynomial.h"

namespace rpsd::servo {

struct BenchmarkTransferSystem {
  double gain = 0.0;
  double a1_beta0 = 0.0;      // servovalve gain product, 1/s^3 units folded in
  double a2 = 0.0;            // pressure feedback of the actuator
  double a3_per_s = 0.0;      // actuator pole
  double beta1_per_s = 0.0;   // servovalve damping term
  double beta2_per_s2 = 0.0;  // servovalve stiffness term
  double specimen_mass_kg = 0.0;
  double specimen_damping_n_s_per_m = 0.0;
  double specimen_stiffness_n_per_m = 0.0;

  // Every key is required: the benchmark's nominal values are in the scenarios, not here.
  static BenchmarkTransferSystem read(config::Source& section);
  // gain a1b0 / ((s^2 + beta1 s + beta2)((s + a3)(m s^2 + c s + k) + a2 s) + a1b0).
  TransferFunction transfer_function() const;
};

}  // namespace rpsd::servo
