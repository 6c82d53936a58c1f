#include "rpsd/hybrid_test/monte_carlo_output.h"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "rpsd/hybrid_test/benchmark_criteria.h"
#include "rpsd/hybrid_test/monte_carlo.h"
#include "rpsd/output/provenance.h"
#include "rpsd/output/results_files.h"
#include "study_results_h5.h"

namespace rpsd::hybrid_test {
namespace {

// What the table summarises per run: J1-J9, then channel 0's peaks for the constraints.
struct Quantity {
  std::string name;
  std::string measures;
};

std::vector<Quantity> quantities() {
  std::vector<Quantity> q;
  for (const auto& c : kBenchmarkCriterionList) q.push_back({std::string(c.name), std::string(c.measures)});
  q.push_back({"peak_measured_m", "peak |x_m| of channel 0 (stroke), m"});
  q.push_back({"peak_measured_force_n", "peak measured force of channel 0, N"});
  q.push_back({"peak_command_velocity_m_per_s", "peak rate of change of channel 0's command, m/s"});
  q.push_back({"tracking_delay_ms",
               "rpsd's signed tracking delay of channel 0 (interpolated, +-200 ms; negative: x_m leads), ms"});
  return q;
}

std::vector<double> values_of(const TestHeadline& h) {
  std::vector<double> v(h.benchmark.begin(), h.benchmark.end());
  v.push_back(h.peak_measured_m);
  v.push_back(h.peak_measured_force_n);
  v.push_back(h.peak_command_velocity_m_per_s);
  v.push_back(h.tracking_delay_ms);
  return v;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "";
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);  // reads back as the same double
  return text;
}

nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); }

using Column = hdf5_output::Hdf5TableColumn;

Column real_column(const std::string& name) { return {name, hdf5_output::unit_of_name(name)}; }

// runs.csv as results.h5's /analysis/runs: the same columns, NaN where the CSV is empty.
struct RunsTable {
  hdf5_output::Hdf5Table table{"runs", {}};
  std::size_t parameters;

  RunsTable(const MonteCarloConfig& mc, const std::vector<Quantity>& names) : parameters(mc.parameters.size()) {
    table.columns.push_back({"run", "1", Column::Kind::kWhole});
    for (const auto& p : mc.parameters) table.columns.push_back(real_column(p.key_path));
    table.columns.push_back({"completed", "1", Column::Kind::kWhole});
    for (const auto& q : names) table.columns.push_back(real_column(q.name));
    table.columns.push_back({"folder", "1", Column::Kind::kText});
  }

  void add(std::size_t run, const std::vector<double>& drawn, bool completed, const std::vector<double>& values,
           const std::string& folder) {
    std::size_t k = 0;
    table.columns[k++].wholes.push_back(static_cast<std::int64_t>(run));
    for (std::size_t p = 0; p < parameters; ++p) table.columns[k++].reals.push_back(drawn[p]);
    table.columns[k++].wholes.push_back(completed ? 1 : 0);
    for (double v : values) table.columns[k++].reals.push_back(std::isfinite(v) ? v : std::nan(""));
    table.columns[k].texts.push_back(folder);
  }
};

// statistics.csv as results.h5's /analysis/statistics, with each quantity's unit beside it.
struct StatisticsTable {
  hdf5_output::Hdf5Table table{"statistics",
                               {{"quantity", "1", Column::Kind::kText},
                                {"units", "1", Column::Kind::kText},
                                {"runs", "1", Column::Kind::kWhole},
                                {"mean", "as units", Column::Kind::kReal},
                                {"standard_deviation", "as units", Column::Kind::kReal},
                                {"minimum", "as units", Column::Kind::kReal},
                                {"maximum", "as units", Column::Kind::kReal},
                                {"measures", "1", Column::Kind::kText}}};

  void add(const Quantity& q, const RunStatistics& s) {
    const auto real = [](double v) { return std::isfinite(v) ? v : std::nan(""); };
    table.columns[0].texts.push_back(q.name);
    table.columns[1].texts.push_back(hdf5_output::unit_of_name(q.name));
    table.columns[2].wholes.push_back(s.runs);
    table.columns[3].reals.push_back(real(s.mean));
    table.columns[4].reals.push_back(real(s.standard_deviation));
    table.columns[5].reals.push_back(real(s.minimum));
    table.columns[6].reals.push_back(real(s.maximum));
    table.columns[7].texts.push_back(q.measures);
  }
};

}  // namespace

RunResult run_monte_carlo_into(const std::filesystem::path& dir, const TestDocument& file, const ProgressSink& progress,
                               const std::atomic<bool>* stop_request) {
  using nlohmann::json;
  const MonteCarloConfig& mc = *file.monte_carlo;
  std::filesystem::create_directories(dir);
  output::reserve_summary(
      dir / "summary.json",
      json{{"study", "rpsd_test_monte_carlo"}, {"scenario", file.name}, {"result", "running"}}.dump(2) + '\n');
  output::write_file_whole(dir / "effective-scenario.yaml", file.effective_yaml);
  // With output.format hdf5 or both: one results.h5 here, a group per run.
  const std::optional<std::filesystem::path> h5 = make_study_results_h5(dir, file, "rpsd_test_monte_carlo");
  const std::vector<Quantity> names = quantities();
  std::ostringstream runs_csv;
  runs_csv << "run,";
  for (const auto& p : mc.parameters) runs_csv << p.key_path << ',';
  runs_csv << "completed,";
  for (const auto& q : names) runs_csv << q.name << ',';
  runs_csv << "folder\n";
  std::vector<std::vector<double>> per_quantity(names.size());
  RunsTable table(mc, names);
  RunResult result = RunResult::kCompleted;
  int completed_runs = 0;
  json left_out = json::array();  // runs whose criteria are partial: not in the statistics
  json runs = json::array();
  for (std::size_t i = 0; i < file.sweep_cases.size(); ++i) {
    char folder[32];
    std::snprintf(folder, sizeof folder, "run_%03zu", i + 1);
    const TestHeadline h = run_test_into(dir / folder, file, file.sweep_cases[i], progress, stop_request, i + 1,
                                         file.sweep_cases.size(), h5 ? CaseHdf5{*h5, folder} : CaseHdf5{});
    const bool completed = h.result == RunResult::kCompleted;
    completed_runs += completed ? 1 : 0;
    if (!completed && result == RunResult::kCompleted) result = h.result;
    const std::vector<double> v = values_of(h);
    table.add(i + 1, file.sweep_values[i], completed, v, folder);
    runs_csv << i + 1 << ',';
    json drawn = json::object();
    for (std::size_t p = 0; p < mc.parameters.size(); ++p) {
      runs_csv << number(file.sweep_values[i][p]) << ',';
      drawn[mc.parameters[p].key_path] = file.sweep_values[i][p];
    }
    runs_csv << (completed ? 1 : 0) << ',';
    json criteria = json::object();
    for (std::size_t q = 0; q < names.size(); ++q) {
      runs_csv << number(v[q]) << ',';
      criteria[names[q].name] = json_number(v[q]);
      // A stopped or interrupted run's criteria cover only the steps it took: not a result.
      if (completed) per_quantity[q].push_back(v[q]);
    }
    if (!completed) left_out.push_back({{"run", i + 1}, {"result", result_name(h.result)}, {"outcome", h.outcome}});
    runs_csv << folder << '\n';
    runs.push_back({{"run", i + 1},
                    {"values", drawn},
                    {"result", result_name(h.result)},
                    {"outcome", h.outcome},
                    {"criteria", criteria},
                    {"criteria_partial", !completed},
                    {"folder", folder}});
    if (h.result == RunResult::kInterrupted || h.result == RunResult::kResultsNotWritten ||
        h.result == RunResult::kNotReady) {
      result = h.result;
      break;
    }
  }
  output::write_file_whole(dir / "runs.csv", runs_csv.str());

  std::ostringstream csv, markdown;
  csv << "quantity,runs,mean,standard_deviation,minimum,maximum,measures\n";
  markdown << "| quantity | runs | mean | standard deviation | minimum | maximum |\n|---|---|---|---|---|---|\n";
  json statistics = json::object();
  StatisticsTable statistics_table;
  for (std::size_t q = 0; q < names.size(); ++q) {
    const RunStatistics s = run_statistics(per_quantity[q]);
    statistics_table.add(names[q], s);
    csv << names[q].name << ',' << s.runs << ',' << number(s.mean) << ',' << number(s.standard_deviation) << ','
        << number(s.minimum) << ',' << number(s.maximum) << ",\"" << names[q].measures << "\"\n";
    markdown << "| " << names[q].name << " | " << s.runs << " | " << number(s.mean) << " | "
             << number(s.standard_deviation) << " | " << number(s.minimum) << " | " << number(s.maximum) << " |\n";
    statistics[names[q].name] = {{"runs", s.runs},
                                 {"mean", json_number(s.mean)},
                                 {"standard_deviation", json_number(s.standard_deviation)},
                                 {"minimum", json_number(s.minimum)},
                                 {"maximum", json_number(s.maximum)},
                                 {"measures", names[q].measures}};
  }
  markdown << "\nOver the " << completed_runs << " completed run(s) of " << runs.size() << "; left out (stopped or "
           << "interrupted, criteria over part of the record only): " << left_out.size() << "\n";
  output::write_file_whole(dir / "statistics.csv", csv.str());
  output::write_file_whole(dir / "statistics.md", markdown.str());
  json parameters = json::array();
  for (std::size_t p = 0; p < mc.parameters.size(); ++p) {
    const auto& m = mc.parameters[p];
    const bool normal = m.distribution == MonteCarloParameter::Distribution::kNormal;
    parameters.push_back({{"key", m.key_path},
                          {"distribution", normal ? "normal" : "uniform"},
                          {"nominal", m.nominal},
                          {normal ? "standard_deviation" : "half_width", m.spread}});
    if (!m.also_key_paths.empty()) parameters.back()["also_keys"] = m.also_key_paths;
  }
  json summary{{"study", "rpsd_test_monte_carlo"},
               {"scenario", file.name},
               {"description", file.description},
               {"result", result_name(result)},
               {"completed", result == RunResult::kCompleted},
               {"runs_planned", mc.runs},
               {"runs_completed", completed_runs},
               {"runs_in_statistics", completed_runs},
               {"runs_left_out_of_statistics", left_out},
               {"seed", mc.seed},
               {"noise_seed_key", mc.noise_seed_key},
               {"parameters", parameters},
               {"statistics", statistics},
               {"runs", runs},
               {"provenance", output::provenance_json(file.input_files)}};
  if (h5) {
    summary["results_h5"] = "results.h5";
    write_study_analysis(*h5, summary, {std::move(table.table), std::move(statistics_table.table)});
  }
  output::write_summary(dir / "summary.json", summary.dump(2) + '\n');
  return result;
}

}  // namespace rpsd::hybrid_test
