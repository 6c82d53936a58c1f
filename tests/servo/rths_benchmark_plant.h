// The RTHS benchmark's nominal transfer system, for tests.
#pragma once

#include <cmath>

#include "rpsd/servo/benchmark_transfer_system.h"

namespace rpsd::testing {

// Silva et al. 2020, F1_input_file.m; c_e from its damping ratio 0.0097: 2 zeta sqrt(k m).
inline servo::BenchmarkTransferSystem rths_benchmark_nominal() {
  servo::BenchmarkTransferSystem b;
  b.gain = 1.0261;
  b.a1_beta0 = 2.1283e13;
  b.a2 = 4.2297e6;
  b.a3_per_s = 3.3;
  b.beta1_per_s = 425.0;
  b.beta2_per_s2 = 9.9976e4;
  b.specimen_mass_kg = 29.13;
  b.specimen_stiffness_n_per_m = 1.19e6;
  b.specimen_damping_n_s_per_m = 2.0 * 0.0097 * std::sqrt(1.19e6 * 29.13);
  return b;
}

}  // namespace rpsd::testing
