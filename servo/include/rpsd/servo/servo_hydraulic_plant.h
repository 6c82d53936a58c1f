// The seed paper's servo-hydraulic test system (Figure 3, Eqs. 1-4) as a continuous-time
// plant integrated with classical fixed-step RK4 at ServoSystemParameters::plant_rate_hz.
// State (5 numbers, contiguous): spool opening x_v (-1..1), pilot-stage flow q, load
// pressure P_L, piston/specimen displacement x and velocity xdot.
//   controller   v    = G_p C_F (u - x) + G_d C_F (udot - xdot)             (Eq. 1)
//                in force control (issue 30): v = G_f (F_u - A P_L)
//   pilot stage  tau qdot = K_vp (v - K_3 x_vmax x_v) - q
//   main spool   x_vmax A_v xdot_v = q, stopped at |x_v| = 1                 (together Eq. 2)
//   valve flow   Q_L  = K_v(x_v) x_v sqrt(1 - sgn(x_v) P_L / P_s)            (Eq. 3)
//   chambers     K_a Pdot_L = Q_L - A xdot - C_l P_L                         (Eq. 4)
//   specimen     m xddot = A P_L - c xdot - k(x) - F_c tanh(xdot / v_reg) - f_ext
// (f_ext: a coupled specimen's share, set_external_load_n; zero otherwise).
// At the default rates the derivative runs 32 times per control step, so it is written for speed: docs/servo-model.md
#pragma once

#include <Eigen/Core>
#include <array>

#include "rpsd/servo/force_controlled_plant.h"
#include "rpsd/servo/plant.h"
#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {

class ServoHydraulicPlant final : public Plant, public ForceControlledPlant {
 public:
  using State = Eigen::Matrix<double, 5, 1>;
  enum StateIndex { kSpoolOpening = 0, kPilotFlow, kLoadPressure, kDisplacement, kVelocity };

  // Validates the parameters (throws std::invalid_argument). Not real-time safe.
  explicit ServoHydraulicPlant(const ServoSystemParameters& parameters);

  void reset(double displacement_m) override;
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  PlantMeasurement measure() const override;
  // The load enters the specimen equation; the load cell (A P_L) carries it at rest.
  bool accepts_external_load() const noexcept override { return true; }
  void set_external_load_n(double force_n) noexcept override { external_load_n_ = force_n; }
  // Force control: the valve command is G_f (F_command - A P_L) (ServoSystemParameters::
  // force_gain_v_per_n); the specimen's displacement follows from its own force balance.
  void advance_in_force(double force_start_n, double force_end_n, double duration_s) override;
  bool controls_force() const override { return k_.force_gain_v_per_n > 0.0; }

  // Time derivative of the state for command u and command rate udot; the model's whole
  // physics in one pure function (used by the integrator and the linearisation). Real-time safe.
  State derivative(const State& state, double command_m, double command_rate_m_per_s) const;

  const State& state() const { return state_; }
  void set_state(const State& state) { state_ = state; }
  double time_s() const { return time_s_; }
  double spool_opening() const { return state_[kSpoolOpening]; }
  double velocity_m_per_s() const { return state_[kVelocity]; }
  double load_pressure_pa() const { return state_[kLoadPressure]; }
  const ServoSystemParameters& parameters() const { return parameters_; }

 private:
  // The parameters as the derivative uses them (SI units, products and reciprocals).
  struct Coefficients {
    double position_gain_v_per_m = 0.0;          // G_p C_F
    double rate_gain_v_s_per_m = 0.0;            // G_d C_F
    double force_gain_v_per_n = 0.0;             // G_f (force control)
    double piston_area_m2 = 0.0;                 // A: the load cell reads A P_L
    double pilot_gain_m3_per_s2_per_v = 0.0;     // K_vp / tau
    double spool_feedback_v = 0.0;               // K_3 x_vmax: volts per unit opening
    double pilot_rate_per_s = 0.0;               // 1 / tau
    double opening_per_m3 = 0.0;                 // 1 / (A_v x_vmax)
    double rolloff_squared = 0.0;                // r^2, or 0 with the flow gain held constant
    double load_pressure_per_pa = 0.0;           // 1 / P_s, or 0 without the load-pressure term
    double flow_gain_per_compressibility = 0.0;  // K_v0 / K_a
    double area_per_compressibility = 0.0;       // A / K_a
    double leakage_per_compressibility = 0.0;    // C_l / K_a
    SpecimenStiffness stiffness;
    double damping_n_s_per_m = 0.0;
    double inverse_mass_per_kg = 0.0;
    double area_per_mass = 0.0;                  // A / m
    double friction_per_mass = 0.0;              // F_c / m
    double friction_per_velocity_s_per_m = 0.0;  // 1 / v_reg
  };

  using Rates = std::array<double, 5>;  // a state or its derivative, in the State order
  // The derivative, and the parts of the pressure and velocity rates that follow the slow
  // links: pressure rate = root_coefficient root - other_flows, acceleration = other_forces -
  // (F_c / m) friction_tanh.
  struct Terms {
    Rates rate;
    double root = 0.0, root_coefficient = 0.0, other_flows = 0.0;
    double friction_tanh = 0.0, other_forces = 0.0;
  };
  // In force control command_m is the force command (N) and the rate is not used.
  Terms terms(const Rates& s, double command_m, double command_rate_m_per_s) const;
  Rates stage_state(const Rates& y, double c, const Terms& t) const;
  void rk4_step(Rates& y, double h, double u0, double command_rate) const;
  void integrate(double command_start, double command_end, double duration_s);

  ServoSystemParameters parameters_;
  Coefficients k_;
  double max_step_s_;
  double stroke_m_;  // the piston's end stops: +/- the actuator's stroke
  State state_ = State::Zero();
  double time_s_ = 0.0;
  double external_load_n_ = 0.0;  // f_ext, held over each advance
  bool in_force_ = false;         // terms() closes the force loop (set for one advance_in_force)
};

}  // namespace rpsd::servo
