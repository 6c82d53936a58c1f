#include "rpsd/studies/servo_studies.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rpsd/servo/harmonic_fit.h"
#include "rpsd/servo/linear_analysis.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/servo/simulated_frequency_response.h"

namespace rpsd::studies {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

Response response_of(std::complex<double> g) { return {std::abs(g), std::arg(g) * 180.0 / std::numbers::pi}; }

// Linear sweep: f(t) = f0 + (f1 - f0) t / T, phase = 2 pi (f0 t + (f1 - f0) t^2 / 2T).
struct LinearSweep {
  double f0, f1, duration;
  double frequency(double t) const { return f0 + (f1 - f0) * t / duration; }
  double phase(double t) const { return kTwoPi * (f0 * t + 0.5 * (f1 - f0) * t * t / duration); }
  double time_of(double f) const { return (f - f0) / (f1 - f0) * duration; }
};

// Fit of the simulated response over three cycles centred where the sweep passes f.
Response sweep_response_at(const SineSweepResult& r, const LinearSweep& sweep, double amplitude_m, double f) {
  const double centre = sweep.time_of(f), half_window = 1.5 / f;
  std::vector<double> phase, response;
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    if (std::abs(r.time_s[i] - centre) <= half_window) {
      phase.push_back(sweep.phase(r.time_s[i]));
      response.push_back(r.displacement_m[i]);
    }
  }
  const servo::HarmonicFit fit = servo::fit_harmonic(phase, response);
  return {fit.amplitude / amplitude_m, fit.phase_rad * 180.0 / std::numbers::pi};
}

SweepComparison linear_models_at(const servo::ServoSystemParameters& p, double f) {
  SweepComparison c;
  c.frequency_hz = f;
  c.eq8 = response_of(servo::command_to_displacement(p, servo::LinearModel::kPaperEq8).at_frequency_hz(f));
  c.full_linear = response_of(servo::command_to_displacement(p, servo::LinearModel::kFullLinear).at_frequency_hz(f));
  c.first_order = response_of(servo::first_order_approximation(p).at_frequency_hz(f));
  return c;
}

}  // namespace

SineSweepResult run_sine_sweep(const SineSweepStudy& study) {
  const LinearSweep sweep{study.start_frequency_hz, study.end_frequency_hz, study.duration_s};
  servo::ServoHydraulicPlant plant(study.servo);
  const double dt = 1.0 / study.command_rate_hz;
  const auto steps = static_cast<std::size_t>(std::llround(study.duration_s * study.command_rate_hz));

  SineSweepResult r;
  for (auto* column : {&r.time_s, &r.frequency_hz, &r.command_m, &r.displacement_m, &r.force_n, &r.spool_opening}) {
    column->reserve(steps + 1);
  }
  const auto record = [&](double t, double command) {
    const servo::PlantMeasurement m = plant.measure();
    r.time_s.push_back(t);
    r.frequency_hz.push_back(sweep.frequency(t));
    r.command_m.push_back(command);
    r.displacement_m.push_back(m.displacement_m);
    r.force_n.push_back(m.force_n);
    r.spool_opening.push_back(plant.spool_opening());
    r.max_spool_opening = std::max(r.max_spool_opening, std::abs(plant.spool_opening()));
    r.peak_force_n = std::max(r.peak_force_n, std::abs(m.force_n));
  };

  plant.reset(0.0);
  double command = 0.0;
  record(0.0, command);
  for (std::size_t i = 1; i <= steps; ++i) {
    const double t = i * dt;
    const double next = study.amplitude_m * std::sin(sweep.phase(t));
    plant.advance(command, next, dt);
    command = next;
    record(t, command);
  }

  for (double f : study.report_frequencies_hz) {
    SweepComparison c = linear_models_at(study.servo, f);
    c.sweep = sweep_response_at(r, sweep, study.amplitude_m, f);
    servo::ServoHydraulicPlant steady(study.servo);
    servo::SineTest test;
    test.amplitude_m = study.amplitude_m;
    test.frequency_hz = f;
    test.control_rate_hz = study.command_rate_hz;
    test.settling_time_s = 2.0;
    test.fitted_cycles = std::max(2, static_cast<int>(std::ceil(2.0 * f)));
    c.steady_state = response_of(servo::simulated_frequency_response(steady, test));
    r.report.push_back(c);
  }
  // The fit needs three whole cycles inside the sweep.
  for (double f = 0.25; f < study.end_frequency_hz; f += 0.25) {
    if (sweep.time_of(f) - 1.5 / f < 0.0 || sweep.time_of(f) + 1.5 / f > study.duration_s) continue;
    SweepComparison c = linear_models_at(study.servo, f);
    c.sweep = sweep_response_at(r, sweep, study.amplitude_m, f);
    r.curve.push_back(c);
  }
  return r;
}

std::vector<FrequencyResponseRow> run_frequency_response(const FrequencyResponseStudy& study) {
  const auto eq8 = servo::command_to_displacement(study.servo, servo::LinearModel::kPaperEq8);
  const auto full = servo::command_to_displacement(study.servo, servo::LinearModel::kFullLinear);
  const auto first_order = servo::first_order_approximation(study.servo);
  std::vector<FrequencyResponseRow> rows;
  for (double f : study.frequencies_hz) {
    const auto lead = compensation::phase_lead_response(study.phase_lead, kTwoPi * f);
    FrequencyResponseRow row;
    row.frequency_hz = f;
    row.eq8 = response_of(eq8.at_frequency_hz(f));
    row.first_order = response_of(first_order.at_frequency_hz(f));
    row.compensated = response_of(lead * eq8.at_frequency_hz(f));
    row.full_linear = response_of(full.at_frequency_hz(f));
    row.full_linear_compensated = response_of(lead * full.at_frequency_hz(f));
    rows.push_back(row);
  }
  return rows;
}

std::vector<MaxGainRow> run_max_gain(const MaxGainStudy& study) {
  std::vector<MaxGainRow> rows;
  for (double mass : study.masses_kg) {
    const auto p = servo::with_attached_mass(study.servo, mass);
    rows.push_back({mass, servo::max_stable_p_gain(p, servo::LinearModel::kPaperEq8),
                    servo::max_stable_p_gain_from_eigenvalues(p), servo::oil_column_frequency_rad_s(p) / kTwoPi});
  }
  return rows;
}

}  // namespace rpsd::studies
