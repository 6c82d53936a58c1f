#include "rpsd/servo/servo_hydraulic_plant.h"

#include <algorithm>
#include <cmath>

#include "rpsd/servo/specimen_forces.h"

namespace rpsd::servo {

ServoHydraulicPlant::ServoHydraulicPlant(const ServoSystemParameters& parameters)
    : parameters_(parameters),
      damping_n_s_per_m_(parameters.specimen.damping_n_s_per_m()),
      compressibility_m5_per_n_(parameters.actuator.compressibility_m5_per_n()),
      max_step_s_(1.0 / parameters.plant_rate_hz) {
  parameters_.validate();
  reset(0.0);
}

void ServoHydraulicPlant::reset(double displacement_m) {
  // At rest the chambers carry the spring force and the spool is open just enough to
  // replace the leakage flow; the pilot flow is zero.
  const auto& p = parameters_;
  const double load_pressure = spring_force_n(p.specimen.stiffness, displacement_m) / p.actuator.piston_area_m2;
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

ServoHydraulicPlant::State ServoHydraulicPlant::derivative(const State& s, double command_m,
                                                           double command_rate_m_per_s) const {
  const auto& p = parameters_;
  const double opening = s[kSpoolOpening];
  const double pilot_flow = s[kPilotFlow];
  const double load_pressure = s[kLoadPressure];
  const double x = s[kDisplacement];
  const double xdot = s[kVelocity];

  const double c_f = p.sensors.lvdt_gain_v_per_m;
  const double valve_command_v = p.controller.proportional_gain * c_f * (command_m - x) +
                                 p.controller.derivative_gain_s * c_f * (command_rate_m_per_s - xdot);

  const auto& valve = p.servovalve;
  const double spool_position_m = valve.max_spool_stroke_m * opening;
  const double pilot_flow_rate =
      (valve.pilot_flow_gain_m3_per_s_per_v * (valve_command_v - valve.spool_lvdt_gain_v_per_m * spool_position_m) -
       pilot_flow) / valve.pilot_time_constant_s;
  double opening_rate = pilot_flow / (valve.main_spool_area_m2 * valve.max_spool_stroke_m);
  if ((opening >= 1.0 && opening_rate > 0.0) || (opening <= -1.0 && opening_rate < 0.0)) opening_rate = 0.0;

  double pressure_factor = 1.0;
  if (p.flow.load_pressure_effect && opening != 0.0) {
    // Flow stops when the load opposes with the full supply pressure; an aiding load can at
    // most double the valve drop.
    const double drop = 1.0 - std::copysign(1.0, opening) * load_pressure / p.flow.supply_pressure_pa;
    pressure_factor = std::sqrt(std::clamp(drop, 0.0, 2.0));
  }
  const double valve_flow = p.flow.flow_gain_at(opening) * opening * pressure_factor;

  const auto& act = p.actuator;
  const double pressure_rate =
      (valve_flow - act.piston_area_m2 * xdot - act.leakage_m3_per_s_per_pa * load_pressure) / compressibility_m5_per_n_;

  const double specimen_force = spring_force_n(p.specimen.stiffness, x) + damping_n_s_per_m_ * xdot +
                                friction_force_n(p.specimen, xdot);
  const double acceleration = (act.piston_area_m2 * load_pressure - specimen_force) / p.specimen.mass_kg;

  State rate;
  rate << opening_rate, pilot_flow_rate, pressure_rate, xdot, acceleration;
  return rate;
}

void ServoHydraulicPlant::apply_spool_stops(State& s) const {
  s[kSpoolOpening] = std::clamp(s[kSpoolOpening], -1.0, 1.0);
}

void ServoHydraulicPlant::rk4_step(double h, double u0, double command_rate) {
  const State k1 = derivative(state_, u0, command_rate);
  const State k2 = derivative(state_ + 0.5 * h * k1, u0 + 0.5 * h * command_rate, command_rate);
  const State k3 = derivative(state_ + 0.5 * h * k2, u0 + 0.5 * h * command_rate, command_rate);
  const State k4 = derivative(state_ + h * k3, u0 + h * command_rate, command_rate);
  state_ += (h / 6.0) * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
  apply_spool_stops(state_);
}

void ServoHydraulicPlant::advance(double command_start_m, double command_end_m, double duration_s) {
  if (!(duration_s > 0.0)) return;
  // Whole substeps no longer than the plant's step, so that the interval is covered exactly.
  const int substeps = std::max(1, static_cast<int>(std::ceil(duration_s / max_step_s_ - 1e-9)));
  const double h = duration_s / substeps;
  const double command_rate = (command_end_m - command_start_m) / duration_s;
  for (int i = 0; i < substeps; ++i) {
    rk4_step(h, command_start_m + command_rate * (i * h), command_rate);
  }
  time_s_ += duration_s;
}

PlantMeasurement ServoHydraulicPlant::measure() const {
  return {state_[kDisplacement], parameters_.actuator.piston_area_m2 * state_[kLoadPressure]};
}

}  // namespace rpsd::servo
