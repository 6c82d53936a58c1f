#include "rpsd/servo/linear_analysis.h"

#include <cmath>
#include <numbers>

#include "rpsd/servo/routh.h"
#include "rpsd/servo/servo_hydraulic_plant.h"

namespace rpsd::servo {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

// (C_l + K_a s)(k + c s + m s^2) + A^2 s: the open hydraulics and specimen of Eq. 8.
Polynomial hydraulics_and_specimen(const ServoSystemParameters& p) {
  const auto& act = p.actuator;
  const Polynomial chambers{act.leakage_m3_per_s_per_pa, act.compressibility_m5_per_n()};
  const Polynomial specimen{p.specimen.stiffness.initial_n_per_m, p.specimen.damping_n_s_per_m(), p.specimen.mass_kg};
  const double area = act.piston_area_m2;
  return chambers * specimen + Polynomial{0.0, area * area};
}

// A K_v C_F: flow into the actuator per unit spool opening per metre of error, times A.
double loop_gain_factor(const ServoSystemParameters& p) {
  return p.actuator.piston_area_m2 * p.flow.no_load_flow_gain_m3_per_s * p.sensors.lvdt_gain_v_per_m;
}

}  // namespace

TransferFunction command_to_displacement(const ServoSystemParameters& p, LinearModel model) {
  const Polynomial open = hydraulics_and_specimen(p);
  if (model == LinearModel::kPaperEq8) {
    const Polynomial numerator{loop_gain_factor(p) * p.servovalve.static_gain_per_v() * p.controller.proportional_gain};
    return {numerator, open + numerator};
  }
  // H_s = (K_vp / x_vmax) / (tau A_v s^2 + A_v s + K_3 K_vp), H_c = G_p + G_d s.
  const auto& v = p.servovalve;
  const Polynomial valve_denominator{v.spool_lvdt_gain_v_per_m * v.pilot_flow_gain_m3_per_s_per_v, v.main_spool_area_m2,
                                     v.pilot_time_constant_s * v.main_spool_area_m2};
  const double valve_numerator = v.pilot_flow_gain_m3_per_s_per_v / v.max_spool_stroke_m;
  const Polynomial controller{p.controller.proportional_gain, p.controller.derivative_gain_s};
  const Polynomial numerator = controller * (loop_gain_factor(p) * valve_numerator);
  return {numerator, valve_denominator * open + numerator};
}

TransferFunction first_order_approximation(const ServoSystemParameters& p) {
  return {Polynomial{1.0}, Polynomial{1.0, 1.0 / cutoff_frequency_rad_s(p)}};
}

double cutoff_frequency_rad_s(const ServoSystemParameters& p) {
  return p.flow.no_load_flow_gain_m3_per_s * p.sensors.lvdt_gain_v_per_m * p.servovalve.static_gain_per_v() *
         p.controller.proportional_gain / p.actuator.piston_area_m2;
}

double response_delay_s(const ServoSystemParameters& p) { return 1.0 / cutoff_frequency_rad_s(p); }

double amplitude_reduction(const ServoSystemParameters& p, double frequency_hz) {
  const double ratio = kTwoPi * frequency_hz / cutoff_frequency_rad_s(p);
  return 1.0 - 1.0 / std::sqrt(1.0 + ratio * ratio);
}

double oil_column_frequency_rad_s(const ServoSystemParameters& p) {
  const double area = p.actuator.piston_area_m2;
  return std::sqrt(area * area / (p.specimen.mass_kg * p.actuator.compressibility_m5_per_n()));
}

ServoSystemParameters with_p_gain(const ServoSystemParameters& p, double proportional_gain) {
  ServoSystemParameters q = p;
  q.controller.proportional_gain = proportional_gain;
  return q;
}

ServoSystemParameters with_attached_mass(const ServoSystemParameters& p, double mass_kg) {
  ServoSystemParameters q = p;
  q.specimen.mass_kg = mass_kg;
  const double k = p.specimen.stiffness.initial_n_per_m;
  if (k > 0.0) q.specimen.damping_ratio = p.specimen.damping_n_s_per_m() / (2.0 * std::sqrt(k * mass_kg));
  return q;
}

ServoSystemParameters linearised(const ServoSystemParameters& p) {
  ServoSystemParameters q = p;
  q.flow.nonlinear_flow_gain = false;
  q.flow.load_pressure_effect = false;
  q.specimen.friction_force_n = 0.0;
  q.specimen.stiffness.change_displacement_m = 0.0;
  return q;
}

namespace {
// Gains far above any practical setting; the search stops there.
double gain_search_bound(const ServoSystemParameters& p) { return 1e4 * p.controller.proportional_gain; }
}  // namespace

double max_stable_p_gain(const ServoSystemParameters& p, LinearModel model) {
  return largest_stable_gain(
      [&](double gain) {
        return routh_hurwitz_stable(command_to_displacement(with_p_gain(p, gain), model).denominator);
      },
      gain_search_bound(p));
}

double max_stable_p_gain_closed_form(const ServoSystemParameters& p) {
  const double ka = p.actuator.compressibility_m5_per_n();
  const double cl = p.actuator.leakage_m3_per_s_per_pa;
  const double area = p.actuator.piston_area_m2;
  const double m = p.specimen.mass_kg;
  const double c = p.specimen.damping_n_s_per_m();
  const double k = p.specimen.stiffness.initial_n_per_m;
  const double a3 = ka * m;
  const double a2 = ka * c + cl * m;
  const double a1 = ka * k + cl * c + area * area;
  return (a2 * a1 / a3 - cl * k) / (loop_gain_factor(p) * p.servovalve.static_gain_per_v());
}

Eigen::MatrixXd linearised_state_matrix(const ServoSystemParameters& p) {
  const ServoHydraulicPlant plant(linearised(p));
  using State = ServoHydraulicPlant::State;
  const State rest = State::Zero();
  // The linearised model is exactly linear, so a central difference is exact up to
  // rounding; each state is perturbed on its own natural scale.
  State scale;
  scale << 1e-3, 1e-3 * p.flow.no_load_flow_gain_m3_per_s, 1e3, 1e-4, 1e-3;
  Eigen::MatrixXd jacobian(5, 5);
  for (int j = 0; j < 5; ++j) {
    State plus = rest, minus = rest;
    plus[j] += scale[j];
    minus[j] -= scale[j];
    jacobian.col(j) = (plant.derivative(plus, 0.0, 0.0) - plant.derivative(minus, 0.0, 0.0)) / (2.0 * scale[j]);
  }
  return jacobian;
}

double max_stable_p_gain_from_eigenvalues(const ServoSystemParameters& p) {
  return largest_stable_gain(
      [&](double gain) {
        const Eigen::MatrixXd a = linearised_state_matrix(with_p_gain(p, gain));
        return balanced_eigenvalues(a).real().maxCoeff() < 0.0;
      },
      gain_search_bound(p), 1e-7);
}

ServoAnalysis analyze(const ServoSystemParameters& p) {
  p.validate();
  ServoAnalysis a;
  a.cutoff_frequency_hz = cutoff_frequency_rad_s(p) / kTwoPi;
  a.response_delay_ms = 1e3 * response_delay_s(p);
  a.amplitude_reduction_at_2hz = amplitude_reduction(p, 2.0);
  a.oil_column_frequency_hz = oil_column_frequency_rad_s(p) / kTwoPi;
  a.max_stable_p_gain = max_stable_p_gain(p, LinearModel::kPaperEq8);
  a.max_stable_p_gain_full_model = max_stable_p_gain_from_eigenvalues(p);
  a.p_gain = p.controller.proportional_gain;
  a.static_gain = command_to_displacement(p, LinearModel::kPaperEq8).static_gain();
  a.specimen_natural_frequency_hz = p.specimen.natural_frequency_rad_s() / kTwoPi;
  a.servovalve_natural_frequency_hz = p.servovalve.natural_frequency_rad_s() / kTwoPi;
  a.servovalve_damping_ratio = p.servovalve.damping_ratio();
  return a;
}

}  // namespace rpsd::servo
