// Linear analysis of the servo-hydraulic test system (seed paper Eqs. 5-12), from the
// same parameters the simulation uses. Not real-time safe.
#pragma once

#include <Eigen/Core>

#include "rpsd/servo/polynomial.h"
#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {

enum class LinearModel {
  // The paper's Eq. 8: controller a pure gain G_p (Eq. 5), servovalve a static gain K_s (Eq. 6),
  // flow linearised about null (Eq. 7). Third order.
  kPaperEq8,
  // Eq. 8 with the controller's derivative gain and the second-order servovalve of Eq. 2
  // kept: the linearisation of the simulated plant with its nonlinearities switched off.
  kFullLinear,
};

// Command-to-displacement transfer function G_xu(s).
TransferFunction command_to_displacement(const ServoSystemParameters& p, LinearModel model);

// First-order approximation of Eq. 9: 1 / (s / omega_c + 1).
TransferFunction first_order_approximation(const ServoSystemParameters& p);

// omega_c = K_v C_F K_s G_p / A (Eq. 9), rad/s, with K_v the initial flow-gain slope.
double cutoff_frequency_rad_s(const ServoSystemParameters& p);

// T_d = 1 / omega_c (Eq. 12), s.
double response_delay_s(const ServoSystemParameters& p);

// AR(omega) = 1 - 1 / sqrt(1 + (omega / omega_c)^2) (Eq. 10).
double amplitude_reduction(const ServoSystemParameters& p, double frequency_hz);

// Oil-column frequency sqrt(A^2 / (m K_a)) (Eq. 11), rad/s.
double oil_column_frequency_rad_s(const ServoSystemParameters& p);

// Largest stable proportional gain of the model from the Routh-Hurwitz criterion.
double max_stable_p_gain(const ServoSystemParameters& p, LinearModel model);

// The same for the paper's cubic in closed form: G_p < (a2 a1 / a3 - C_l k) / (A K_v C_F K_s),
// with a3 = K_a m, a2 = K_a c + C_l m, a1 = K_a k + C_l c + A^2.
double max_stable_p_gain_closed_form(const ServoSystemParameters& p);

// State matrix of the simulated plant linearised at rest (numerical Jacobian of
// ServoHydraulicPlant::derivative with the flow nonlinearities and friction switched off).
Eigen::MatrixXd linearised_state_matrix(const ServoSystemParameters& p);

// Largest stable proportional gain found from the eigenvalues of linearised_state_matrix.
double max_stable_p_gain_from_eigenvalues(const ServoSystemParameters& p);

// The parameters with a different attached mass, holding the specimen's stiffness and
// viscous damping coefficient (the physical spring and damper stay; Figure 7's sweep).
ServoSystemParameters with_attached_mass(const ServoSystemParameters& p, double mass_kg);

// The parameters with a different proportional gain.
ServoSystemParameters with_p_gain(const ServoSystemParameters& p, double proportional_gain);

// The parameters as the linear analysis assumes them: no flow nonlinearity, no friction.
ServoSystemParameters linearised(const ServoSystemParameters& p);

// The headline numbers of `rpsd analyze SERVO.yaml`.
struct ServoAnalysis {
  double cutoff_frequency_hz = 0.0;
  double response_delay_ms = 0.0;
  double amplitude_reduction_at_2hz = 0.0;
  double oil_column_frequency_hz = 0.0;
  double max_stable_p_gain = 0.0;             // Routh, paper's Eq. 8
  double max_stable_p_gain_full_model = 0.0;  // eigenvalues, servovalve dynamics included
  double p_gain = 0.0;
  double static_gain = 0.0;  // G_xu(0) of Eq. 8
  double specimen_natural_frequency_hz = 0.0;
  double servovalve_natural_frequency_hz = 0.0;
  double servovalve_damping_ratio = 0.0;
};

ServoAnalysis analyze(const ServoSystemParameters& p);

}  // namespace rpsd::servo
