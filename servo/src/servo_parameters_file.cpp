#include <stdexcept>

#include "rpsd/servo/servo_parameters.h"

namespace rpsd::servo {
namespace {

// Every bound lies far beyond any servo-hydraulic rig (1000 bar, 10 m of stroke, a 1 s
// pilot stage) and is there to catch a typing or unit error.
using config::Number;

ControllerParameters read_controller(config::Source& r) {
  ControllerParameters c;
  c.proportional_gain =
      r.number("proportional_gain", Number{"V/V", "G_p, valve command volts per error volt", 0.0, 1e4, true});
  c.derivative_gain_s = r.number_or("derivative_gain_s", 0.0, Number::between(0.0, 10.0, "s", "G_d"));
  c.force_gain_v_per_n = r.number_or(
      "force_gain_v_per_n", 0.0,
      Number::between(0.0, 1.0, "V/N",
                      "G_f, valve command volts per newton of force error in force control; 0: no force loop"));
  r.finish();
  return c;
}

ServovalveParameters read_servovalve(config::Source& r) {
  ServovalveParameters v;
  v.pilot_time_constant_s =
      r.number("pilot_time_constant_s", Number{"s", "tau, the pilot stage's time constant", 0.0, 1.0, true});
  v.pilot_flow_gain_m3_per_s_per_v =
      r.number("pilot_flow_gain_m3_per_s_per_v", Number{"m^3/(s V)", "K_vp, pilot flow per volt", 0.0, 1.0, true});
  v.main_spool_area_m2 =
      r.number("main_spool_area_m2", Number{"m^2", "A_v, the main spool's end area", 0.0, 1.0, true});
  v.spool_lvdt_gain_v_per_m =
      r.number("spool_lvdt_gain_v_per_m", Number{"V/m", "K_3, the spool LVDT's gain", 0.0, 1e6, true});
  v.max_spool_stroke_m =
      r.number("max_spool_stroke_m", Number{"m", "x_vmax, the spool's full opening", 0.0, 0.1, true});
  r.finish();
  return v;
}

ValveFlowParameters read_flow(config::Source& r) {
  ValveFlowParameters f;
  f.no_load_flow_gain_m3_per_s = r.number("no_load_flow_gain_m3_per_s",
                                          Number{"m^3/s", "K_v0, flow at full opening without load", 0.0, 10.0, true});
  f.flow_gain_rolloff =
      r.number("flow_gain_rolloff", Number::between(0.0, 1e3, "", "r in K_v = K_v0 / sqrt(1 + (r x_v)^2)"));
  f.supply_pressure_pa = r.number("supply_pressure_pa", Number{"Pa", "P_s, the supply pressure", 0.0, 1e8, true});
  f.nonlinear_flow_gain = r.boolean_or("nonlinear_flow_gain", true, "the flow gain falls as the opening grows");
  f.load_pressure_effect = r.boolean_or("load_pressure_effect", true, "the square-root load-pressure term of the flow");
  r.finish();
  return f;
}

ActuatorParameters read_actuator(config::Source& r) {
  ActuatorParameters a;
  a.piston_area_m2 = r.number("piston_area_m2", Number{"m^2", "A, the piston's area", 0.0, 10.0, true});
  a.stroke_m = r.number("stroke_m", Number{"m", "half the stroke (the piston moves +/- this)", 0.0, 10.0, true});
  a.oil_volume_m3 = r.number("oil_volume_m3", Number{"m^3", "V_t, both chambers and their passages", 0.0, 10.0, true});
  a.bulk_modulus_pa =
      r.number("bulk_modulus_pa", Number{"Pa", "beta_e, the oil's effective bulk modulus", 0.0, 1e10, true});
  a.leakage_m3_per_s_per_pa =
      r.number("leakage_m3_per_s_per_pa", Number::between(0.0, 1e-6, "m^3/(s Pa)", "C_l, total leakage"));
  r.finish();
  return a;
}

SpecimenStiffness read_stiffness(config::Source& r) {
  SpecimenStiffness s;
  s.initial_n_per_m =
      r.number("initial_n_per_m", Number::between(0.0, 1e13, "N/m", "the specimen's initial stiffness"));
  s.change_displacement_m = r.number_or("change_displacement_m", 0.0,
                                        Number::between(0.0, 10.0, "m", "where the stiffness changes (0: linear)"));
  const auto secondary = r.optional_number(
      "secondary_n_per_m", Number::between(0.0, 1e13, "N/m", "the stiffness beyond change_displacement_m"));
  r.finish();
  if (s.change_displacement_m > 0.0) {
    if (!secondary) r.fail("secondary_n_per_m", "required key is missing (change_displacement_m > 0)");
    s.secondary_n_per_m = *secondary;
  } else if (secondary) {
    r.fail("secondary_n_per_m", "needs change_displacement_m > 0 (the displacement where the stiffness changes)");
  }
  return s;
}

SpecimenParameters read_specimen(config::Source& r) {
  SpecimenParameters s;
  s.mass_kg = r.number("mass_kg", Number{"kg", "the moving mass, the piston's included", 0.0, 1e9, true});
  s.stiffness = read_stiffness(*r.section("stiffness", "elastic, linear or bilinear"));
  s.damping_ratio =
      r.number_or("damping_ratio", 0.0, Number::between(0.0, 1.0, "", "viscous, of the initial stiffness and mass"));
  s.friction_force_n = r.number_or("friction_force_n", 0.0, Number::between(0.0, 1e9, "N", "Coulomb friction"));
  s.friction_regularisation_velocity_m_per_s = r.number_or(
      "friction_regularisation_velocity_m_per_s", s.friction_regularisation_velocity_m_per_s,
      Number{"m/s", "v_reg in tanh(v / v_reg), which smooths the friction for integration", 0.0, 10.0, true});
  r.finish();
  return s;
}

}  // namespace

ServoSystemParameters read_servo_parameters(config::Source& file) {
  ServoSystemParameters p;
  p.name = file.text("name", "the rig's name, for titles");
  p.controller = read_controller(*file.section("controller", "the servo controller (Eq. 1)"));
  p.servovalve = read_servovalve(*file.section("servovalve", "the three-stage servovalve (Eq. 2)"));
  p.flow = read_flow(*file.section("flow", "the valve flow (Eq. 3)"));
  p.actuator = read_actuator(*file.section("actuator", "the actuator's chambers (Eq. 4)"));
  {
    const auto sensors = file.section("sensors", "the displacement transducer");
    p.sensors.lvdt_gain_v_per_m =
        sensors->number("lvdt_gain_v_per_m", Number{"V/m", "C_F, the LVDT's gain", 0.0, 1e6, true});
    sensors->finish();
  }
  p.specimen = read_specimen(*file.section("specimen", "what the actuator drives"));
  if (const auto simulation = file.optional_section("simulation", "how the plant is integrated")) {
    p.plant_rate_hz =
        simulation->number_or("plant_rate_hz", p.plant_rate_hz,
                              Number::between(1e3, 1e6, "Hz", "fixed-step RK4 rate of the continuous plant"));
    simulation->finish();
  }
  file.finish();
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    file.fail_section(e.what());
  }
  return p;
}

ServoSystemParameters ServoSystemParameters::read(config::Source& section, double) {
  const auto file = section.file("parameters", "the servo-system parameter file (examples/servo/paper-mts-244.yaml)");
  return read_servo_parameters(*file);
}

}  // namespace rpsd::servo
