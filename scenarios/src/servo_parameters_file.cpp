#include "rpsd/scenarios/servo_parameters_file.h"

#include <stdexcept>

#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace {

servo::ControllerParameters read_controller(MappingReader r) {
  servo::ControllerParameters c;
  c.proportional_gain = r.positive_number("proportional_gain");
  c.derivative_gain_s = r.non_negative_number_or("derivative_gain_s", 0.0);
  r.finish();
  return c;
}

servo::ServovalveParameters read_servovalve(MappingReader r) {
  servo::ServovalveParameters v;
  v.pilot_time_constant_s = r.positive_number("pilot_time_constant_s");
  v.pilot_flow_gain_m3_per_s_per_v = r.positive_number("pilot_flow_gain_m3_per_s_per_v");
  v.main_spool_area_m2 = r.positive_number("main_spool_area_m2");
  v.spool_lvdt_gain_v_per_m = r.positive_number("spool_lvdt_gain_v_per_m");
  v.max_spool_stroke_m = r.positive_number("max_spool_stroke_m");
  r.finish();
  return v;
}

servo::ValveFlowParameters read_flow(MappingReader r) {
  servo::ValveFlowParameters f;
  f.no_load_flow_gain_m3_per_s = r.positive_number("no_load_flow_gain_m3_per_s");
  f.flow_gain_rolloff = r.non_negative_number("flow_gain_rolloff");
  f.supply_pressure_pa = r.positive_number("supply_pressure_pa");
  f.nonlinear_flow_gain = r.boolean_or("nonlinear_flow_gain", true);
  f.load_pressure_effect = r.boolean_or("load_pressure_effect", true);
  r.finish();
  return f;
}

servo::ActuatorParameters read_actuator(MappingReader r) {
  servo::ActuatorParameters a;
  a.piston_area_m2 = r.positive_number("piston_area_m2");
  a.stroke_m = r.positive_number("stroke_m");
  a.oil_volume_m3 = r.positive_number("oil_volume_m3");
  a.bulk_modulus_pa = r.positive_number("bulk_modulus_pa");
  a.leakage_m3_per_s_per_pa = r.non_negative_number("leakage_m3_per_s_per_pa");
  r.finish();
  return a;
}

servo::SpecimenStiffness read_stiffness(MappingReader r) {
  servo::SpecimenStiffness s;
  s.initial_n_per_m = r.non_negative_number("initial_n_per_m");
  s.change_displacement_m = r.non_negative_number_or("change_displacement_m", 0.0);
  if (s.change_displacement_m > 0.0) {
    s.secondary_n_per_m = r.non_negative_number("secondary_n_per_m");
  } else if (r.has("secondary_n_per_m")) {
    r.fail("secondary_n_per_m", "needs change_displacement_m > 0 (the displacement where the stiffness changes)");
  }
  r.finish();
  return s;
}

servo::SpecimenParameters read_specimen(MappingReader r) {
  servo::SpecimenParameters s;
  s.mass_kg = r.positive_number("mass_kg");
  s.stiffness = read_stiffness(r.mapping("stiffness"));
  s.damping_ratio = r.non_negative_number_or("damping_ratio", 0.0);
  s.friction_force_n = r.non_negative_number_or("friction_force_n", 0.0);
  s.friction_regularisation_velocity_m_per_s =
      r.positive_number_or("friction_regularisation_velocity_m_per_s", s.friction_regularisation_velocity_m_per_s);
  r.finish();
  return s;
}

}  // namespace

servo::ServoSystemParameters load_servo_parameters(const std::filesystem::path& file) {
  MappingReader root(load_yaml_file(file), file.string(), "");
  servo::ServoSystemParameters p;
  p.name = root.string("name");
  p.controller = read_controller(root.mapping("controller"));
  p.servovalve = read_servovalve(root.mapping("servovalve"));
  p.flow = read_flow(root.mapping("flow"));
  p.actuator = read_actuator(root.mapping("actuator"));
  {
    MappingReader sensors = root.mapping("sensors");
    p.sensors.lvdt_gain_v_per_m = sensors.positive_number("lvdt_gain_v_per_m");
    sensors.finish();
  }
  p.specimen = read_specimen(root.mapping("specimen"));
  if (auto simulation = root.optional_mapping("simulation")) {
    p.plant_rate_hz = simulation->positive_number_or("plant_rate_hz", p.plant_rate_hz);
    simulation->finish();
  }
  root.finish();
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    throw ConfigError(file.string() + ": " + e.what());
  }
  return p;
}

}  // namespace rpsd::scenarios
