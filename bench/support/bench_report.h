// What every bench step has in common: repeated timed trials summarised as a median with its
// spread, and one JSON fragment per step that bench/run-all merges into the report.
// Not real-time safe (benchmark drivers only).
#pragma once

#include <chrono>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rpsd::bench {

// Median and spread of repeated measurements.
struct Summary {
  double median = 0.0;
  double min = 0.0;
  double max = 0.0;
  double p25 = 0.0;  // lower quartile (linear interpolation between order statistics)
  double p75 = 0.0;
  int samples = 0;
};

// Summarises the values; throws std::invalid_argument when there are none.
Summary summarize(std::vector<double> values);

// The summary of a figure measured once.
inline Summary single(double value) { return summarize({value}); }

// The summary of f(v) for every value (for example seconds -> multiple of real time); f must
// be monotonic, so the median maps to the median and the spread keeps its order.
Summary map_summary(const Summary& s, const std::function<double(double)>& f);

// Seconds per trial: wall clock, and CPU time of the calling thread (on a shared machine
// the gap between the two is time the thread waited for a core, or for another thread).
struct Trials {
  std::vector<double> wall_s;
  std::vector<double> cpu_s;
};

// `trials` timed calls of `body`, after `warmup` untimed calls.
Trials time_trials(int trials, int warmup, const std::function<void()>& body);

// CPU seconds the calling thread has used.
double thread_cpu_s();

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// One reported figure. `baseline` (optional) is a figure measured in the same run;
// `ratio_to_baseline` is this figure's median over the baseline's.
struct Figure {
  std::string id;     // stable key, e.g. "sdof_afap_x_realtime"
  std::string title;  // what the row says in the table
  std::string unit;
  Summary value;  // samples == 0: not measured (the title says why; the report shows "-")
  // The same figure from the measuring thread's CPU time instead of the wall clock, where
  // that is meaningful (samples == 0: not reported).
  Summary cpu_value;
  std::string target;  // the target, or empty
  bool meets_target = true;
  std::string baseline_id;
  std::string ratio_label;  // how to read the ratio, e.g. "loop / plant alone"
  double ratio_to_baseline = 0.0;

  // Compares this figure with a baseline figure of the same run.
  Figure& against(std::string baseline, std::string label, double ratio) {
    baseline_id = std::move(baseline);
    ratio_label = std::move(label);
    ratio_to_baseline = ratio;
    return *this;
  }
  // The target and whether this run meets it.
  Figure& aiming_for(std::string text, bool met) {
    target = std::move(text);
    meets_target = met;
    return *this;
  }
};

// A row of the report: what it is and its value (and its CPU-time value where meaningful).
inline Figure figure(std::string id, std::string title, std::string unit, Summary value, Summary cpu_value = {}) {
  Figure f;
  f.id = std::move(id);
  f.title = std::move(title);
  f.unit = std::move(unit);
  f.value = value;
  f.cpu_value = cpu_value;
  return f;
}

// The JSON fragment of one bench step: its command line, figures and notes.
class Fragment {
 public:
  Fragment(std::string step, int argc, char** argv);
  void add(const Figure& f);
  void note(const std::string& text);
  // Writes the fragment (pretty JSON) and prints its figures on stdout.
  void write(const std::filesystem::path& file) const;
  const std::string& command() const { return command_; }

 private:
  std::string step_, command_;
  nlohmann::json figures_ = nlohmann::json::array();
  nlohmann::json notes_ = nlohmann::json::array();
};

// Command-line options common to the bench steps: --out FILE, --repetitions N,
// --source-dir DIR (the rpsd source tree; default RPSD_SOURCE_DIR or the build's).
struct Options {
  std::filesystem::path out;
  int repetitions = 0;
  std::filesystem::path source_dir;
  std::vector<std::string> rest;  // unrecognised arguments, in order
};
// Throws std::invalid_argument on a malformed option.
Options parse_options(int argc, char** argv, int default_repetitions);

// A comma-separated list of control rates in Hz ("1024,2048,4096"); throws
// std::invalid_argument on a value that is not a positive whole number.
std::vector<int> parse_rates(const std::string& list);

}  // namespace rpsd::bench
