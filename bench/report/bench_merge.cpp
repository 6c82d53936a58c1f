// Builds the benchmark report from the bench steps' JSON fragments (bench/run-all runs it).
//
//   bench_merge convert-gbench --in RAW.json --out FRAGMENT.json --step NAME --command "..."
//       Google Benchmark JSON (with repetitions) to a fragment: one figure per benchmark,
//       median and spread over the repetitions.
//   bench_merge merge --expected bench/figures.json --json REPORT.json --md REPORT.md
//                     [--require-all 1] [--date D] [--machine TEXT] [--load-before X] [--load-after Y]
//                     FRAGMENT...
//       One machine-readable report and one human table; the expected figures that no
//       fragment carries are listed as missing. With --require-all 1 a missing figure makes
//       the exit code 3 (the report is still written): CI's check that no step lost a figure.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using nlohmann::json;

json read_json(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  try {
    return json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot write");
  out << text;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  const double position = q * static_cast<double>(v.size() - 1);
  const auto below = static_cast<std::size_t>(position);
  const std::size_t above = std::min(below + 1, v.size() - 1);
  return v[below] + (position - static_cast<double>(below)) * (v[above] - v[below]);
}

json summary_of(const std::vector<double>& v) {
  return {{"median", quantile(v, 0.5)}, {"min", quantile(v, 0.0)},  {"max", quantile(v, 1.0)},
          {"p25", quantile(v, 0.25)},   {"p75", quantile(v, 0.75)}, {"samples", v.size()}};
}

std::map<std::string, std::string> parse_flags(int argc, char** argv, int first, std::vector<std::string>& rest) {
  std::map<std::string, std::string> flags;
  for (int i = first; i < argc; ++i) {
    const std::string a = argv[i];
    if (a.rfind("--", 0) == 0) {
      if (i + 1 >= argc) throw std::invalid_argument(a + ": needs a value");
      flags[a] = argv[++i];
    } else {
      rest.push_back(a);
    }
  }
  return flags;
}

std::string required(const std::map<std::string, std::string>& flags, const std::string& key) {
  const auto it = flags.find(key);
  if (it == flags.end()) throw std::invalid_argument("missing " + key);
  return it->second;
}

// Google Benchmark's iterations, grouped by run name, in the order they ran.
int convert_gbench(const std::map<std::string, std::string>& flags) {
  const json raw = read_json(required(flags, "--in"));
  std::vector<std::string> order;
  std::map<std::string, std::vector<double>> wall, cpu;
  std::map<std::string, std::string> unit;
  for (const auto& b : raw.at("benchmarks")) {
    if (b.value("run_type", "iteration") != "iteration") continue;
    const std::string name = b.at("run_name");
    if (!wall.count(name)) order.push_back(name);
    wall[name].push_back(b.at("real_time").get<double>());
    cpu[name].push_back(b.at("cpu_time").get<double>());
    unit[name] = b.at("time_unit");
  }
  json figures = json::array();
  const std::string command = required(flags, "--command");
  for (const auto& name : order) {
    json f = {
        {"id", "integrator_step_us/" + name}, {"title", "Integrator step, " + name + " DOF"}, {"unit", unit[name]},
        {"value", summary_of(wall[name])},    {"cpu_value", summary_of(cpu[name])},           {"command", command}};
    // KR-alpha against central difference at the same size and storage.
    const auto kr = name.find("/kr_alpha/");
    if (kr != std::string::npos) {
      const std::string cd = name.substr(0, kr) + "/central_difference/" + name.substr(kr + 10);
      if (wall.count(cd)) {
        f["baseline_id"] = "integrator_step_us/" + cd;
        f["ratio_label"] = "KR-alpha / central difference (time)";
        f["ratio_to_baseline"] = quantile(wall[name], 0.5) / quantile(wall[cd], 0.5);
      }
    }
    figures.push_back(f);
  }
  const json fragment = {{"step", required(flags, "--step")},
                         {"command", command},
                         {"figures", figures},
                         {"notes", json::array({"Google Benchmark, median over repetitions; load average at start " +
                                                raw.at("context").at("load_avg").dump()})}};
  write_text(required(flags, "--out"), fragment.dump(2) + "\n");
  return 0;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "-";
  char text[32];
  const double a = std::abs(v);
  if (a != 0.0 && (a >= 1e5 || a < 1e-3)) {
    std::snprintf(text, sizeof text, "%.3g", v);
  } else if (a >= 100.0) {
    std::snprintf(text, sizeof text, "%.0f", v);
  } else if (a >= 10.0) {
    std::snprintf(text, sizeof text, "%.1f", v);
  } else {
    std::snprintf(text, sizeof text, "%.3g", v);
  }
  return text;
}

std::string escape(std::string text) {
  std::string out;
  for (char c : text) {
    if (c == '|')
      out += "\\|";
    else
      out += c;
  }
  return out;
}

int merge(const std::map<std::string, std::string>& flags, const std::vector<std::string>& files) {
  const json expected = read_json(required(flags, "--expected"));
  json steps = json::array();
  json figures = json::array();
  for (const auto& file : files) {
    json fragment = read_json(file);
    for (const auto& f : fragment.at("figures")) {
      json g = f;
      g["step"] = fragment.at("step");
      figures.push_back(g);
    }
    steps.push_back(fragment);
  }
  json missing = json::array();
  for (const auto& e : expected.at("figures")) {
    const std::string id = e.at("id");
    const bool prefix = e.value("prefix", false);
    const bool found = std::any_of(figures.begin(), figures.end(), [&](const json& f) {
      const std::string fid = f.at("id");
      return prefix ? fid.rfind(id, 0) == 0 : fid == id;
    });
    if (!found) missing.push_back(e);
  }
  const auto flag = [&](const std::string& key) {
    const auto it = flags.find(key);
    return it == flags.end() ? std::string() : it->second;
  };
  const json report = {{"date", flag("--date")},
                       {"machine", flag("--machine")},
                       {"load_average_before", flag("--load-before")},
                       {"load_average_after", flag("--load-after")},
                       {"figures", figures},
                       {"missing", missing},
                       {"steps", steps}};
  write_text(required(flags, "--json"), report.dump(2) + "\n");

  std::ostringstream md;
  md << "# rpsd benchmark report\n\n";
  md << "Date: " << flag("--date") << ". Machine: " << flag("--machine")
     << ". Load average (1 min) before: " << flag("--load-before") << ", after: " << flag("--load-after") << ".\n\n";
  md << "Medians over repetitions; spread is min - max. \"CPU\" is the same figure from the measuring thread's CPU "
        "time: "
        "on a shared machine the wall-clock figure also counts time spent waiting for a core. Ratios are to a baseline "
        "measured in the same run. No absolute time is a pass/fail criterion of the test suite.\n\n";
  md << "| figure | median | spread | unit | CPU | ratio to baseline | target |\n|---|---|---|---|---|---|---|\n";
  for (const auto& f : figures) {
    const auto& v = f.at("value");
    md << "| " << escape(f.at("title")) << " | ";
    if (v.is_null())
      md << "not measured | | ";  // the title says why
    else
      md << number(v.at("median")) << " | " << number(v.at("min")) << " - " << number(v.at("max")) << " | ";
    md << escape(f.at("unit")) << " | "
       << (f.contains("cpu_value") ? number(f.at("cpu_value").at("median")) : std::string("")) << " | ";
    if (f.contains("ratio_to_baseline"))
      md << number(f.at("ratio_to_baseline")) << " (" << escape(f.at("ratio_label")) << ")";
    md << " | ";
    if (f.contains("target")) {
      md << escape(f.at("target")) << (f.value("meets_target", true) ? " (met)" : " (**not met**)");
    }
    md << " |\n";
  }
  if (!missing.empty()) {
    md << "\n## Missing figures\n\nNo step of this run measured these (their bench steps do not exist yet):\n\n";
    for (const auto& e : missing)
      md << "- " << e.at("title").get<std::string>() << " (`" << e.at("id").get<std::string>() << "`)\n";
  }
  md << "\n## Commands\n\n";
  for (const auto& s : steps)
    md << "- " << s.at("step").get<std::string>() << ": `" << s.at("command").get<std::string>() << "`\n";
  md << "\n## Notes\n\n";
  for (const auto& s : steps) {
    for (const auto& n : s.at("notes"))
      md << "- " << s.at("step").get<std::string>() << ": " << n.get<std::string>() << "\n";
  }
  write_text(required(flags, "--md"), md.str());
  std::cout << md.str();
  if (flag("--require-all") == "1" && !missing.empty()) {
    std::fprintf(stderr, "bench_merge: %zu expected figure(s) missing (listed under Missing figures)\n",
                 missing.size());
    return 3;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) try {
  if (argc < 2) throw std::invalid_argument("usage: bench_merge convert-gbench|merge ...");
  const std::string command = argv[1];
  std::vector<std::string> rest;
  const auto flags = parse_flags(argc, argv, 2, rest);
  if (command == "convert-gbench") return convert_gbench(flags);
  if (command == "merge") return merge(flags, rest);
  throw std::invalid_argument("unknown command " + command);
} catch (const std::exception& e) {
  std::fprintf(stderr, "bench_merge: %s\n", e.what());
  return 1;
}
