#include "rpsd/hybrid_test/hybrid_test_output.h"
#include "rpsd/hybrid_test/run_watchers.h"

#include "rpsd/hybrid_test/benchmark_criteria.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "operator_run_output.h"
#include "rpsd/coordinator/limit_stop_text.h"
#include "rpsd/ground_motion/response_spectrum.h"
#include "rpsd/hdf5_output/hdf5_batch.h"
#include "rpsd/hdf5_output/hdf5_results.h"
#include "rpsd/hybrid_test/actuator_links.h"
#include "rpsd/hybrid_test/held_forces.h"
#include "rpsd/hybrid_test/hybrid_test_runs.h"
#include "rpsd/hybrid_test/setup_plan.h"
#include "rpsd/output/gnuplot.h"
#include "rpsd/output/plot_decimation.h"
#include "rpsd/output/provenance.h"
#include "rpsd/output/results_files.h"
#include "rpsd/realtime/latency_json.h"
#include "rpsd/transport/messages.h"
#include "study_results_h5.h"

namespace rpsd::hybrid_test {
namespace {

const char* outcome_text(coordinator::StepOutcome o) {
  switch (o) {
    case coordinator::StepOutcome::kOk:
      return "completed";
    case coordinator::StepOutcome::kRecordEnded:
      return "completed";
    case coordinator::StepOutcome::kLinkFailure:
      return "aborted: the servo node stopped answering";
    case coordinator::StepOutcome::kIntegratorError:
      return "aborted: the integrator rejected a step";
    case coordinator::StepOutcome::kNodeFault:
      return "aborted: the servo node reported a fault";
    case coordinator::StepOutcome::kNonFinite:
      return "aborted: a non-finite measurement arrived";
    case coordinator::StepOutcome::kLimit:
      return "aborted: a coordinator limit was reached";
    case coordinator::StepOutcome::kRunAway:
      return "stopped: the test ran away";
    case coordinator::StepOutcome::kGeometry:
      return "stopped: an experimental setup's geometry failed";
    case coordinator::StepOutcome::kResultsNotWritten:
      return "stopped: the results could not be written";
    case coordinator::StepOutcome::kInterrupted:
      return "interrupted: the user stopped the run (SIGINT or SIGTERM); the nodes hold where they are";
    case coordinator::StepOutcome::kRefused:
      return "refused";
    case coordinator::StepOutcome::kOperatorStop:
      return "operator stop: the test ended in order after the step under way";
    case coordinator::StepOutcome::kOperatorAbort:
      return "operator abort: the coordinator stopped commanding; every node holds at once";
    case coordinator::StepOutcome::kHostCallFailed:
      return "stopped: a host program's call failed";
  }
  return "aborted";
}

// The tables the plots read: a long test's drawn from its rows keeping every peak of what
// the plots show (plot_time_history.csv, plot_reference_history.csv), a short one's whole;
// and plot_zoom.csv, every row within 0.5 s of the largest target, where the lag shows.
struct PlottedTables {
  std::string test, reference, zoom;
};

// `thinned`: the tables hold every k-th step only (output.histories: decimated), already few
// enough rows to draw whole; thinning them again for the plots would copy most of them.
PlottedTables plotted_tables(const std::filesystem::path& dir, int first_dof_column, int dofs, bool drifts,
                             bool thinned) {
  constexpr std::size_t kBuckets = 1100;  // one per pixel column of the widest plot
  const auto column = [](int c) { return [c](const output::CsvRow& row) { return row.at(c - 1); }; };
  std::vector<output::PlottedQuantity> dof_columns;
  for (int d = 0; d < dofs; ++d) dof_columns.push_back(column(first_dof_column + 4 * d));
  for (int d = 1; drifts && d < dofs; ++d) {
    const int upper = first_dof_column + 4 * d - 1, lower = upper - 4;
    dof_columns.push_back([=](const output::CsvRow& row) { return row.at(upper) - row.at(lower); });
  }
  std::vector<output::PlottedQuantity> drawn = dof_columns;
  for (int c : {3, 4, 5, 6, 8}) drawn.push_back(column(c));
  drawn.push_back([](const output::CsvRow& row) { return row.at(5) - row.at(3); });  // measured - target
  PlottedTables names{"time_history.csv", "reference_history.csv", "plot_zoom.csv"};
  const auto decimate = [&](std::string& name, const output::RecordedCsv& table,
                            const std::vector<output::PlottedQuantity>& quantities) {
    const std::string decimated = "plot_" + name;
    if (!thinned && output::write_rows_keeping_peaks(table, dir / decimated, quantities, kBuckets)) {
      name = decimated;
    } else {
      std::filesystem::remove(dir / decimated);  // a shorter run's redraw must not draw an older one's
    }
  };
  {
    const output::RecordedCsv test = output::read_csv_table(dir / names.test);
    if (!output::write_rows_around_peak(test, dir / names.zoom, column(4), column(2), 0.5)) names.zoom.clear();
    decimate(names.test, test, drawn);
  }
  decimate(names.reference, output::read_csv_table(dir / names.reference), dof_columns);
  return names;
}

std::string dof_panels(const std::string& title, const PlottedTables& t, int first_dof_column,
                       const std::vector<int>& dof_numbers, bool drifts) {
  const int dofs = static_cast<int>(dof_numbers.size());
  std::string script = "set datafile separator ','\nset grid\nset key top right\nset xlabel 'time (s)'\n";
  script += "set multiplot layout " + std::to_string(dofs) + "," + (drifts ? "2" : "1") + " title '" + title +
            ": test against the perfect-actuator reference'\n";
  char line[640];
  for (int d = 0; d < dofs; ++d) {
    const int c = first_dof_column + 4 * d;
    std::snprintf(line, sizeof line,
                  "set ylabel 'displacement (mm)'\nset title 'DOF %d'\n"
                  "plot '%s' using 2:($%d*1e3) with lines lw 1.5 title 'test', "
                  "'%s' using 2:($%d*1e3) with lines lw 1 dt 2 title 'reference'\n",
                  dof_numbers[d], t.test.c_str(), c, t.reference.c_str(), c);
    script += line;
    if (!drifts) continue;
    // Storey d's drift: this floor less the one below (the ground for the first).
    const std::string drift = d == 0 ? "($" + std::to_string(c) + "*1e3)"
                                     : "(($" + std::to_string(c) + "-$" + std::to_string(c - 4) + ")*1e3)";
    std::snprintf(line, sizeof line,
                  "set ylabel 'drift (mm)'\nset title 'storey %d drift'\n"
                  "plot '%s' using 2:%s with lines lw 1.5 title 'test', "
                  "'%s' using 2:%s with lines lw 1 dt 2 title 'reference'\n",
                  d + 1, t.test.c_str(), drift.c_str(), t.reference.c_str(), drift.c_str());
    script += line;
  }
  return script + "unset multiplot\n";
}

// The plots read only the CSV files and plot.json, so `rpsd plot DIR` can redraw them.
void draw(const std::filesystem::path& dir, const nlohmann::json& info) {
  const int channels = info.at("channels");
  const int dofs = info.at("recorded_dofs");
  const std::string title = info.at("title");
  const bool has_record = info.at("ground_motion");
  const bool drifts = info.value("storey_drifts", false);
  std::vector<int> dof_numbers = info.value("dof_numbers", std::vector<int>{});
  if (static_cast<int>(dof_numbers.size()) != dofs) {
    dof_numbers.resize(dofs);
    for (int d = 0; d < dofs; ++d) dof_numbers[d] = d;
  }
  // time_history.csv columns: 1 step, 2 time, 3 a_g, then 6 per channel, then 4 per DOF.
  const int first_dof_column = 4 + 6 * channels;
  const bool thinned = info.value("histories_every_steps", 1) > 1;
  const PlottedTables t = plotted_tables(dir, first_dof_column, dofs, drifts, thinned);
  const std::string& th = t.test;
  const int panels = 3 + (has_record ? 1 : 0) + (t.zoom.empty() ? 0 : 1);
  std::string script = "set datafile separator ','\nset grid\nset key outside right\n";
  script += "set multiplot layout " + std::to_string(panels) + ",1 title '" + title + "'\n";
  const std::string tracking =
      "' using 2:($4*1e3) with lines lw 1.5 title 'target', "
      "'' using 2:($5*1e3) with lines lw 1 dt 2 title 'command', '' using 2:($6*1e3) "
      "with lines lw 1 title 'measured'\n";
  script += "set xlabel 'time (s)'\nset ylabel 'displacement (mm)'\nset title 'experimental channel 0'\n";
  script += "plot '" + th + tracking;
  if (!t.zoom.empty()) {
    script += "set title 'channel 0 around its largest target: the lag of measured behind target'\n";
    script += "plot '" + t.zoom + tracking;
  }
  script += "set ylabel 'tracking error (mm)'\nset title 'measured - target'\n";
  script += "plot '" + th + "' using 2:(($6-$4)*1e3) with lines lw 1 notitle\n";
  script +=
      "set xlabel 'measured displacement (mm)'\nset ylabel 'specimen restoring force (kN)'\nset title 'hysteresis, "
      "channel 0'\n";
  script += "plot '" + th + "' using ($6*1e3):($8*1e-3) with lines lw 1 notitle\n";
  if (has_record) {
    script += "set xlabel 'time (s)'\nset ylabel 'ground acceleration (m/s^2)'\nset title 'record'\n";
    script += "plot '" + th + "' using 2:3 with lines lw 1 notitle\n";
  }
  script += "unset multiplot\n";
  output::render_png(dir / "test.png", script, 1100, 300 * panels + 100);
  output::render_png(dir / "response.png", dof_panels(title, t, first_dof_column, dof_numbers, drifts),
                     drifts ? 1400 : 1100, 260 * dofs + 80);

  if (has_record) {
    output::render_png(dir / "record.png",
                       "set datafile separator ','\nset grid\nset multiplot layout 2,1 title '" + title +
                           ": ground motion as applied'\n"
                           "set xlabel 'time (s)'\nset ylabel 'acceleration (m/s^2)'\n"
                           "plot '" +
                           th +
                           "' using 2:3 with lines lw 1 notitle\n"
                           "set logscale x\nset xlabel 'period (s)'\nset ylabel 'pseudo-acceleration (m/s^2)'\n"
                           "set title '5 % damped response spectrum'\n"
                           "plot 'spectrum.csv' using 1:2 with lines lw 2 notitle\nunset multiplot\n",
                       1000, 800);
  }
}

// Pseudo-acceleration and displacement spectra (5 %) of the record as applied.
void write_spectrum(const std::filesystem::path& dir, const hybrid_test::GroundMotion& motion) {
  ground_motion::GroundMotionRecord record;
  record.source = motion.name;
  record.dt_s = motion.dt_s;
  record.acceleration_m_per_s2 = motion.acceleration_m_per_s2;
  ground_motion::ResponseSpectrumOptions options;
  options.periods_s = ground_motion::log_spaced_periods(0.02, 5.0, 80);
  const auto spectrum = ground_motion::response_spectrum(record, options);
  std::ostringstream out;
  out << "period_s,pseudo_acceleration_m_per_s2,displacement_m\n";
  for (std::size_t i = 0; i < spectrum.periods_s.size(); ++i) {
    out << spectrum.periods_s[i] << ',' << spectrum.pseudo_acceleration_m_per_s2[i] << ',' << spectrum.displacement_m[i]
        << '\n';
  }
  output::write_file_whole(dir / "spectrum.csv", out.str());
}

nlohmann::json ground_motion_json(const hybrid_test::GroundMotion& motion) {
  double pga = 0.0;
  for (double a : motion.acceleration_m_per_s2) pga = std::max(pga, std::abs(a));
  return {{"source", motion.name},
          {"dt_s", motion.dt_s},
          {"points", motion.acceleration_m_per_s2.size()},
          {"pga_m_per_s2", pga},
          {"pga_g", pga / 9.80665},
          {"record_step_s", motion.record_step_s},
          {"record_pga_g", std::abs(motion.record_pga_m_per_s2) / 9.80665},
          {"processing", motion.processing}};
}

std::string describe_outcome(const hybrid_test::TestConfig& s, const hybrid_test::TestRun& test) {
  std::string text = outcome_text(test.outcome);
  if (test.outcome == coordinator::StepOutcome::kRefused) {
    // Refused by a site's node: its reason, not a step (the run never had the site).
    return text + ": " + (test.refusal.empty() ? std::string("a site's node refused this run") : test.refusal);
  }
  if (test.outcome == coordinator::StepOutcome::kLinkFailure) {
    char detail[200];
    if (test.timing.real_time) {
      std::snprintf(detail, sizeof detail, " (newest feedback %lld control periods old; step %zu, t = %.4f s)",
                    static_cast<long long>(test.feedback_age_periods), static_cast<std::size_t>(test.steps + 1),
                    static_cast<double>(test.steps + 1) / s.control_rate_hz);
    } else {
      std::snprintf(detail, sizeof detail, " (none within %g s at step %zu, t = %.4f s)",
                    s.transport.feedback_timeout_s, static_cast<std::size_t>(test.steps + 1),
                    static_cast<double>(test.steps + 1) / s.control_rate_hz);
    }
    text += detail;
  } else if (test.outcome == coordinator::StepOutcome::kInterrupted ||
             test.outcome == coordinator::StepOutcome::kOperatorStop ||
             test.outcome == coordinator::StepOutcome::kOperatorAbort) {
    char detail[100];
    std::snprintf(detail, sizeof detail, " (after step %zu, t = %.4f s)", static_cast<std::size_t>(test.steps),
                  static_cast<double>(test.steps) / s.control_rate_hz);
    text += detail;
  } else if (test.outcome != coordinator::StepOutcome::kOk && test.outcome != coordinator::StepOutcome::kRecordEnded) {
    char detail[100];
    std::snprintf(detail, sizeof detail, " (at step %zu, t = %.4f s)", static_cast<std::size_t>(test.steps + 1),
                  static_cast<double>(test.steps + 1) / s.control_rate_hz);
    text += detail;
  }
  if (test.outcome == coordinator::StepOutcome::kLimit || test.outcome == coordinator::StepOutcome::kRunAway ||
      test.outcome == coordinator::StepOutcome::kGeometry) {
    text += " (" + coordinator::describe_limit_stop(test.limit_stop) + ")";
  }
  if (test.outcome == coordinator::StepOutcome::kOperatorStop ||
      test.outcome == coordinator::StepOutcome::kOperatorAbort) {
    text += operator_outcome_detail(test);
  }
  if (!test.node_fault.empty()) text += ": " + test.node_fault;
  if (!test.host_error.empty()) text += ": " + test.host_error;
  if (!test.write_error.empty()) text += " (" + test.write_error + ")";
  return text;
}

nlohmann::json timing_json(const hybrid_test::TimingReport& t) {
  using nlohmann::json;
  json sites = json::array();
  for (std::size_t i = 0; i < t.sites.size(); ++i) {
    json site = {{"site_id", t.sites[i].site_id}, {"round_trip", realtime::latency_json(t.sites[i].round_trip)}};
    if (i < t.dds_counters.size()) {
      const auto& c = t.dds_counters[i];
      site["messages"] = {{"sent", c.sent},
                          {"received", c.received},
                          {"late", c.late},
                          {"dropped_wrong_test_or_site", c.wrong_test_or_site},
                          {"dropped_wrong_channels", c.wrong_channels},
                          {"dropped_older_step", c.older_step},
                          {"dropped_other_run", c.other_run},
                          {"dropped_unknown_writer", c.unknown_writer},
                          {"dropped_no_run", c.no_run},
                          {"dropped_impossible_step", c.impossible_step}};
    }
    sites.push_back(site);
  }
  json j = {{"real_time", t.real_time}, {"over_dds", t.over_dds}, {"sites", sites}};
  if (t.real_time || t.over_dds) {
    j["cpus_kept_awake"] = t.cpus_kept_awake;
    j["refused"] = t.refused;
  }
  if (t.real_time) {
    j["cycles"] = t.cycles;
    j["overruns"] = t.overruns;
    j["skipped_deadlines"] = t.skipped_deadlines;
    j["late_feedback"] = t.late_feedback;
    j["jitter"] = realtime::latency_json(t.jitter);
    j["memory_locked"] = t.memory_locked;
    j["sched_fifo"] = t.fifo_granted;
    if (t.pinned_cpu >= 0) j["loop_cpu"] = t.pinned_cpu;
  }
  return j;
}

}  // namespace

namespace {

// No node answered before the first step: the summary says so (not "running"), names no file
// the run did not write, and carries no criteria (there are none to compute).
TestHeadline not_ready(const std::filesystem::path& dir, const TestDocument& file, const std::string& why) {
  TestHeadline headline;
  headline.result = RunResult::kNotReady;
  headline.outcome = "not ready: " + why;
  headline.benchmark.fill(std::nan(""));
  output::write_summary(dir / "summary.json", nlohmann::json{{"study", "rpsd_test"},
                                                             {"scenario", file.name},
                                                             {"description", file.description},
                                                             {"result", result_name(RunResult::kNotReady)},
                                                             {"outcome", headline.outcome},
                                                             {"completed", false},
                                                             {"steps", 0},
                                                             {"benchmark_criteria", nullptr},
                                                             {"provenance", output::provenance_json(file.input_files)}}
                                                      .dump(2) +
                                                  '\n');
  return headline;
}

RunResult result_of(const hybrid_test::TestRun& test, const hybrid_test::TestRun& reference) {
  using coordinator::StepOutcome;
  if (test.outcome == StepOutcome::kResultsNotWritten || !test.write_error.empty() || !reference.write_error.empty()) {
    return RunResult::kResultsNotWritten;
  }
  if (test.outcome == StepOutcome::kInterrupted) return RunResult::kInterrupted;
  if (test.outcome == StepOutcome::kOk || test.outcome == StepOutcome::kRecordEnded) return RunResult::kCompleted;
  return RunResult::kStopped;
}

}  // namespace

const char* result_name(RunResult r) {
  switch (r) {
    case RunResult::kCompleted:
      return "completed";
    case RunResult::kStopped:
      return "stopped";
    case RunResult::kResultsNotWritten:
      return "results_not_written";
    case RunResult::kInterrupted:
      return "interrupted";
    case RunResult::kNotReady:
      return "not_ready";
  }
  return "stopped";
}

namespace {

// Each experimental setup as the run used it: its kind and geometry, each actuator (name,
// channel, attachment points, reference length) and DOF, and each actuator's calibration.
nlohmann::json experimental_setups_json(const hybrid_test::TestConfig& scenario,
                                        const std::vector<hybrid_test::SetupCalibration>& calibrations) {
  using nlohmann::json;
  json out = json::array();
  for (std::size_t k = 0; k < scenario.setups.size(); ++k) {
    const hybrid_test::ExperimentalSetupSite& site = scenario.setups[k];
    const setups::PlanarGeometry g = setups::planar_geometry(site.setup);
    const setups::PlanarSetup setup(g);
    json actuators = json::array(), dofs = json::array();
    for (int i = 0; i < setup.dofs(); ++i) {
      const setups::PlanarActuator& a = g.actuators[static_cast<std::size_t>(i)];
      actuators.push_back({{"name", a.name.empty() ? "actuator " + std::to_string(i + 1) : a.name},
                           {"channel", site.channels[static_cast<std::size_t>(i)]},
                           {"fixed_end_m", {a.fixed_end_m.x(), a.fixed_end_m.y()}},
                           {"attachment_m", {a.attachment_m.x(), a.attachment_m.y()}},
                           {"reference_length_m", setup.reference_length_m(i)}});
      dofs.push_back({{"channel", site.channels[static_cast<std::size_t>(i)]},
                      {"motion", setups::dof_motion_name(g.dofs[static_cast<std::size_t>(i)])}});
    }
    json calibration = nullptr;
    if (k < calibrations.size()) {
      const hybrid_test::SetupCalibration& c = calibrations[k];
      calibration = {{"measured", c.measured},
                     {"max_calibration_offset_m", site.max_calibration_offset_m},
                     {"reading_m", c.reading_m},
                     {"predicted_stroke_m", c.predicted_stroke_m},
                     {"offset_m", c.offset_m},
                     {"force_at_rest_measured", c.force_at_rest_measured},
                     {"force_at_rest_n", c.force_at_rest_n}};
    }
    out.push_back(
        {{"site_id", site.site_id},
         {"kind",
          std::visit([](const auto& kind) { return std::string(std::decay_t<decltype(kind)>::kName); }, site.setup)},
         {"geometry", g.geometry == setups::Geometry::kLinear ? "linear" : "large_displacement"},
         {"compensated",
          site.compensated == hybrid_test::ExperimentalSetupSite::Compensated::kDofs ? "dofs" : "actuators"},
         {"dofs", dofs},
         {"actuators", actuators},
         {"calibration", calibration}});
  }
  return out;
}

}  // namespace

// Only with held forces: each one's site, channel, force, ramp and limits, and what the run's
// records say of it (how well it was held once ramped, how far its piston went).
nlohmann::json held_forces_json(const hybrid_test::TestConfig& scenario, const hybrid_test::TestRun& test) {
  using nlohmann::json;
  const auto number = [](double v) { return std::isfinite(v) ? json(v) : json(nullptr); };
  json held = json::array();
  for (std::size_t k = 0; k < scenario.held_forces.size(); ++k) {
    const hybrid_test::HeldForce& h = scenario.held_forces[k];
    // The channel as the loop held it; a run that never started one: as the file says.
    const coordinator::HeldForceChannel c =
        k < test.held_forces.size() ? test.held_forces[k] : hybrid_test::held_force_channel(scenario, k, 0.0);
    json entry = {{"site", h.site_id},
                  {"channel", c.channel},
                  {"name", h.name},
                  {"force_n", h.force_n},
                  {"max_force_rate_n_per_s", h.max_force_rate_n_per_s},
                  {"specimen_stiffness_n_per_m", h.specimen_stiffness_n_per_m},
                  {"limits",
                   {{"max_force_n", c.limits.max_force_n},
                    {"max_stroke_m", c.limits.max_stroke_m},
                    {"max_force_error_n", c.limits.max_force_error_n}}},
                  {"force_at_rest_n", c.force_at_rest_n},
                  {"ramp_s", hybrid_test::held_force_ramp_s(h, c.force_at_rest_n)}};
    if (k < test.held_stats.size() && test.held_stats[k].steps > 0) {
      const hybrid_test::HeldForceStats& st = test.held_stats[k];
      entry["max_force_error_after_ramp_n"] = number(st.max_force_error_after_ramp_n);
      entry["measured_stroke_m"] = {{"min", st.min_measured_m}, {"max", st.max_measured_m}};
      entry["final_measured_force_n"] = number(st.last_measured_force_n);
    } else {
      entry["max_force_error_after_ramp_n"] = nullptr;
      entry["measured_stroke_m"] = nullptr;
      entry["final_measured_force_n"] = nullptr;
    }
    held.push_back(entry);
  }
  return held;
}

namespace {

// results.h5 for a test and its reference, with the inputs: the case's own document in a batch,
// under the case's group of the study's file. The histories as output.histories keeps them:
// none (only the inputs, and the criteria at the end), or every k-th step.
// Throws output::ResultsNotWritten when it cannot be made.
std::unique_ptr<hdf5_output::Hdf5Results> make_results_h5(const std::filesystem::path& path, const TestDocument& file,
                                                          const TestConfig& scenario, std::size_t batch_case,
                                                          const std::string& group) {
  hdf5_output::Hdf5Inputs inputs;
  inputs.scenario_name = file.name;
  inputs.effective_yaml = batch_case > 0 ? file.case_yaml[batch_case - 1] : file.effective_yaml;
  inputs.input_files = file.input_files;
  std::vector<hdf5_output::Hdf5RunLayout> runs;
  for (const char* name : {"test", "reference"}) {
    if (!scenario.histories.written()) break;
    const bool reference = std::string_view(name) == "reference";
    const coordinator::RecorderOptions columns = recorded_columns(scenario, reference);
    hdf5_output::Hdf5RunLayout run;
    run.name = name;
    run.control_rate_hz = scenario.control_rate_hz;
    run.channels = static_cast<int>(scenario.experimental.size());
    for (auto d : scenario.record_dofs) run.dof_numbers.push_back(static_cast<std::int64_t>(d));
    run.dof_view = columns.dof_view;
    run.held_channels = columns.held_channels;
    run.every_steps = scenario.histories.every_steps;
    runs.push_back(std::move(run));
  }
  try {
    return std::make_unique<hdf5_output::Hdf5Results>(path, inputs, runs, group);
  } catch (const std::runtime_error& e) {
    throw output::ResultsNotWritten(e.what());
  }
}

// What summary.json says of the histories kept, when not every step was (nothing otherwise).
nlohmann::json histories_json(const HistoriesConfig& h) {
  nlohmann::json j = {{"kept", kept_name(h.kept)}};
  if (h.kept == HistoriesConfig::Kept::kDecimated) {
    j["rate_hz"] = h.rate_hz;
    j["every_steps"] = h.every_steps;
  }
  return j;
}

}  // namespace

std::optional<std::filesystem::path> make_study_results_h5(const std::filesystem::path& dir, const TestDocument& file,
                                                           const std::string& study) {
  if (file.sweep_cases.empty() || file.sweep_cases.front().results_format == ResultsFormat::kCsv) return std::nullopt;
  const std::filesystem::path path = dir / "results.h5";
  try {
    hdf5_output::create_batch_file(path, {file.name, file.effective_yaml, file.input_files}, study);
  } catch (const std::runtime_error& e) {
    throw output::ResultsNotWritten(e.what());
  }
  return path;
}

TestHeadline run_test_into(const std::filesystem::path& dir, const TestDocument& file,
                           const hybrid_test::TestConfig& scenario, const ProgressSink& progress,
                           const std::atomic<bool>* stop_request, std::size_t case_number, std::size_t cases,
                           const CaseHdf5& in_study) {
  const auto report = [&](std::string_view phase, std::int64_t done, std::int64_t planned) {
    if (progress) progress({phase, case_number, cases, done, planned});
  };
  std::filesystem::create_directories(dir);
  output::reserve_summary(dir / "summary.json",
                          nlohmann::json{{"study", "rpsd_test"},
                                         {"scenario", file.name},
                                         {"result", "running"},
                                         {"outcome", "running (or killed before it could finish)"},
                                         {"completed", false}}
                                  .dump(2) +
                              '\n');
  // A case of a batch writes its own document, with its values, never the batch's.
  const bool one_of_a_batch = case_number >= 1 && case_number <= file.case_yaml.size();
  output::write_file_whole(dir / "effective-scenario.yaml",
                           one_of_a_batch ? file.case_yaml[case_number - 1] : file.effective_yaml);
  if (scenario.ground_motion) write_spectrum(dir, *scenario.ground_motion);
  // The histories as CSV tables, results.h5 (docs/results-format.md) or both; none with
  // output.histories: criteria_only (results.h5 then holds the inputs and the criteria).
  const bool csv = scenario.results_format != ResultsFormat::kHdf5 && scenario.histories.written();
  const bool hdf5 = scenario.results_format != ResultsFormat::kCsv;
  const bool in_study_h5 = !in_study.file.empty();
  const std::filesystem::path h5_path = in_study_h5 ? in_study.file : dir / "results.h5";
  std::unique_ptr<hdf5_output::Hdf5Results> h5;
  if (hdf5) h5 = make_results_h5(h5_path, file, scenario, one_of_a_batch ? case_number : 0, in_study.group);
  // The test and its reference run side by side and are evaluated as they go, so memory
  // does not grow with the record's length.
  hybrid_test::RunWatchers watchers(scenario, progress, case_number, cases);
  hybrid_test::RunWatch watch = watchers.watch();
  if (h5 && scenario.histories.written()) {
    watch.observers.push_back(&h5->observer(0));
    watch.reference_observers.push_back(&h5->observer(1));
  }
  hybrid_test::EvaluatedTest run;
  try {
    run = hybrid_test::run_test_and_reference(
        scenario, csv ? dir / "time_history.csv" : std::filesystem::path(),
        csv ? dir / "reference_history.csv" : std::filesystem::path(),
        [&](std::int64_t done, std::int64_t planned) { report("test", done, planned); }, stop_request, watch);
  } catch (const hybrid_test::NoNodeAnswered& e) {
    return not_ready(dir, file, e.what());
  } catch (const hybrid_test::CalibrationOutOfRange& e) {
    return not_ready(dir, file, e.what());
  }
  const hybrid_test::TestRun& test = run.test;
  const coordinator::Criteria& criteria = run.criteria;
  // Both recorders have finished: what the HDF5 writer still holds is written now.
  const std::string h5_error = h5 ? h5->close() : std::string();
  RunResult result = result_of(test, run.reference);
  std::string outcome = describe_outcome(scenario, test);
  // The reference's own host structure (kind external) failing leaves the criteria partial.
  if (run.reference.outcome == coordinator::StepOutcome::kHostCallFailed) {
    outcome = (result == RunResult::kCompleted ? std::string() : outcome + "; ") +
              "stopped: the perfect-actuator reference's host call failed: " + run.reference.host_error;
    if (result == RunResult::kCompleted) result = RunResult::kStopped;
  }
  const bool completed_run = result == RunResult::kCompleted;
  if (test.write_error.empty() && !run.reference.write_error.empty()) {
    outcome = (completed_run ? "" : outcome + "; ") + "stopped: the results could not be written (" +
              run.reference.write_error + ")";
  } else if (test.write_error.empty() && !h5_error.empty()) {
    // The test went on (the CSV, if any, has every step); results.h5 lacks the steps from then.
    outcome = (completed_run ? "" : outcome + "; ") + "the results could not be written (" + h5_error + ")";
    result = RunResult::kResultsNotWritten;
  }
  const bool completed = result == RunResult::kCompleted;
  watchers.ended(test, outcome);

  using nlohmann::json;
  json channels = json::array();
  for (std::size_t c = 0; c < criteria.channels.size(); ++c) {
    const auto& cc = criteria.channels[c];
    channels.push_back(
        {{"channel", c},
         {"J1_tracking_delay_ms",
          std::isfinite(cc.j1_tracking_delay_ms) ? json(cc.j1_tracking_delay_ms) : json(nullptr)},
         {"J2_rms_tracking_error_percent", cc.j2_rms_tracking_error_percent},
         // rpsd's own signed delay beside the benchmark's J1 (negative: x_m leads).
         {"tracking_delay_ms", std::isfinite(cc.tracking_delay_ms) ? json(cc.tracking_delay_ms) : json(nullptr)},
         {"tracking_delay_at_window_edge", cc.tracking_delay_at_window_edge},
         {"J3_peak_tracking_error_percent", cc.j3_peak_tracking_error_percent},
         {"final_tracking_indicator_m2", cc.final_tracking_indicator_m2},
         {"peak_measured_m", cc.peak_measured_m},
         {"peak_measured_force_n", cc.peak_measured_force_n},
         {"peak_command_velocity_m_per_s", cc.peak_command_velocity_m_per_s}});
  }
  json dofs = json::array();
  for (std::size_t d = 0; d < criteria.dofs.size(); ++d) {
    const auto& dc = criteria.dofs[d];
    dofs.push_back({{"dof", scenario.record_dofs[d]},
                    {"peak_displacement_m", dc.peak_displacement_m},
                    {"reference_peak_displacement_m", dc.reference_peak_displacement_m},
                    {"rms_error_vs_reference_percent", dc.rms_error_percent},
                    {"peak_error_vs_reference_percent", dc.peak_error_percent}});
  }
  const json benchmark = benchmark_criteria_json(criteria);
  // What stopped a test that did not complete, for scripts: its kind (a limit, a node's fault,
  // a lost link, the user...), the reason in words, where; for a limit which, how far.
  json stopped_by = nullptr;
  if (!completed) {
    // A run that reached its end and still did not complete lost its results on the way.
    const bool ran_to_end =
        test.outcome == coordinator::StepOutcome::kOk || test.outcome == coordinator::StepOutcome::kRecordEnded;
    const bool after_step = ran_to_end || test.outcome == coordinator::StepOutcome::kInterrupted ||
                            test.outcome == coordinator::StepOutcome::kOperatorStop ||
                            test.outcome == coordinator::StepOutcome::kOperatorAbort;
    const auto step = static_cast<std::int64_t>(after_step ? test.steps : test.steps + 1);
    const bool reference_failed = run.reference.outcome == coordinator::StepOutcome::kHostCallFailed;
    const char* kind = !ran_to_end        ? coordinator::step_outcome_name(test.outcome)
                       : reference_failed ? coordinator::step_outcome_name(run.reference.outcome)
                                          : "results_not_written";
    stopped_by = {{"kind", kind},
                  {"reason", outcome},
                  {"step", step},
                  {"time_s", static_cast<double>(step) / scenario.control_rate_hz}};
    if (test.outcome == coordinator::StepOutcome::kLimit || test.outcome == coordinator::StepOutcome::kRunAway ||
        test.outcome == coordinator::StepOutcome::kGeometry) {
      const coordinator::LimitStop& l = test.limit_stop;
      // A held force's tracking limit is on its force (held_forces[].limits.max_force_error_n).
      stopped_by["limit"] = l.held >= 0 && l.kind == coordinator::LimitStop::Kind::kTrackingError
                                ? "max_force_error_n"
                                : coordinator::limit_stop_name(l.kind);
      stopped_by["channel"] = l.channel;
      stopped_by["value"] = l.value;
      stopped_by["bound"] = l.bound;
      // On a setup's channel: the actuator or the DOF (or the setup, for its geometry) by name;
      // on a held force's (after the structure's channels): the held force.
      const bool held_channel = l.held >= 0;
      if (l.name[0] != '\0') {
        stopped_by[held_channel      ? "held_force"
                   : l.actuator >= 0 ? "actuator"
                   : l.dof >= 0      ? "dof"
                                     : "setup"] = std::string(l.name.data());
        stopped_by["unit"] = l.unit;
      }
    }
    if (test.outcome == coordinator::StepOutcome::kOperatorStop ||
        test.outcome == coordinator::StepOutcome::kOperatorAbort) {
      stopped_by["operator"] = {{"action", test.outcome == coordinator::StepOutcome::kOperatorStop ? "stop" : "abort"},
                                {"sender", test.operator_sender}};
    }
    // A node's fault in its own words, or those of the lab controller behind it.
    if (!test.node_fault.empty()) stopped_by["node_says"] = test.node_fault;
    // A host program's part (kind external) in its own words.
    if (!test.host_error.empty()) stopped_by["host_says"] = test.host_error;
  }
  json summary = {
      {"study", "rpsd_test"},
      {"scenario", file.name},
      {"description", file.description},
      {"result", result_name(result)},
      {"outcome", outcome},
      {"completed", completed},
      {"run_id", transport::run_id_text(test.run_id)},
      {"stopped_by", stopped_by},
      {"steps", test.steps},
      {"steps_planned", test.steps_planned},
      {"control_rate_hz", scenario.control_rate_hz},
      {"integrator", std::string(integrators::integrator_name(scenario.integrator)) + " " +
                         integrators::describe(scenario.integrator)},
      {"compensation", std::string(compensation::compensator_name(scenario.compensation))},
      {"ground_motion", scenario.ground_motion ? ground_motion_json(*scenario.ground_motion) : json(nullptr)},
      {"channels", channels},
      {"dofs", dofs},
      {"benchmark_criteria", benchmark},
      // A run that did not complete was measured over the steps it took, against a reference
      // that went on: its criteria describe that stretch, not the test (J4 near 100 % where
      // the test stood still). They are kept, marked, and left out of a batch's statistics.
      {"benchmark_criteria_partial", !completed},
      {"benchmark_criteria_partial_reason", completed ? json(nullptr) : json(outcome)},
      {"benchmark_criteria_definitions", benchmark_criteria_definitions(criteria)},
      {"energy_error_j", criteria.energy_error_j},
      {"dropped_records", test.dropped_records},
      {"overruns", test.timing.overruns},
      {"clock", scenario.clock.mode == hybrid_test::ClockConfig::Mode::kRealTime ? "real_time" : "as_fast_as_possible"},
      {"transport", scenario.transport.kind == hybrid_test::TransportConfig::Kind::kDds ? "dds" : "in_process"},
      {"timing", timing_json(test.timing)},
      {"operator_commands", operator_commands_json(test)},
      {"held", held_intervals_json(test)},
      {"return_to_start", return_to_start_json(test)},
      {"provenance", output::provenance_json(file.input_files)},
  };
  if (hdf5) {
    // A case of a study writes into the study's file, one folder up, under its own group.
    summary["results_h5"] = in_study_h5 ? "../" + h5_path.filename().string() : h5_path.filename().string();
    if (in_study_h5) summary["results_h5_group"] = "/" + in_study.group;
  }
  if (scenario.histories.kept != HistoriesConfig::Kept::kAll) summary["histories"] = histories_json(scenario.histories);
  // Only with a setup: its kind, geometry, actuators and the calibration the run used.
  if (!scenario.setups.empty()) summary["experimental_setups"] = experimental_setups_json(scenario, test.calibrations);
  // Only with held forces: nothing of this section without them.
  if (!scenario.held_forces.empty()) summary["held_forces"] = held_forces_json(scenario, test);
  // Which of the host's compensators ran (kind external, rpsd.run's callables key): the kind
  // alone does not say.
  if (const auto* host = std::get_if<compensation::ExternalCompensatorParameters>(&scenario.compensation))
    summary["compensation_host_name"] = host->name;
  std::vector<int> dof_numbers;
  for (auto d : scenario.record_dofs) dof_numbers.push_back(static_cast<int>(d));
  bool from_the_ground_up = true;  // DOFs 0, 1, ... n-1: a storey's drift is one less the next
  for (std::size_t i = 0; i < dof_numbers.size(); ++i) from_the_ground_up &= dof_numbers[i] == static_cast<int>(i);
  const bool storey_drifts = std::holds_alternative<substructure::ShearBuildingParameters>(scenario.structure) &&
                             from_the_ground_up && dof_numbers.size() > 1;
  json plot_info = {{"title", file.name},
                    {"channels", scenario.experimental.size()},
                    {"recorded_dofs", scenario.record_dofs.size()},
                    {"dof_numbers", dof_numbers},
                    {"storey_drifts", storey_drifts},
                    {"ground_motion", scenario.ground_motion.has_value()}};
  if (scenario.histories.every_steps > 1) plot_info["histories_every_steps"] = scenario.histories.every_steps;
  // The plots are drawn from the CSV files, which are the results: one that cannot be drawn
  // (too few steps, no gnuplot) is reported and `rpsd plot` redraws it; summary.json comes
  // last, so that it describes every file beside it.
  // Without CSV tables (results.h5 only) there is nothing to draw from.
  try {
    if (csv) {
      output::write_file_whole(dir / "plot.json", plot_info.dump(2) + '\n');
      report("plots", 0, 0);
      if (test.steps >= 2) draw(dir, plot_info);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rpsd: warning: %s\n", e.what());
  }
  write_return_to_start(dir, test);
  // The criteria into results.h5 (/analysis), once its SWMR writing is over.
  if (h5 && h5_error.empty()) {
    try {
      hdf5_output::Hdf5Results::write_analysis(h5_path, summary, in_study.group);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "rpsd: warning: %s\n", e.what());
    }
  }
  output::write_summary(dir / "summary.json", summary.dump(2) + '\n');
  TestHeadline headline;
  headline.result = result;
  headline.outcome = outcome;
  headline.benchmark = benchmark_values(criteria);
  if (!criteria.channels.empty()) {
    const auto& c0 = criteria.channels[0];
    headline.j2_percent = c0.j2_rms_tracking_error_percent;
    headline.peak_measured_m = c0.peak_measured_m;
    headline.peak_measured_force_n = c0.peak_measured_force_n;
    headline.peak_command_velocity_m_per_s = c0.peak_command_velocity_m_per_s;
    headline.tracking_delay_ms = c0.tracking_delay_ms;
  }
  if (!criteria.dofs.empty()) {
    headline.j4_percent = criteria.dofs[0].rms_error_percent;
    headline.peak_displacement_m = criteria.dofs[0].peak_displacement_m;
    headline.reference_peak_displacement_m = criteria.dofs[0].reference_peak_displacement_m;
  }
  return headline;
}

namespace {
std::string legend_entry(const std::string& key, double value) {
  char text[160];
  std::snprintf(text, sizeof text, "%s = %g", key.c_str(), value);
  return text;
}
// A log axis where the values span a decade or more (and are all positive), else a linear one.
std::string logscale(const char* axis, const std::vector<double>& values) {
  const auto [low, high] = std::minmax_element(values.begin(), values.end());
  const bool decades = low != values.end() && *low > 0.0 && *high >= 10.0 * *low;
  return std::string(decades ? "set logscale " : "unset logscale ") + axis + "\n";
}

// sweep.csv as results.h5's /analysis/sweep.
hdf5_output::Hdf5Table sweep_table(const TestDocument& file, const std::vector<TestHeadline>& headlines) {
  using Column = hdf5_output::Hdf5TableColumn;
  const auto real = [](const std::string& name) { return Column{name, hdf5_output::unit_of_name(name)}; };
  hdf5_output::Hdf5Table table{"sweep", {}};
  for (std::size_t a = 0; a < file.sweep.size(); ++a) {
    table.columns.push_back(real(file.sweep[a].key_path));
    for (std::size_t i = 0; i < headlines.size(); ++i) table.columns.back().reals.push_back(file.sweep_values[i][a]);
  }
  Column completed{"completed", "1", Column::Kind::kWhole}, folder{"folder", "1", Column::Kind::kText};
  Column j2 = real("J2_percent"), j4 = real("J4_percent"), peak = real("peak_displacement_m"),
         reference = real("reference_peak_displacement_m");
  for (std::size_t i = 0; i < headlines.size(); ++i) {
    const TestHeadline& h = headlines[i];
    completed.wholes.push_back(h.result == RunResult::kCompleted ? 1 : 0);
    j2.reals.push_back(h.j2_percent);
    j4.reals.push_back(h.j4_percent);
    peak.reals.push_back(h.peak_displacement_m);
    reference.reals.push_back(h.reference_peak_displacement_m);
    char name[32];
    std::snprintf(name, sizeof name, "case_%03zu", i);
    folder.texts.emplace_back(name);
  }
  for (Column* c : {&completed, &j2, &j4, &peak, &reference, &folder}) table.columns.push_back(std::move(*c));
  return table;
}

}  // namespace

void write_study_analysis(const std::filesystem::path& h5, const nlohmann::json& summary,
                          const std::vector<hdf5_output::Hdf5Table>& tables) {
  try {
    hdf5_output::write_batch_analysis(h5, summary, tables);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rpsd: warning: %s\n", e.what());
  }
}

RunResult run_sweep_into(const std::filesystem::path& dir, const TestDocument& file, const ProgressSink& progress,
                         const std::atomic<bool>* stop_request) {
  using nlohmann::json;
  std::filesystem::create_directories(dir);
  output::reserve_summary(
      dir / "summary.json",
      json{{"study", "rpsd_test_sweep"}, {"scenario", file.name}, {"result", "running"}}.dump(2) + '\n');
  output::write_file_whole(dir / "effective-scenario.yaml", file.effective_yaml);
  // With output.format hdf5 or both: one results.h5 here, a group per case.
  const std::optional<std::filesystem::path> h5 = make_study_results_h5(dir, file, "rpsd_test_sweep");
  json cases = json::array();
  std::ostringstream table;
  for (const auto& axis : file.sweep) table << axis.key_path << ',';
  table << "completed,J2_percent,J4_percent,peak_displacement_m,reference_peak_displacement_m,folder\n";
  RunResult result = RunResult::kCompleted;
  std::vector<double> j2s, j4s;
  std::vector<TestHeadline> headlines;
  for (std::size_t i = 0; i < file.sweep_cases.size(); ++i) {
    char folder[32];
    std::snprintf(folder, sizeof folder, "case_%03zu", i);
    const TestHeadline h = run_test_into(dir / folder, file, file.sweep_cases[i], progress, stop_request, i + 1,
                                         file.sweep_cases.size(), h5 ? CaseHdf5{*h5, folder} : CaseHdf5{});
    const bool completed = h.result == RunResult::kCompleted;
    if (!completed && result == RunResult::kCompleted) result = h.result;
    headlines.push_back(h);
    json values = json::object();
    for (std::size_t a = 0; a < file.sweep.size(); ++a) {
      values[file.sweep[a].key_path] = file.sweep_values[i][a];
      table << file.sweep_values[i][a] << ',';
    }
    j2s.push_back(h.j2_percent);
    j4s.push_back(h.j4_percent);
    table << (completed ? 1 : 0) << ',' << h.j2_percent << ',' << h.j4_percent << ',' << h.peak_displacement_m << ','
          << h.reference_peak_displacement_m << ',' << folder << '\n';
    cases.push_back({{"values", values},
                     {"result", result_name(h.result)},
                     {"completed", completed},
                     {"criteria_partial", !completed},
                     {"J2_percent", h.j2_percent},
                     {"J4_percent", h.j4_percent},
                     {"peak_displacement_m", h.peak_displacement_m},
                     {"reference_peak_displacement_m", h.reference_peak_displacement_m},
                     {"folder", folder}});
    // A case stopped by the user, by a failed write or by a missing node ends the sweep; a case
    // stopped by a limit is a result of the sweep, and the next case runs.
    if (h.result == RunResult::kInterrupted || h.result == RunResult::kResultsNotWritten ||
        h.result == RunResult::kNotReady) {
      result = h.result;
      break;
    }
  }
  output::write_file_whole(dir / "sweep.csv", table.str());
  json axes = json::array();
  for (const auto& axis : file.sweep) axes.push_back({{"key", axis.key_path}, {"values", axis.values}});
  json summary{{"study", "rpsd_test_sweep"},
               {"scenario", file.name},
               {"provenance", output::provenance_json(file.input_files)},
               {"result", result_name(result)},
               {"cases_planned", file.sweep_cases.size()},
               {"axes", axes},
               {"cases", cases}};
  if (h5) {
    summary["results_h5"] = "results.h5";
    write_study_analysis(*h5, summary, {sweep_table(file, headlines)});
  }
  // One line per value of the second axis (or one line), J2 and J4 against the first axis.
  const std::size_t lines = file.sweep.size() > 1 ? file.sweep[1].values.size() : 1;
  const std::size_t per_line = file.sweep[0].values.size();
  const int metric_column = static_cast<int>(file.sweep.size()) + 2;  // J2 after the axes and `completed`
  std::string plots = logscale("x", file.sweep[0].values);
  for (const char* metric : {"J2 (tracking error, %)", "J4 (error against perfect actuator, %)"}) {
    const bool second = plots.find("plot ") != std::string::npos;
    const int column = metric_column + (second ? 1 : 0);
    plots += logscale("y", second ? j4s : j2s);
    plots += std::string("set ylabel '") + metric + "'\nplot ";
    for (std::size_t l = 0; l < lines; ++l) {
      char piece[256];
      std::snprintf(piece, sizeof piece,
                    "%s'sweep.csv' skip 1 every ::%zu::%zu using 1:%d with linespoints lw 2 title '%s'", l ? ", " : "",
                    l * per_line, (l + 1) * per_line - 1, column,
                    lines > 1 ? legend_entry(file.sweep[1].key_path, file.sweep[1].values[l]).c_str() : "");
      plots += piece;
    }
    plots += "\n";
  }
  if (progress) progress({"sweep plots", file.sweep_cases.size(), file.sweep_cases.size(), 0, 0});
  try {
    output::render_png(
        dir / "sweep.png",
        "set termoption noenhanced\nset datafile separator ','\nset grid\nset key outside right\nset multiplot "
        "layout 2,1 title '" +
            file.name + ": sweep of " + file.sweep[0].key_path + "'\nset xlabel '" + file.sweep[0].key_path + "'\n" +
            plots + "unset multiplot\n",
        1000, 800);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rpsd: warning: %s\n", e.what());
  }
  output::write_summary(dir / "summary.json", summary.dump(2) + '\n');
  return result;
}

void plot_test(const std::filesystem::path& dir) {
  std::ifstream in(dir / "plot.json");
  if (!in) throw std::runtime_error((dir / "plot.json").string() + ": not found; is this an rpsd_test output folder?");
  draw(dir, nlohmann::json::parse(in));
}

std::vector<std::filesystem::path> plot_folder(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> drawn, scripts, cases;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    const auto& path = entry.path();
    if (entry.is_directory() && std::filesystem::exists(path / "summary.json")) cases.push_back(path);
    if (entry.is_regular_file() && path.extension() == ".gp") scripts.push_back(path);
  }
  std::sort(cases.begin(), cases.end());
  std::sort(scripts.begin(), scripts.end());
  for (const auto& c : cases)
    for (auto& png : plot_folder(c)) drawn.push_back(std::move(png));
  // A test's plots are drawn afresh from its tables; any other script as it stands.
  const bool test = std::filesystem::exists(dir / "plot.json");
  if (test) plot_test(dir);
  for (const auto& gp : scripts) {
    if (!test) output::rerender(gp);
    drawn.push_back(std::filesystem::path(gp).replace_extension(".png"));
  }
  if (drawn.empty()) throw std::invalid_argument(dir.string() + ": no plots to draw; is this a folder rpsd wrote?");
  return drawn;
}

}  // namespace rpsd::hybrid_test
