// Typed parameters of a displacement-controlled servo-hydraulic test system: the
// controller, three-stage servovalve, valve flow, actuator, sensors and the attached
// specimen (the seed paper's Eqs. 1-4 and its test structure). SI units throughout.
#pragma once

#include <string>
#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/envelope.h"

namespace rpsd::servo {

// PID controller with the integral gain zero (paper Eq. 1): H_c = G_p + G_d s. In force
// control (issue 30) the valve command is G_f (F_command - F_load_cell), proportional only.
struct ControllerParameters {
  double proportional_gain = 0.0;  // G_p, valve command volts per error volt
  double derivative_gain_s = 0.0;  // G_d, seconds
  // G_f, valve command volts per newton of force error. 0 (the default): no force loop, and a
  // node refuses a force channel on this plant. No default is safe for every rig: against the
  // oil column the loop's gain is G_f K_s K_v0 A / K_a, which the spool must follow
  // (docs/servo-model.md, "Force control").
  double force_gain_v_per_n = 0.0;
};

// Three-stage servovalve spool dynamics with the inner spool loop (paper Eq. 2):
// x_v / v = K_vp / (tau A_v s^2 + A_v s + K_3 K_vp) / x_vmax, with |x_v| <= 1.
struct ServovalveParameters {
  double pilot_time_constant_s = 0.0;           // tau
  double pilot_flow_gain_m3_per_s_per_v = 0.0;  // K_vp
  double main_spool_area_m2 = 0.0;              // A_v
  double spool_lvdt_gain_v_per_m = 0.0;         // K_3
  double max_spool_stroke_m = 0.0;              // x_vmax

  // Static gain K_s = 1 / (K_3 x_vmax): spool opening per volt of valve command (Eq. 6).
  double static_gain_per_v() const { return 1.0 / (spool_lvdt_gain_v_per_m * max_spool_stroke_m); }
  // Natural frequency of the inner spool loop, rad/s.
  double natural_frequency_rad_s() const;
  // Damping ratio of the inner spool loop.
  double damping_ratio() const;
};

// Valve flow (paper Eq. 3): Q_L = K_v(x_v) x_v sqrt(1 - sgn(x_v) P_L / P_s).
// K_v(x_v) = K_v0 / sqrt(1 + (r x_v)^2) falls as the opening grows (r is the roll-off).
// Each nonlinearity can be switched off; with both off Q_L = K_v0 x_v (Eq. 7).
struct ValveFlowParameters {
  double no_load_flow_gain_m3_per_s = 0.0;  // K_v0: initial slope of flow vs opening
  double flow_gain_rolloff = 0.0;           // r in K_v(x_v) = K_v0 / sqrt(1 + (r x_v)^2)
  double supply_pressure_pa = 0.0;          // P_s
  bool nonlinear_flow_gain = true;          // K_v falls with opening
  bool load_pressure_effect = true;         // the square-root load-pressure term

  // No-load flow gain at opening x_v (real-time safe).
  double flow_gain_at(double spool_opening) const;
};

// Actuator chambers (paper Eq. 4): P_L = (Q_L - A xdot) / (K_a s + C_l); force = P_L A.
struct ActuatorParameters {
  double piston_area_m2 = 0.0;           // A
  double oil_volume_m3 = 0.0;            // V_t, both chambers and passages
  double bulk_modulus_pa = 0.0;          // beta_e, effective
  double leakage_m3_per_s_per_pa = 0.0;  // C_l, total servovalve/actuator leakage
  double stroke_m = 0.0;                 // half stroke (+/-): the piston's end stops

  // Compressibility coefficient K_a = V_t / (4 beta_e), m^5/N (Merritt).
  double compressibility_m5_per_n() const { return oil_volume_m3 / (4.0 * bulk_modulus_pa); }
};

// Displacement transducer (LVDT) feedback gain C_F. The load cell reads P_L A.
struct SensorParameters {
  double lvdt_gain_v_per_m = 0.0;  // C_F
};

// Elastic stiffness: linear, or bilinear elastic (softening beyond a displacement, as the
// paper's springs: 700.8 kN/m dropping to 350.4 kN/m beyond 25.4 mm). Not hysteretic.
struct SpecimenStiffness {
  double initial_n_per_m = 0.0;
  double change_displacement_m = 0.0;  // 0 means linear
  double secondary_n_per_m = 0.0;      // stiffness beyond change_displacement_m

  bool is_bilinear() const { return change_displacement_m > 0.0; }
};

// The specimen the actuator drives: mass (including the piston), stiffness, viscous
// damping and Coulomb friction (regularised with tanh(v / v_reg) for integration).
struct SpecimenParameters {
  double mass_kg = 0.0;
  SpecimenStiffness stiffness;
  double damping_ratio = 0.0;  // of the initial stiffness and mass
  double friction_force_n = 0.0;
  double friction_regularisation_velocity_m_per_s = 1.0e-3;

  // Viscous damping coefficient c = 2 zeta sqrt(k0 m), N s/m.
  double damping_n_s_per_m() const;
  // Undamped natural frequency with the initial stiffness, rad/s.
  double natural_frequency_rad_s() const;
};

// The whole test system of the paper's Figure 3, plus the plant's integration rate.
class ServoHydraulicPlant;

struct ServoSystemParameters {
  using Model = ServoHydraulicPlant;  // the Plant these parameters build
  static constexpr std::string_view kName = "servo_model";
  static constexpr std::string_view kSummary =
      "the seed paper's servo-hydraulic model (controller, three-stage servovalve, actuator, specimen), from a "
      "parameter file";
  // `parameters`: the parameter file, relative to the file that names it (the specimen is the
  // file's own, so the scenario's specimen stiffness is not used).
  static ServoSystemParameters read(config::Source& section, double specimen_stiffness_n_per_m);

  std::string name;
  ControllerParameters controller;
  ServovalveParameters servovalve;
  ValveFlowParameters flow;
  ActuatorParameters actuator;
  SensorParameters sensors;
  SpecimenParameters specimen;
  double plant_rate_hz = 8192.0;   // fixed-step integration rate of the continuous plant
  ChannelConverters converters{};  // the scenario's servo.converters (none unless stated)

  // Throws std::invalid_argument naming the first inconsistent field. Not real-time safe.
  void validate() const;
  // The rig's envelope: the actuator's stroke, the supply pressure on the piston area, and the
  // no-load velocity at full valve opening (the valve's full flow over the piston area).
  Envelope envelope() const;
};

// Reads a servo-system parameter file (its root section; examples/servo/paper-mts-244.yaml)
// and validates it. Not real-time safe.
ServoSystemParameters read_servo_parameters(config::Source& file);

}  // namespace rpsd::servo
