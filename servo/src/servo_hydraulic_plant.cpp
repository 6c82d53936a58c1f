#include "rpsd/servo/servo_hydraulic_plant.h"

#include <algorithm>
#include <cmath>

#include "substeps.h"

#include "rpsd/servo/specimen_forces.h"

namespace rpsd::servo {

ServoHydraulicPlant::ServoHydraulicPlant(const ServoSystemParameters& parameters)
    : parameters_(parameters), max_step_s_(1.0 / parameters.plant_rate_hz), stroke_m_(parameters.actuator.stroke_m) {
  parameters_.validate();
  const auto& p = parameters_;
  const auto& valve = p.servovalve;
  const double c_f = p.sensors.lvdt_gain_v_per_m;
  k_.position_gain_v_per_m = p.controller.proportional_gain * c_f;
  k_.rate_gain_v_s_per_m = p.controller.derivative_gain_s * c_f;
  k_.force_gain_v_per_n = p.controller.force_gain_v_per_n;
  k_.piston_area_m2 = p.actuator.piston_area_m2;
  k_.pilot_gain_m3_per_s2_per_v = valve.pilot_flow_gain_m3_per_s_per_v / valve.pilot_time_constant_s;
  k_.spool_feedback_v = valve.spool_lvdt_gain_v_per_m * valve.max_spool_stroke_m;
  k_.pilot_rate_per_s = 1.0 / valve.pilot_time_constant_s;
  k_.opening_per_m3 = 1.0 / (valve.main_spool_area_m2 * valve.max_spool_stroke_m);
  k_.rolloff_squared = p.flow.nonlinear_flow_gain ? p.flow.flow_gain_rolloff * p.flow.flow_gain_rolloff : 0.0;
  k_.load_pressure_per_pa = p.flow.load_pressure_effect ? 1.0 / p.flow.supply_pressure_pa : 0.0;
  const double compressibility = p.actuator.compressibility_m5_per_n();
  k_.flow_gain_per_compressibility = p.flow.no_load_flow_gain_m3_per_s / compressibility;
  k_.area_per_compressibility = p.actuator.piston_area_m2 / compressibility;
  k_.leakage_per_compressibility = p.actuator.leakage_m3_per_s_per_pa / compressibility;
  k_.stiffness = p.specimen.stiffness;
  k_.damping_n_s_per_m = p.specimen.damping_n_s_per_m();
  k_.inverse_mass_per_kg = 1.0 / p.specimen.mass_kg;
  k_.area_per_mass = p.actuator.piston_area_m2 / p.specimen.mass_kg;
  k_.friction_per_mass = p.specimen.friction_force_n / p.specimen.mass_kg;
  k_.friction_per_velocity_s_per_m = 1.0 / p.specimen.friction_regularisation_velocity_m_per_s;
  reset(0.0);
}

void ServoHydraulicPlant::reset(double displacement_m) {
  // At rest the chambers carry the spring force and the outside load, and the spool is open
  // just enough to replace the leakage flow; the pilot flow is zero.
  const auto& p = parameters_;
  const double load_pressure =
      (spring_force_n(p.specimen.stiffness, displacement_m) + external_load_n_) / p.actuator.piston_area_m2;
  const double leakage_flow = p.actuator.leakage_m3_per_s_per_pa * load_pressure;
  state_ = State::Zero();
  state_[kLoadPressure] = load_pressure;
  state_[kDisplacement] = displacement_m;
  const double drop = p.flow.load_pressure_effect && load_pressure != 0.0
                          ? 1.0 - std::abs(load_pressure) / p.flow.supply_pressure_pa
                          : 1.0;
  const double flow_per_opening = p.flow.no_load_flow_gain_m3_per_s * std::sqrt(std::max(drop, 1e-6));
  state_[kSpoolOpening] = std::clamp(leakage_flow / flow_per_opening, -1.0, 1.0);
  time_s_ = 0.0;
}

// The whole physics; inline so that RK4's four evaluations are one straight piece of code.
// The two slow links of a stage, the square root of the valve flow and the friction's tanh,
// are kept apart (Terms) so that the next stage's pressure and velocity can be formed with
// one product and one sum after them (see rk4_step).
inline ServoHydraulicPlant::Terms ServoHydraulicPlant::terms(const Rates& s, double command_m,
                                                             double command_rate_m_per_s) const {
  const double opening = s[kSpoolOpening];
  const double pilot_flow = s[kPilotFlow];
  const double load_pressure = s[kLoadPressure];
  const double x = s[kDisplacement];
  const double xdot = s[kVelocity];
  Terms t;

  const double valve_command_v =
      in_force_ ? k_.force_gain_v_per_n * (command_m - k_.piston_area_m2 * load_pressure)
                : k_.position_gain_v_per_m * (command_m - x) + k_.rate_gain_v_s_per_m * (command_rate_m_per_s - xdot);
  const double pilot_flow_rate = k_.pilot_gain_m3_per_s2_per_v * (valve_command_v - k_.spool_feedback_v * opening) -
                                 k_.pilot_rate_per_s * pilot_flow;
  double opening_rate = k_.opening_per_m3 * pilot_flow;
  if ((opening >= 1.0 && opening_rate > 0.0) || (opening <= -1.0 && opening_rate < 0.0)) opening_rate = 0.0;

  // Q_L = K_v0 x_v sqrt(drop / (1 + (r x_v)^2)): the load-pressure drop and the flow-gain
  // roll-off under one square root. Flow stops when the load opposes with the full supply
  // pressure; an aiding load can at most double the valve drop. With a term switched off its
  // factor is exactly 1.
  // From one RK4 stage to the next the pressure is on the longest chain of dependent
  // operations (pressure, drop, root, pressure rate, next stage's pressure), so everything
  // that does not depend on it (the roll-off, the signs, the other flows) is formed first:
  // rolloff * drop = rolloff - (rolloff sgn(x_v) / P_s) P_L, clamped to [0, 2 rolloff].
  const double rolloff = 1.0 / (1.0 + k_.rolloff_squared * (opening * opening));
  const double opposing_per_pa = (opening > 0.0 ? rolloff : -rolloff) * k_.load_pressure_per_pa;
  t.root = std::sqrt(std::clamp(rolloff - opposing_per_pa * load_pressure, 0.0, 2.0 * rolloff));
  t.root_coefficient = k_.flow_gain_per_compressibility * opening;
  t.other_flows = k_.area_per_compressibility * xdot + k_.leakage_per_compressibility * load_pressure;

  // The same for the velocity, whose chain runs through the friction's tanh.
  t.other_forces =
      k_.area_per_mass * load_pressure -
      (spring_force_n(k_.stiffness, x) + k_.damping_n_s_per_m * xdot + external_load_n_) * k_.inverse_mass_per_kg;
  t.friction_tanh = k_.friction_per_mass == 0.0 ? 0.0 : regularised_tanh(xdot * k_.friction_per_velocity_s_per_m);

  t.rate = {opening_rate, pilot_flow_rate, t.root_coefficient * t.root - t.other_flows, xdot,
            t.other_forces - k_.friction_per_mass * t.friction_tanh};
  return t;
}

// The next stage's state y + c k. The pressure and the velocity take the slow link last:
// y + c (a root - b) = (y - c b) + (c a) root, and likewise for the friction, so that only a
// product and a sum follow the root and the tanh (equal to y + c k up to round-off).
inline ServoHydraulicPlant::Rates ServoHydraulicPlant::stage_state(const Rates& y, double c, const Terms& t) const {
  return {y[kSpoolOpening] + c * t.rate[kSpoolOpening], y[kPilotFlow] + c * t.rate[kPilotFlow],
          (y[kLoadPressure] - c * t.other_flows) + (c * t.root_coefficient) * t.root,
          y[kDisplacement] + c * t.rate[kDisplacement],
          (y[kVelocity] + c * t.other_forces) - (c * k_.friction_per_mass) * t.friction_tanh};
}

ServoHydraulicPlant::State ServoHydraulicPlant::derivative(const State& state, double command_m,
                                                           double command_rate_m_per_s) const {
  const Terms t = terms({state[0], state[1], state[2], state[3], state[4]}, command_m, command_rate_m_per_s);
  return State(t.rate.data());
}

// Plain arrays rather than Eigen's 5-vectors here: with everything inlined the state stays in
// registers, where packed 2-wide Eigen operations would bounce each stage through memory.
void ServoHydraulicPlant::rk4_step(Rates& y, double h, double u0, double command_rate) const {
  const double half = 0.5 * h;
  const Terms t1 = terms(y, u0, command_rate);
  const Terms t2 = terms(stage_state(y, half, t1), u0 + half * command_rate, command_rate);
  const Terms t3 = terms(stage_state(y, half, t2), u0 + half * command_rate, command_rate);
  const Terms t4 = terms(stage_state(y, h, t3), u0 + h * command_rate, command_rate);
  const double sixth = h / 6.0;
  for (std::size_t i = 0; i < y.size(); ++i) {
    y[i] += sixth * (t1.rate[i] + 2.0 * t2.rate[i] + 2.0 * t3.rate[i] + t4.rate[i]);
  }
  y[kSpoolOpening] = std::clamp(y[kSpoolOpening], -1.0, 1.0);  // the spool's stops
  // The piston's end stops: it stays at the end cap and stops moving outward there.
  if (std::abs(y[kDisplacement]) >= stroke_m_) {
    y[kDisplacement] = std::copysign(stroke_m_, y[kDisplacement]);
    if (y[kVelocity] * y[kDisplacement] > 0.0) y[kVelocity] = 0.0;
  }
}

void ServoHydraulicPlant::advance(double command_start_m, double command_end_m, double duration_s) {
  in_force_ = false;
  integrate(command_start_m, command_end_m, duration_s);
}

void ServoHydraulicPlant::advance_in_force(double force_start_n, double force_end_n, double duration_s) {
  in_force_ = true;
  integrate(force_start_n, force_end_n, duration_s);
  in_force_ = false;
}

void ServoHydraulicPlant::integrate(double command_start, double command_end, double duration_s) {
  if (!(duration_s > 0.0)) return;
  // Whole substeps no longer than the plant's step, so that the interval is covered exactly.
  const int substeps = detail::substeps(duration_s / max_step_s_);
  const double h = duration_s / substeps;
  const double command_rate = (command_end - command_start) / duration_s;
  Rates y{state_[0], state_[1], state_[2], state_[3], state_[4]};
  for (int i = 0; i < substeps; ++i) {
    rk4_step(y, h, command_start + command_rate * (i * h), command_rate);
  }
  state_ = State(y.data());
  time_s_ += duration_s;
}

PlantMeasurement ServoHydraulicPlant::measure() const {
  const double x = state_[kDisplacement];
  return {x, parameters_.actuator.piston_area_m2 * state_[kLoadPressure], std::abs(x) >= stroke_m_,
          std::abs(state_[kSpoolOpening]) >= 1.0};
}

}  // namespace rpsd::servo
