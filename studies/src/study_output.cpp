#include "rpsd/studies/study_output.h"

#include "rpsd/hybrid_test/monte_carlo_output.h"
#include "rpsd/studies/dry_run.h"
#include "rpsd/studies/lowest_mode.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>
#include <stdexcept>

#include "rpsd/output/csv_table.h"
#include "rpsd/output/gnuplot.h"
#include "rpsd/output/provenance.h"
#include "rpsd/output/results_files.h"
#include "rpsd/servo/linear_analysis.h"
#include "rpsd/studies/delay_compensation_study.h"

namespace rpsd::studies {
namespace {

using nlohmann::json;

json to_json(const Response& r) { return {{"amplitude_ratio", r.amplitude_ratio}, {"phase_deg", r.phase_deg}}; }

json servo_json(const servo::ServoSystemParameters& p) {
  const servo::ServoAnalysis a = servo::analyze(p);
  return {{"name", p.name},
          {"cutoff_frequency_hz", a.cutoff_frequency_hz},
          {"response_delay_ms", a.response_delay_ms},
          {"amplitude_reduction_at_2hz", a.amplitude_reduction_at_2hz},
          {"oil_column_frequency_hz", a.oil_column_frequency_hz},
          {"p_gain", a.p_gain},
          {"max_stable_p_gain", a.max_stable_p_gain},
          {"max_stable_p_gain_full_model", a.max_stable_p_gain_full_model}};
}

// DIR/summary.json of a study, with where it came from.
void write_summary_json(const std::filesystem::path& dir, const StudyDocument& file, json summary) {
  summary["provenance"] = output::provenance_json(file.input_files);
  output::write_file_whole(dir / "summary.json", summary.dump(2) + '\n');
}

template <typename Row, typename Getter>
std::vector<double> pick(const std::vector<Row>& rows, Getter get) {
  std::vector<double> values;
  values.reserve(rows.size());
  for (const Row& row : rows) values.push_back(get(row));
  return values;
}

std::vector<double> scaled(const std::vector<double>& values, double factor) {
  std::vector<double> out(values);
  for (double& v : out) v *= factor;
  return out;
}

// The time histories of a batch's cases that did not complete, as they are on disk: a batch
// folder has no time_history.csv of its own, and a case that never started has none.
std::string stopped_cases_records(const std::filesystem::path& dir) {
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto csv = entry.path() / "time_history.csv";
    std::ifstream in(entry.path() / "summary.json");
    if (!entry.is_directory() || !in || !std::filesystem::exists(csv)) continue;
    const json summary = json::parse(in, nullptr, false);
    if (summary.is_object() && summary.value("result", "") != "completed") files.push_back(csv.string());
  }
  std::sort(files.begin(), files.end());
  if (files.empty()) return "the cases' folders (" + (dir / "summary.json").string() + " lists them)";
  constexpr std::size_t kNamed = 3;
  std::string text = files.front();
  for (std::size_t i = 1; i < std::min(files.size(), kNamed); ++i) text += ", " + files[i];
  if (files.size() > kNamed) {
    text +=
        " and " + std::to_string(files.size() - kNamed) + " more (" + (dir / "summary.json").string() + " lists them)";
  }
  return text;
}

}  // namespace

void write_sine_sweep(const std::filesystem::path& dir, const StudyDocument& file, const SineSweepStudy& study,
                      const SineSweepResult& r) {
  output::CsvTable()
      .column("time_s", r.time_s)
      .column("sweep_frequency_hz", r.frequency_hz)
      .column("command_mm", scaled(r.command_m, 1e3))
      .column("displacement_mm", scaled(r.displacement_m, 1e3))
      .column("force_kn", scaled(r.force_n, 1e-3))
      .column("spool_opening", r.spool_opening)
      .write(dir / "time_history.csv");
  output::CsvTable()
      .column("frequency_hz", pick(r.curve, [](auto& c) { return c.frequency_hz; }))
      .column("sweep_amplitude_ratio", pick(r.curve, [](auto& c) { return c.sweep.amplitude_ratio; }))
      .column("sweep_phase_deg", pick(r.curve, [](auto& c) { return c.sweep.phase_deg; }))
      .column("eq8_amplitude_ratio", pick(r.curve, [](auto& c) { return c.eq8.amplitude_ratio; }))
      .column("eq8_phase_deg", pick(r.curve, [](auto& c) { return c.eq8.phase_deg; }))
      .column("full_linear_amplitude_ratio", pick(r.curve, [](auto& c) { return c.full_linear.amplitude_ratio; }))
      .column("full_linear_phase_deg", pick(r.curve, [](auto& c) { return c.full_linear.phase_deg; }))
      .column("first_order_amplitude_ratio", pick(r.curve, [](auto& c) { return c.first_order.amplitude_ratio; }))
      .write(dir / "sweep_response.csv");

  json report = json::array();
  for (const auto& c : r.report) {
    report.push_back({{"frequency_hz", c.frequency_hz},
                      {"simulated_sweep", to_json(c.sweep)},
                      {"simulated_steady_state", to_json(c.steady_state)},
                      {"linear_eq8", to_json(c.eq8)},
                      {"linear_with_servovalve", to_json(c.full_linear)},
                      {"first_order_eq9", to_json(c.first_order)}});
  }
  write_summary_json(dir, file,
                     {{"study", "servo_sine_sweep"},
                      {"scenario", file.name},
                      {"servo", servo_json(study.servo)},
                      {"amplitude_mm", 1e3 * study.amplitude_m},
                      {"sweep_hz", {study.start_frequency_hz, study.end_frequency_hz}},
                      {"duration_s", study.duration_s},
                      {"plant_rate_hz", study.servo.plant_rate_hz},
                      {"command_rate_hz", study.command_rate_hz},
                      {"max_spool_opening", r.max_spool_opening},
                      {"peak_force_kn", 1e-3 * r.peak_force_n},
                      {"comparison", report}});
  output::render_png(
      dir / "sine_sweep.png",
      "set multiplot layout 2,1 title '" + file.name + ": " + std::to_string(1e3 * study.amplitude_m).substr(0, 4) +
          " mm sine sweep through the nonlinear servo model (cf. paper Figure 5)'\n"
          "set datafile separator ','\nset grid\nset key top right\n"
          "set xlabel 'time (s)'\nset ylabel 'displacement (mm)'\n"
          "plot 'time_history.csv' using 1:3 with lines lw 1 lc rgb '#999999' title 'command', \\\n"
          "     '' using 1:4 with lines lw 1 lc rgb '#c0392b' title 'measured (simulated)'\n"
          "set xlabel 'frequency (Hz)'\nset ylabel 'amplitude ratio'\nset yrange [0:1.1]\n"
          "plot 'sweep_response.csv' using 1:2 with points pt 7 ps 0.6 lc rgb '#c0392b' title 'simulated sweep "
          "(3-cycle fit)', \\\n"
          "     '' using 1:4 with lines lw 2 lc rgb '#2c3e50' title 'Eq. 8', \\\n"
          "     '' using 1:6 with lines lw 1 dt 2 lc rgb '#27ae60' title 'Eq. 8 with servovalve (Eq. 2)', \\\n"
          "     '' using 1:8 with lines lw 1 dt 3 lc rgb '#8e44ad' title 'first order (Eq. 9)'\n"
          "unset multiplot\n");
}

void write_frequency_response(const std::filesystem::path& dir, const StudyDocument& file,
                              const FrequencyResponseStudy& study, const std::vector<FrequencyResponseRow>& rows) {
  output::CsvTable table;
  table.column("frequency_hz", pick(rows, [](auto& r) { return r.frequency_hz; }));
  const auto add = [&](const std::string& name, auto member) {
    table.column(name + "_amplitude_ratio", pick(rows, [&](auto& r) { return (r.*member).amplitude_ratio; }));
    table.column(name + "_phase_deg", pick(rows, [&](auto& r) { return (r.*member).phase_deg; }));
  };
  add("eq8", &FrequencyResponseRow::eq8);
  add("first_order_eq9", &FrequencyResponseRow::first_order);
  add("compensated_eq8", &FrequencyResponseRow::compensated);
  add("full_linear", &FrequencyResponseRow::full_linear);
  add("compensated_full_linear", &FrequencyResponseRow::full_linear_compensated);
  table.write(dir / "frequency_response.csv");

  // Summary at round frequencies, evaluated exactly rather than read off the grid.
  FrequencyResponseStudy at_points = study;
  at_points.frequencies_hz = {1.0, 2.0, 5.0, 10.0};
  json points = json::array();
  for (const auto& r : run_frequency_response(at_points)) {
    points.push_back({{"frequency_hz", r.frequency_hz},
                      {"eq8", to_json(r.eq8)},
                      {"first_order_eq9", to_json(r.first_order)},
                      {"compensated_eq8", to_json(r.compensated)},
                      {"full_linear", to_json(r.full_linear)}});
  }
  const auto peak = std::max_element(rows.begin(), rows.end(),
                                     [](auto& a, auto& b) { return a.eq8.amplitude_ratio < b.eq8.amplitude_ratio; });
  write_summary_json(
      dir, file,
      {{"study", "servo_frequency_response"},
       {"scenario", file.name},
       {"servo", servo_json(study.servo)},
       {"phase_lead",
        {{"ratio_a", study.phase_lead.ratio_a},
         {"time_constant_s", study.phase_lead.time_constant_s},
         {"zero_time_constant_s", study.phase_lead.ratio_a * study.phase_lead.time_constant_s},
         {"max_phase_lead_deg", study.phase_lead.max_phase_lead_rad() * 180.0 / std::numbers::pi}}},
       {"eq8_peak", {{"frequency_hz", peak->frequency_hz}, {"amplitude_ratio", peak->eq8.amplitude_ratio}}},
       {"at", points}});
  output::render_png(
      dir / "frequency_response.png",
      "set multiplot layout 2,1 title '" + file.name +
          ": frequency response with amplitude compensation (cf. paper Figure 6)'\n"
          "set datafile separator ','\nset grid\nset logscale x\nset key bottom left\n"
          "set xlabel 'frequency (Hz)'\nset ylabel 'amplitude ratio'\nset logscale y\n"
          "plot 'frequency_response.csv' using 1:2 with lines lw 2 lc rgb '#2c3e50' title 'system (Eq. 8)', \\\n"
          "     '' using 1:4 with lines lw 2 dt 2 lc rgb '#8e44ad' title 'first-order approximation (Eq. 9)', \\\n"
          "     '' using 1:6 with lines lw 2 lc rgb '#c0392b' title 'with phase-lead compensation', \\\n"
          "     '' using 1:8 with lines lw 1 dt 3 lc rgb '#27ae60' title 'Eq. 8 with servovalve dynamics'\n"
          "unset logscale y\nset ylabel 'phase (deg)'\nset yrange [-270:90]\nset ytics 45\n"
          "plot 'frequency_response.csv' using 1:3 with lines lw 2 lc rgb '#2c3e50' title 'system (Eq. 8)', \\\n"
          "     '' using 1:5 with lines lw 2 dt 2 lc rgb '#8e44ad' title 'first order (Eq. 9)', \\\n"
          "     '' using 1:7 with lines lw 2 lc rgb '#c0392b' title 'compensated', \\\n"
          "     '' using 1:9 with lines lw 1 dt 3 lc rgb '#27ae60' title 'with servovalve'\n"
          "unset multiplot\n");
}

void write_max_gain(const std::filesystem::path& dir, const StudyDocument& file, const MaxGainStudy& study,
                    const std::vector<MaxGainRow>& rows) {
  output::CsvTable()
      .column("attached_mass_kg", pick(rows, [](auto& r) { return r.mass_kg; }))
      .column("max_p_gain_routh_eq8", pick(rows, [](auto& r) { return r.max_p_gain_routh; }))
      .column("max_p_gain_full_model_eigenvalues", pick(rows, [](auto& r) { return r.max_p_gain_full_model; }))
      .column("oil_column_frequency_hz", pick(rows, [](auto& r) { return r.oil_column_frequency_hz; }))
      .write(dir / "max_gain.csv");
  const auto& p = study.servo;
  write_summary_json(dir, file,
                     {{"study", "servo_max_gain"},
                      {"scenario", file.name},
                      {"servo", servo_json(p)},
                      {"rig_mass_kg", p.specimen.mass_kg},
                      {"rig_max_p_gain_routh_eq8", servo::max_stable_p_gain(p, servo::LinearModel::kPaperEq8)},
                      {"rig_max_p_gain_full_model", servo::max_stable_p_gain_from_eigenvalues(p)},
                      {"held_constant",
                       {{"stiffness_n_per_m", p.specimen.stiffness.initial_n_per_m},
                        {"damping_n_s_per_m", p.specimen.damping_n_s_per_m()}}},
                      {"mass_range_kg", {rows.front().mass_kg, rows.back().mass_kg}},
                      {"max_p_gain_range", {rows.front().max_p_gain_routh, rows.back().max_p_gain_routh}}});
  char point[160];
  std::snprintf(point, sizeof point,
                "set label 1 'operating gain %.3f' at first %g, first %g point pt 7 ps 1.2 offset 1,1\n",
                p.controller.proportional_gain, p.specimen.mass_kg, p.controller.proportional_gain);
  output::render_png(
      dir / "max_gain.png",
      "set title '" + file.name +
          ": largest stable P gain vs attached mass (cf. paper Figure 7)'\n"
          "set datafile separator ','\nset grid\nset logscale xy\nset key top right\n"
          "set xlabel 'attached mass (kg)'\nset ylabel 'maximum P gain (V/V)'\nset yrange [0.3:*]\n" +
          std::string(point) +
          "plot 'max_gain.csv' using 1:2 with lines lw 2 lc rgb '#2c3e50' title 'Routh criterion on Eq. 8', \\\n"
          "     '' using 1:3 with points pt 6 ps 0.8 lc rgb '#c0392b' title 'eigenvalues of the full linear model'\n",
      900, 600);
}

// A test whose telemetry is on carries the delay theory's damping of its lowest mode to the
// monitors (the dry run's prediction), and the mode its identified damping is projected on;
// off, the test as it is.
namespace {
hybrid_test::TestConfig with_predicted_damping(const hybrid_test::TestConfig& test) {
  hybrid_test::TestConfig watched = test;
  if (test.telemetry.enabled) {
    watched.telemetry.predicted_effective_damping = predicted_lowest_mode_damping(test);
    watched.telemetry.lowest_mode = lowest_mode_for_identification(test);
  }
  return watched;
}
}  // namespace

StudyRun run_and_write(const StudyDocument& file, const std::filesystem::path& dir,
                       const hybrid_test::ProgressSink& progress, const std::atomic<bool>* stop_request) {
  StudyRun run;
  std::filesystem::create_directories(dir);
  std::visit(
      [&](const auto& study) {
        using Study = std::decay_t<decltype(study)>;
        if constexpr (std::is_same_v<Study, SineSweepStudy>) {
          write_sine_sweep(dir, file, study, run_sine_sweep(study));
        } else if constexpr (std::is_same_v<Study, FrequencyResponseStudy>) {
          write_frequency_response(dir, file, study, run_frequency_response(study));
        } else if constexpr (std::is_same_v<Study, MaxGainStudy>) {
          write_max_gain(dir, file, study, run_max_gain(study));
        } else if constexpr (std::is_same_v<Study, DelayCompensationStudy>) {
          write_delay_compensation(dir, file, study, run_delay_compensation(study, dir));
        } else if (file.monte_carlo) {
          run.result = hybrid_test::run_monte_carlo_into(dir, file, progress, stop_request);
          if (run.result != hybrid_test::RunResult::kCompleted) {
            run.reason = std::string(hybrid_test::result_name(run.result)) + ": see " + (dir / "summary.json").string();
            run.recorded_in = stopped_cases_records(dir);
          }
        } else if (!file.sweep.empty()) {
          run.result = hybrid_test::run_sweep_into(dir, file, progress, stop_request);
          if (run.result != hybrid_test::RunResult::kCompleted) {
            run.reason = std::string(hybrid_test::result_name(run.result)) + ": see " + (dir / "summary.json").string();
            run.recorded_in = stopped_cases_records(dir);
          }
        } else {
          const hybrid_test::TestHeadline headline =
              hybrid_test::run_test_into(dir, file, with_predicted_damping(study), progress, stop_request);
          run.result = headline.result;
          run.reason = headline.outcome;
          run.recorded_in = (dir / "time_history.csv").string();
        }
      },
      file.study);
  return run;
}

}  // namespace rpsd::studies
