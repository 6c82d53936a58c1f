#include "bench_report.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace rpsd::bench {
namespace {

double quantile(const std::vector<double>& sorted, double q) {
  const double position = q * static_cast<double>(sorted.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  const double fraction = position - static_cast<double>(below);
  return sorted[below] + fraction * (sorted[above] - sorted[below]);
}

nlohmann::json to_json(const Summary& s) {
  return {{"median", s.median}, {"min", s.min}, {"max", s.max}, {"p25", s.p25}, {"p75", s.p75}, {"samples", s.samples}};
}

}  // namespace

Summary summarize(std::vector<double> values) {
  if (values.empty()) throw std::invalid_argument("summarize: no values");
  std::sort(values.begin(), values.end());
  Summary s;
  s.samples = static_cast<int>(values.size());
  s.min = values.front();
  s.max = values.back();
  s.median = quantile(values, 0.5);
  s.p25 = quantile(values, 0.25);
  s.p75 = quantile(values, 0.75);
  return s;
}

Summary map_summary(const Summary& s, const std::function<double(double)>& f) {
  Summary m = s;
  m.median = f(s.median);
  const double a = f(s.min), b = f(s.max), c = f(s.p25), d = f(s.p75);
  m.min = std::min(a, b);
  m.max = std::max(a, b);
  m.p25 = std::min(c, d);
  m.p75 = std::max(c, d);
  return m;
}

double thread_cpu_s() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

Trials time_trials(int trials, int warmup, const std::function<void()>& body) {
  for (int i = 0; i < warmup; ++i) body();
  Trials t;
  t.wall_s.reserve(static_cast<std::size_t>(trials));
  t.cpu_s.reserve(static_cast<std::size_t>(trials));
  for (int i = 0; i < trials; ++i) {
    const double cpu_start = thread_cpu_s();
    const auto start = Clock::now();
    body();
    t.wall_s.push_back(seconds_since(start));
    t.cpu_s.push_back(thread_cpu_s() - cpu_start);
  }
  return t;
}

Fragment::Fragment(std::string step, int argc, char** argv) : step_(std::move(step)) {
  for (int i = 0; i < argc; ++i) {
    std::string word = argv[i];
    if (i == 0) {
      // Relative to the working directory run-all uses (the source tree), when it is below it.
      std::error_code ec;
      const auto relative =
          std::filesystem::relative(std::filesystem::absolute(word), std::filesystem::current_path(), ec);
      if (!ec && !relative.empty() && relative.native().rfind("..", 0) != 0) word = "./" + relative.string();
    }
    command_ += (i ? " " : "") + word;
  }
}

void Fragment::add(const Figure& f) {
  // No samples: the figure could not be measured (its title says why); its value is null.
  nlohmann::json j = {{"id", f.id},
                      {"title", f.title},
                      {"unit", f.unit},
                      {"value", f.value.samples > 0 ? to_json(f.value) : nlohmann::json(nullptr)}};
  if (f.cpu_value.samples > 0) j["cpu_value"] = to_json(f.cpu_value);
  if (!f.target.empty()) {
    j["target"] = f.target;
    j["meets_target"] = f.meets_target;
  }
  if (!f.baseline_id.empty()) {
    j["baseline_id"] = f.baseline_id;
    j["ratio_label"] = f.ratio_label;
    j["ratio_to_baseline"] = f.ratio_to_baseline;
  }
  j["command"] = command_;
  figures_.push_back(std::move(j));
}

void Fragment::note(const std::string& text) { notes_.push_back(text); }

void Fragment::write(const std::filesystem::path& file) const {
  const nlohmann::json j = {{"step", step_}, {"command", command_}, {"figures", figures_}, {"notes", notes_}};
  if (!file.empty()) {
    if (file.has_parent_path()) std::filesystem::create_directories(file.parent_path());
    std::ofstream out(file);
    if (!out) throw std::runtime_error(file.string() + ": cannot write");
    out << j.dump(2) << '\n';
  }
  for (const auto& f : figures_) {
    const auto& v = f["value"];
    if (v.is_null()) {
      std::printf("%-66s not measured\n", f["title"].get<std::string>().c_str());
      continue;
    }
    std::printf("%-66s %10.4g %-12s (min %.4g, max %.4g, n %d)", f["title"].get<std::string>().c_str(),
                v["median"].get<double>(), f["unit"].get<std::string>().c_str(), v["min"].get<double>(),
                v["max"].get<double>(), v["samples"].get<int>());
    if (f.contains("cpu_value")) std::printf("  [thread CPU time: %.4g]", f["cpu_value"]["median"].get<double>());
    std::printf("\n");
  }
  for (const auto& n : notes_) std::printf("  note: %s\n", n.get<std::string>().c_str());
}

Options parse_options(int argc, char** argv, int default_repetitions) {
  Options o;
  o.repetitions = default_repetitions;
  if (const char* env = std::getenv("RPSD_SOURCE_DIR")) o.source_dir = env;
#ifdef RPSD_BENCH_SOURCE_DIR
  if (o.source_dir.empty()) o.source_dir = RPSD_BENCH_SOURCE_DIR;
#endif
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument(a + ": needs a value");
      return argv[++i];
    };
    if (a == "--out") {
      o.out = value();
    } else if (a == "--repetitions") {
      o.repetitions = std::stoi(value());
      if (o.repetitions < 1) throw std::invalid_argument("--repetitions: at least 1");
    } else if (a == "--source-dir") {
      o.source_dir = value();
    } else {
      o.rest.push_back(a);
    }
  }
  return o;
}

std::vector<int> parse_rates(const std::string& list) {
  std::vector<int> rates;
  std::stringstream items(list);
  for (std::string item; std::getline(items, item, ',');) {
    const int rate = std::stoi(item);
    if (rate <= 0) throw std::invalid_argument("--rates: positive whole numbers, got " + item);
    rates.push_back(rate);
  }
  return rates;
}

}  // namespace rpsd::bench
