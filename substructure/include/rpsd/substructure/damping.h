#pragma once
// How a model's damping matrix C is specified, and how it is built from M and K0.

#include <vector>

#include "rpsd/linalg/structural_matrix.h"
#include "rpsd/substructure/rayleigh.h"

#include <optional>
#include <string>
#include <variant>

namespace rpsd::substructure {

struct Undamped {};

// C given explicitly (e.g. exported by a finite-element program).
struct DampingMatrix {
  linalg::StructuralMatrix c;
};

// Rayleigh damping with ratio damping_ratio_a in mode mode_a and damping_ratio_b in mode_b.
// Mode numbers are 1-based in order of ascending frequency: 1 is the fundamental mode.
// Frequencies come from the dense generalized eigen-solver (see kMaxDenseEigenDofs).
struct RayleighFromModes {
  int mode_a = 1;
  int mode_b = 2;
  double damping_ratio_a = 0.05;
  double damping_ratio_b = 0.05;
};

// Rayleigh damping anchored at two given circular frequencies (for models too large for the
// dense eigen-solver: take the frequencies from the finite-element program).
struct RayleighFromFrequencies {
  double omega_a_rad_s = 0.0;
  double omega_b_rad_s = 0.0;
  double damping_ratio_a = 0.05;
  double damping_ratio_b = 0.05;
};

// Classical damping with a ratio per mode: C = M Φ diag(2 ζ_k ω_k) Φᵀ M, Φ mass-normalised
// (modal.h), so that mode k has ratio ζ_k exactly (the RTHS benchmark's 5 % in every mode).
// One ratio applies to every mode; otherwise one per mode, in ascending frequency.
struct ModalDamping {
  std::vector<double> damping_ratios;
};

using DampingConfig = std::variant<Undamped, DampingMatrix, RayleighFromModes, RayleighFromFrequencies,
                                   RayleighCoefficients, ModalDamping>;

struct BuiltDamping {
  linalg::StructuralMatrix c;                    // same storage as K0
  std::optional<RayleighCoefficients> rayleigh;  // set for the three Rayleigh forms
};

// Builds C for a model whose M and K0 are already validated (square, same size, symmetric,
// M positive definite). C = a0 M + a1 K0 for Rayleigh damping, with the storage of K0.
// Errors are std::invalid_argument prefixed with `context`. Not real-time safe.
[[nodiscard]] BuiltDamping build_damping(const DampingConfig& config, const linalg::StructuralMatrix& mass,
                                         const linalg::StructuralMatrix& initial_stiffness, const std::string& context);

}  // namespace rpsd::substructure
