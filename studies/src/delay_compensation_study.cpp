#include "rpsd/studies/delay_compensation_study.h"

#include <cmath>
#include <complex>
#include <cstdio>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "rpsd/compensation/delay_theory.h"
#include "rpsd/compensation/discrete_phase_lead.h"
#include "rpsd/coordinator/run_criteria.h"
#include "rpsd/hybrid_test/hybrid_test_assembly.h"
#include "rpsd/hybrid_test/specimen_sdof.h"
#include "rpsd/output/gnuplot.h"
#include "rpsd/output/provenance.h"
#include "rpsd/output/results_files.h"
#include "rpsd/servo/linear_analysis.h"
#include "rpsd/servo/servo_hydraulic_plant.h"
#include "rpsd/studies/damping_identification.h"

namespace rpsd::studies {
namespace {

using Complex = std::complex<double>;

// The actuator's command-to-displacement response, continuous.
Complex actuator_response(const DelayCompensationStudy& study, Complex s) {
  if (const auto* delay = std::get_if<servo::PureDelayParameters>(&study.plant)) return std::exp(-s * delay->delay_s);
  const auto& servo = std::get<servo::ServoSystemParameters>(study.plant);
  return servo::command_to_displacement(servo, servo::LinearModel::kFullLinear)(s);
}

// Root of m s^2 + c s + k G_c(s) G_a(s) = 0 near `start`, by Newton with a numerical derivative.
Complex loop_root(const DelayCompensationStudy& study, const compensation::PhaseLeadParameters& lead, double c,
                  Complex start) {
  const auto f = [&](Complex s) {
    const Complex gc = (1.0 + lead.ratio_a * lead.time_constant_s * s) / (1.0 + lead.time_constant_s * s);
    return study.mass_kg * s * s + c * s + study.stiffness_n_per_m * gc * actuator_response(study, s);
  };
  Complex s = start;
  for (int i = 0; i < 100; ++i) {
    const Complex h = 1e-7 * std::abs(s);
    const Complex step = f(s) / ((f(s + h) - f(s - h)) / (2.0 * h));
    s -= step;
    if (std::abs(step) < 1e-12 * std::abs(s)) break;
  }
  return s;
}

}  // namespace

std::string delay_case_csv_name(std::size_t index, double compensated_delay_s) {
  char name[64];
  std::snprintf(name, sizeof name, "case_%02zu_compensated_%03.0fms.csv", index, compensated_delay_s * 1e3);
  return name;
}

std::vector<DelayCompensationCase> run_delay_compensation(const DelayCompensationStudy& study,
                                                          const std::filesystem::path& dir) {
  const double omega_n = std::sqrt(study.stiffness_n_per_m / study.mass_kg);
  const double c = 2.0 * study.damping_ratio * std::sqrt(study.stiffness_n_per_m * study.mass_kg);
  const double dt = 1.0 / study.control_rate_hz;
  const compensation::DelayedOscillator oscillator{study.mass_kg, c, 0.0, study.stiffness_n_per_m};
  const double actuator_delay = -std::arg(actuator_response(study, Complex(0.0, omega_n))) / omega_n;

  std::vector<DelayCompensationCase> cases;
  for (std::size_t i = 0; i < study.compensated_delays_s.size(); ++i) {
    DelayCompensationCase k;
    k.compensated_delay_s = study.compensated_delays_s[i];
    const auto lead =
        compensation::DiscretePhaseLeadParameters::for_delay(k.compensated_delay_s, study.phase_lead_ratio_a);
    k.actuator_delay_s = actuator_delay;
    k.compensator_lead_s = std::arg(compensation::discrete_phase_lead_response(lead, dt, omega_n)) / omega_n;
    k.residual_delay_s = k.actuator_delay_s - k.compensator_lead_s;
    const Complex dde = compensation::dominant_root(oscillator, k.residual_delay_s);
    k.predicted_damping_ratio = compensation::damping_ratio_of(dde);
    k.approximate_damping_ratio = compensation::approximate_damping_ratio(oscillator, k.residual_delay_s);
    k.predicted_damping_ratio_loop = compensation::damping_ratio_of(loop_root(study, lead.network, c, dde));

    hybrid_test::SpecimenSdof sdof;
    sdof.mass_kg = study.mass_kg;
    sdof.damping_ratio = study.damping_ratio;
    sdof.stiffness_n_per_m = study.stiffness_n_per_m;
    sdof.initial_displacement_m = study.initial_displacement_m;
    sdof.control_rate_hz = study.control_rate_hz;
    sdof.duration_s = study.duration_s;
    sdof.integrator = study.integrator;
    sdof.compensation = lead;
    sdof.plant = std::visit([](const auto& plant) { return servo::PlantConfig{plant}; }, study.plant);
    const hybrid_test::TestConfig config = hybrid_test::specimen_sdof_test(sdof);
    // The case is evaluated as it runs; nothing is kept but the response.
    hybrid_test::TestAssembly test(
        config, {dir.empty() ? dir : dir / delay_case_csv_name(i, k.compensated_delay_s), false, false, {}});
    coordinator::CriteriaAccumulator sums(1, 0, study.control_rate_hz);
    std::vector<double> x;
    const std::int64_t steps = test.steps_planned();
    x.reserve(static_cast<std::size_t>(steps));
    const double abort_level = study.abort_amplitude_factor * std::abs(study.initial_displacement_m);
    for (std::int64_t n = 0; n < steps; ++n) {
      const coordinator::StepOutcome outcome = test.step();
      // An unstable case leaves the rig's envelope on purpose: the stop is its expected end.
      if (outcome == coordinator::StepOutcome::kLimit || outcome == coordinator::StepOutcome::kRunAway) {
        k.stopped_by = coordinator::limit_stop_name(test.limit_stop().kind);
        break;
      }
      if (outcome != coordinator::StepOutcome::kOk)
        throw std::runtime_error("delay-compensation case stopped: loop failure");
      sums.add_test(test.last_record());
      x.push_back(test.last_record().displacement_m[0]);
      if (abort_level > 0.0 && std::abs(x.back()) > abort_level) {
        k.aborted_on_amplitude = true;
        break;
      }
    }
    test.finish(coordinator::StepOutcome::kOk);
    k.steps = static_cast<std::int64_t>(x.size());
    // Skip the first quarter second: the actuator settles from holding to following.
    const IdentifiedDamping identified = identify_damping(x, dt, 0.25, 1e-4);
    k.identified_damping_ratio = identified.damping_ratio;
    k.identified_frequency_hz = identified.damped_frequency_hz;
    k.stable = k.identified_damping_ratio > 0.0 && !k.aborted_on_amplitude && k.stopped_by.empty();
    const coordinator::ChannelCriteria criteria = sums.channel(0);
    k.tracking_rms_error_percent = criteria.j2_rms_tracking_error_percent;
    k.tracking_peak_error_percent = criteria.j3_peak_tracking_error_percent;
    k.tracking_delay_s = 1e-3 * criteria.tracking_delay_ms;
    k.tracking_delay_at_window_edge = criteria.tracking_delay_at_window_edge;
    k.final_tracking_indicator_m2 = criteria.final_tracking_indicator_m2;
    k.energy_balance_error_j = sums.criteria().energy_error_j;
    cases.push_back(k);
  }
  return cases;
}

void write_delay_compensation(const std::filesystem::path& dir, const StudyDocument& file,
                              const DelayCompensationStudy& study, const std::vector<DelayCompensationCase>& cases) {
  using nlohmann::json;
  json entries = json::array();
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const auto& k = cases[i];
    entries.push_back(
        {{"compensated_delay_ms", 1e3 * k.compensated_delay_s},
         {"actuator_delay_ms", 1e3 * k.actuator_delay_s},
         {"compensator_lead_ms", 1e3 * k.compensator_lead_s},
         {"residual_delay_ms", 1e3 * k.residual_delay_s},
         {"identified_damping_ratio", k.identified_damping_ratio},
         {"identified_frequency_hz", k.identified_frequency_hz},
         {"predicted_damping_ratio", k.predicted_damping_ratio},
         {"approximate_damping_ratio", k.approximate_damping_ratio},
         {"predicted_damping_ratio_loop", k.predicted_damping_ratio_loop},
         {"stable", k.stable},
         {"aborted_on_amplitude", k.aborted_on_amplitude},
         {"stopped_by", k.stopped_by.empty() ? nlohmann::json(nullptr) : nlohmann::json(k.stopped_by)},
         {"tracking_rms_error_percent", k.tracking_rms_error_percent},
         {"tracking_peak_error_percent", k.tracking_peak_error_percent},
         {"tracking_delay_ms", std::isfinite(k.tracking_delay_s) ? json(1e3 * k.tracking_delay_s) : json(nullptr)},
         {"tracking_delay_at_window_edge", k.tracking_delay_at_window_edge},
         {"final_tracking_indicator_m2", k.final_tracking_indicator_m2},
         {"energy_balance_error_j", k.energy_balance_error_j},
         {"time_history", delay_case_csv_name(i, k.compensated_delay_s)}});
  }
  const bool ideal = std::holds_alternative<servo::PureDelayParameters>(study.plant);
  const json summary = {
      {"study", "rpsd_delay_compensation"},
      {"scenario", file.name},
      {"provenance", output::provenance_json(file.input_files)},
      {"plant", ideal ? "ideal_delay" : "servo_model"},
      {"structure",
       {{"mass_kg", study.mass_kg},
        {"stiffness_n_per_m", study.stiffness_n_per_m},
        {"damping_ratio", study.damping_ratio},
        {"natural_frequency_hz", std::sqrt(study.stiffness_n_per_m / study.mass_kg) / (2.0 * std::numbers::pi)}}},
      {"initial_displacement_m", study.initial_displacement_m},
      {"control_rate_hz", study.control_rate_hz},
      {"integrator",
       std::string(integrators::integrator_name(study.integrator)) + " " + integrators::describe(study.integrator)},
      {"phase_lead_ratio_a", study.phase_lead_ratio_a},
      {"cases", entries}};
  output::write_file_whole(dir / "summary.json", summary.dump(2) + '\n');

  // Table for the damping plot.
  {
    std::ostringstream table;
    table << "residual_delay_ms,compensated_delay_ms,identified_damping_ratio,predicted_damping_ratio,"
             "approximate_damping_ratio,predicted_damping_ratio_loop\n";
    for (const auto& k : cases) {
      table << 1e3 * k.residual_delay_s << ',' << 1e3 * k.compensated_delay_s << ',' << k.identified_damping_ratio
            << ',' << k.predicted_damping_ratio << ',' << k.approximate_damping_ratio << ','
            << k.predicted_damping_ratio_loop << '\n';
    }
    output::write_file_whole(dir / "damping.csv", table.str());
  }
  // Panels (a) under- and (b) over-compensation: every case of each kind, displacement / d0.
  const auto panel = [&](bool under) {
    std::string plots;
    for (std::size_t i = 0; i < cases.size(); ++i) {
      if ((cases[i].residual_delay_s > 0.0) != under) continue;
      char line[256];
      std::snprintf(line, sizeof line, "%s'%s' using 2:($10/%g) with lines lw 1.5 title '%.0f ms (residual %+.0f ms)'",
                    plots.empty() ? "plot " : ", \\\n     ",
                    delay_case_csv_name(i, cases[i].compensated_delay_s).c_str(), study.initial_displacement_m,
                    1e3 * cases[i].compensated_delay_s, 1e3 * cases[i].residual_delay_s);
      plots += line;
    }
    return plots.empty() ? std::string("plot 0 notitle\n") : plots + "\n";
  };
  output::render_png(
      dir / "delay_compensation.png",
      "set multiplot layout 3,1 title '" + file.name + (ideal ? " (ideal delay plant)" : " (servo model)") +
          ": RPsD free vibration with phase-lead delay compensation (cf. paper Figure 8)'\n"
          "set datafile separator ','\nset grid\nset key outside right\nset xlabel 'time (s)'\n"
          "set ylabel 'x / x_0'\nset yrange [-5:5]\n"
          "set title '(a) under-compensated: compensated delay < actuator delay'\n" +
          panel(true) +
          "set title '(b) over-compensated: compensated delay > actuator delay'\nset yrange [-1.2:1.2]\n" +
          panel(false) +
          "set title '(c) effective damping ratio against residual delay'\nset autoscale y\n"
          "set xlabel 'residual delay (ms)'\nset ylabel 'damping ratio'\n"
          "plot 'damping.csv' using 1:3 with points pt 7 ps 1.2 title 'identified from RPsD response', \\\n"
          "     '' using 1:4 with linespoints lw 2 pt 6 title 'exact root, m s^2+cs+k e^{-s tau}', \\\n"
          "     '' using 1:5 with lines lw 1 dt 2 title 'zeta - omega_n tau / 2', \\\n"
          "     '' using 1:6 with linespoints lw 1 pt 4 title 'root with G_c(s) G_a(s)'\n"
          "unset multiplot\n",
      1100, 1200);
}

}  // namespace rpsd::studies
