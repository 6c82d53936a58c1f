#include "rpsd/servo/servo_parameters.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::servo {

double ServovalveParameters::natural_frequency_rad_s() const {
  // tau A_v s^2 + A_v s + K_3 K_vp: omega^2 = K_3 K_vp / (tau A_v)
  return std::sqrt(spool_lvdt_gain_v_per_m * pilot_flow_gain_m3_per_s_per_v /
                   (pilot_time_constant_s * main_spool_area_m2));
}

double ServovalveParameters::damping_ratio() const {
  // 2 zeta omega = 1 / tau
  return 1.0 / (2.0 * pilot_time_constant_s * natural_frequency_rad_s());
}

double ValveFlowParameters::flow_gain_at(double spool_opening) const {
  if (!nonlinear_flow_gain) return no_load_flow_gain_m3_per_s;
  const double r = flow_gain_rolloff * spool_opening;
  return no_load_flow_gain_m3_per_s / std::sqrt(1.0 + r * r);
}

double SpecimenParameters::damping_n_s_per_m() const {
  return 2.0 * damping_ratio * std::sqrt(stiffness.initial_n_per_m * mass_kg);
}

double SpecimenParameters::natural_frequency_rad_s() const { return std::sqrt(stiffness.initial_n_per_m / mass_kg); }

namespace {
void require(bool ok, const char* field, const char* what) {
  if (!ok) throw std::invalid_argument(std::string(field) + ": " + what);
}
void require_positive(double v, const char* field) {
  require(std::isfinite(v) && v > 0.0, field, "must be a positive number");
}
void require_non_negative(double v, const char* field) {
  require(std::isfinite(v) && v >= 0.0, field, "must be zero or positive");
}
}  // namespace

void ServoSystemParameters::validate() const {
  require_positive(controller.proportional_gain, "controller.proportional_gain");
  require_non_negative(controller.derivative_gain_s, "controller.derivative_gain_s");
  require_non_negative(controller.force_gain_v_per_n, "controller.force_gain_v_per_n");
  require_positive(servovalve.pilot_time_constant_s, "servovalve.pilot_time_constant_s");
  require_positive(servovalve.pilot_flow_gain_m3_per_s_per_v, "servovalve.pilot_flow_gain_m3_per_s_per_v");
  require_positive(servovalve.main_spool_area_m2, "servovalve.main_spool_area_m2");
  require_positive(servovalve.spool_lvdt_gain_v_per_m, "servovalve.spool_lvdt_gain_v_per_m");
  require_positive(servovalve.max_spool_stroke_m, "servovalve.max_spool_stroke_m");
  require_positive(flow.no_load_flow_gain_m3_per_s, "flow.no_load_flow_gain_m3_per_s");
  require_non_negative(flow.flow_gain_rolloff, "flow.flow_gain_rolloff");
  require_positive(flow.supply_pressure_pa, "flow.supply_pressure_pa");
  require_positive(actuator.piston_area_m2, "actuator.piston_area_m2");
  require_positive(actuator.oil_volume_m3, "actuator.oil_volume_m3");
  require_positive(actuator.bulk_modulus_pa, "actuator.bulk_modulus_pa");
  require_non_negative(actuator.leakage_m3_per_s_per_pa, "actuator.leakage_m3_per_s_per_pa");
  require_positive(actuator.stroke_m, "actuator.stroke_m");
  require_positive(sensors.lvdt_gain_v_per_m, "sensors.lvdt_gain_v_per_m");
  require_positive(specimen.mass_kg, "specimen.mass_kg");
  require_non_negative(specimen.stiffness.initial_n_per_m, "specimen.stiffness.initial_n_per_m");
  require_non_negative(specimen.stiffness.change_displacement_m, "specimen.stiffness.change_displacement_m");
  require_non_negative(specimen.stiffness.secondary_n_per_m, "specimen.stiffness.secondary_n_per_m");
  require_non_negative(specimen.damping_ratio, "specimen.damping_ratio");
  require_non_negative(specimen.friction_force_n, "specimen.friction_force_n");
  require_positive(specimen.friction_regularisation_velocity_m_per_s,
                   "specimen.friction_regularisation_velocity_m_per_s");
  require(plant_rate_hz >= 1e3 && plant_rate_hz <= 1e6, "plant_rate_hz", "must be from 1e3 to 1e6 Hz");
  // The spool loop must be resolved by the fixed step (RK4 is stable to |lambda dt| ~ 2.8).
  require(servovalve.natural_frequency_rad_s() / plant_rate_hz < 0.5, "plant_rate_hz",
          "too low to resolve the servovalve spool loop (need rate > 2 x spool natural frequency in rad/s)");
}

Envelope ServoSystemParameters::envelope() const {
  return {actuator.stroke_m, flow.supply_pressure_pa * actuator.piston_area_m2,
          flow.flow_gain_at(1.0) / actuator.piston_area_m2};
}

}  // namespace rpsd::servo
