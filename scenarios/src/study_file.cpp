#include "rpsd/scenarios/study_file.h"

#include <charconv>
#include <cmath>

#include "physical_ranges.h"
#include "rpsd/config/closest_name.h"
#include "rpsd/config/input_log.h"
#include "rpsd/config/kind_list.h"
#include "rpsd/scenarios/ground_motion_section.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/test_scenario_file.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "rpsd/servo/linear_analysis.h"

namespace rpsd::scenarios {
namespace {

using config::Number;
using namespace ranges;

// `points` values from start to stop, equally spaced in log10, within `value`.
std::vector<double> read_log_range(MappingReader range, const Number& value) {
  const double start = range.number("start", value);
  const double stop = range.number("stop", value);
  const long points = range.whole_number("points", 2, 100000, "how many values");
  if (stop <= start) range.fail("stop", "must be greater than start");
  range.finish();
  return log_spaced(start, stop, static_cast<int>(points));
}

studies::SineSweepStudy read_sine_sweep(MappingReader& root, servo::ServoSystemParameters servo) {
  studies::SineSweepStudy s;
  s.servo = std::move(servo);
  s.command_rate_hz = root.number_or("command_rate_hz", s.command_rate_hz,
                                     Number::between(kMinControlRateHz, kMaxNodeRateHz, "Hz", "commands per second"));
  MappingReader sweep = root.mapping("sine_sweep");
  s.amplitude_m = sweep.number("amplitude_m", Number{"m", "the sine's amplitude", 0.0, kMaxDisplacementM, true});
  s.start_frequency_hz =
      sweep.number("start_frequency_hz", Number::between(0.0, kMaxFrequencyHz, "Hz", "the sweep's first frequency"));
  s.end_frequency_hz =
      sweep.number("end_frequency_hz", Number{"Hz", "the sweep's last frequency", 0.0, kMaxFrequencyHz, true});
  s.duration_s = sweep.number("duration_s", Number{"s", "the sweep's length", 0.0, kMaxRecordDurationS, true});
  if (s.duration_s * s.command_rate_hz > kMaxSteps) sweep.fail("duration_s", "more than 1e9 commands");
  if (s.end_frequency_hz <= s.start_frequency_hz) sweep.fail("end_frequency_hz", "must exceed start_frequency_hz");
  if (s.end_frequency_hz * 8.0 > s.command_rate_hz) {
    sweep.fail("end_frequency_hz", "needs at least 8 command samples per cycle (raise command_rate_hz)");
  }
  sweep.finish();
  if (root.has("report_frequencies_hz")) {
    s.report_frequencies_hz =
        root.numbers("report_frequencies_hz",
                     Number{"Hz", "frequencies the report gives gain and phase at", 0.0, kMaxFrequencyHz, true}, 1000);
    for (double f : s.report_frequencies_hz) {
      if (f <= s.start_frequency_hz || f >= s.end_frequency_hz) {
        root.fail("report_frequencies_hz", "every report frequency must lie inside the sweep");
      }
    }
  }
  return s;
}

studies::FrequencyResponseStudy read_frequency_response(MappingReader& root, servo::ServoSystemParameters servo) {
  studies::FrequencyResponseStudy s;
  s.frequencies_hz = read_log_range(root.mapping("frequencies_hz"),
                                    Number{"Hz", "the frequencies of the response", 0.0, kMaxFrequencyHz, true});
  MappingReader lead = root.mapping("phase_lead");
  const double a = lead.number("ratio_a", Number::between(1.0, 100.0, "", "the lead network's a (1: no lead)"));
  // Without an explicit T the network's zero cancels the first-order lag of Eq. 9.
  s.phase_lead =
      lead.has("time_constant_s")
          ? compensation::PhaseLeadParameters{a, lead.number("time_constant_s",
                                                             Number{"s", "the lead network's T", 0.0, 10.0, true})}
          : compensation::cancel_first_order_lag(servo::response_delay_s(servo), a);
  lead.finish();
  s.servo = std::move(servo);
  return s;
}

studies::MaxGainStudy read_max_gain(MappingReader& root, servo::ServoSystemParameters servo) {
  studies::MaxGainStudy s;
  s.servo = std::move(servo);
  s.masses_kg = read_log_range(root.mapping("attached_mass_kg"),
                               Number{"kg", "the masses the actuator carries", 0.0, kMaxMassKg, true});
  return s;
}

studies::DelayCompensationStudy read_delay_compensation(MappingReader& root) {
  studies::DelayCompensationStudy s;
  MappingReader structure = root.mapping("structure");
  s.mass_kg = structure.number("mass_kg", Number{"kg", "the SDOF's mass", 0.0, kMaxMassKg, true});
  s.stiffness_n_per_m =
      structure.number("stiffness_n_per_m", Number{"N/m", "the SDOF's stiffness", 0.0, kMaxStiffnessNPerM, true});
  s.damping_ratio = structure.number("damping_ratio", Number::between(0.0, 1.0, "", "fraction of critical"));
  structure.finish();
  s.initial_displacement_m =
      root.number("initial_displacement_m", Number{"m", "the free vibration's start", 0.0, kMaxDisplacementM, true});
  s.control_rate_hz =
      root.number_or("control_rate_hz", s.control_rate_hz,
                     Number::between(kMinControlRateHz, kMaxControlRateHz, "Hz", "integration steps per second"));
  s.duration_s = root.number("duration_s", Number{"s", "each run's length", 0.0, kMaxDurationS, true});
  if (s.duration_s * s.control_rate_hz > kMaxSteps) root.fail("duration_s", "more than 1e9 steps");
  s.abort_amplitude_factor =
      root.number_or("abort_amplitude_factor", s.abort_amplitude_factor,
                     Number::between(1.0, 1e3, "", "a run stops once it grows this many times its start"));
  if (root.has("integrator")) {
    const std::string name = root.string("integrator");
    const auto config = default_integrator(name);
    if (!config)
      root.fail("integrator", "unknown integrator \"" + name + "\"; expected " +
                                  config::listed(integrators::scheme_names()) +
                                  config::did_you_mean(name, integrators::scheme_names()));
    s.integrator = *config;
  }
  {
    MappingReader plant = root.mapping("plant");
    const servo::PlantConfig config = servo::read_plant_config(plant, s.stiffness_n_per_m);
    if (const auto* servo = std::get_if<servo::ServoSystemParameters>(&config)) {
      s.plant = *servo;
    } else if (const auto* delay = std::get_if<servo::PureDelayParameters>(&config)) {
      s.plant = *delay;
    } else {
      plant.fail("kind", "the Figure 8 study takes servo_model or ideal_delay");
    }
  }
  MappingReader compensation = root.mapping("compensation");
  s.phase_lead_ratio_a =
      compensation.number("phase_lead_ratio_a", Number{"", "the lead network's a", 1.0, 100.0, true});
  for (double ms : compensation.numbers("compensated_delays_ms",
                                        Number{"ms", "each run's compensated delay", 0.0, 1000.0, true}, 100)) {
    s.compensated_delays_s.push_back(ms * 1e-3);
  }
  compensation.finish();
  return s;
}

}  // namespace

std::optional<integrators::IntegratorConfig> default_integrator(std::string_view name) {
  const auto scheme = integrators::parse_scheme(name);
  if (!scheme) return std::nullopt;
  switch (*scheme) {
    case integrators::Scheme::kCentralDifference:
      return integrators::CentralDifferenceParams{};
    case integrators::Scheme::kNewmark:
      return integrators::NewmarkParams{};
    case integrators::Scheme::kHhtAlpha:
      return integrators::HhtAlphaParams{};
    case integrators::Scheme::kGeneralizedAlpha:
      return integrators::GeneralizedAlphaParams{};
    case integrators::Scheme::kAlphaOs:
      return integrators::AlphaOsParams{};
    case integrators::Scheme::kChang:
      return integrators::ChangParams{};
    case integrators::Scheme::kChenRicles:
      return integrators::ChenRiclesParams{};
    case integrators::Scheme::kKolayRiclesAlpha:
      return integrators::KolayRiclesAlphaParams{};
  }
  return std::nullopt;
}

std::vector<double> log_spaced(double start, double stop, int points) {
  std::vector<double> values(points);
  const double a = std::log10(start), b = std::log10(stop);
  for (int i = 0; i < points; ++i) values[i] = std::pow(10.0, a + (b - a) * i / (points - 1));
  return values;
}

Override parse_override(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw ConfigError("--set " + text + ": expected key.path=value");
  }
  return {text.substr(0, equals), text.substr(equals + 1), "--set", Override::Kind::kSet};
}

namespace {

std::string origin_of(const Override& o) {
  return (o.origin.empty() ? std::string("--set") : o.origin) + " (" + o.key_path + "=" + o.value + ")";
}

// The key under which `value` sits in `parent`, and the value: an "unknown key" error there
// names the override.
void note_key_of(const YAML::Node& parent, const YAML::Node& value, const std::string& origin,
                 std::vector<OverrideNode>& nodes) {
  for (const auto& entry : parent) {
    if (entry.second.is(value)) nodes.push_back({entry.first, origin});
  }
  nodes.push_back({value, origin});
}

// Walks key.path (mapping keys, or list indices as numbers) and replaces the value there; a
// missing mapping on the way is created (ground_motion.trim.end_s=5 without a trim). Returns
// the nodes the command line put in, so that an error in one names its override.
std::vector<OverrideNode> apply_override(YAML::Node root, const Override& o) {
  const std::string origin = origin_of(o);
  std::vector<std::string> keys;
  std::size_t start = 0;
  for (std::size_t dot; (dot = o.key_path.find('.', start)) != std::string::npos; start = dot + 1) {
    keys.push_back(o.key_path.substr(start, dot - start));
  }
  keys.push_back(o.key_path.substr(start));
  YAML::Node value;
  try {
    value = YAML::Load(o.value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(origin + ": not a YAML value: " + e.msg);
  }
  if (o.kind == Override::Kind::kRecord) {
    const YAML::Node section = root["ground_motion"];
    root["ground_motion"] = with_record(section ? section : YAML::Node(YAML::NodeType::Map), value);
    const YAML::Node replaced = root["ground_motion"];
    return {{replaced["file"], origin}, {replaced["format"], origin}};
  }
  std::vector<OverrideNode> created{{value, origin}};
  std::vector<YAML::Node> path{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node parent = path.back();
    YAML::Node child;
    if (parent.IsSequence()) {
      std::size_t index = 0;
      try {
        index = std::stoul(keys[i]);
      } catch (const std::exception&) {
        throw ConfigError(origin + ": '" + keys[i] + "' must be a list index");
      }
      if (index >= parent.size()) throw ConfigError(origin + ": index " + keys[i] + " out of range");
      child = parent[index];
    } else if (parent.IsMap()) {
      if (!parent[keys[i]]) {
        parent[keys[i]] = YAML::Node(YAML::NodeType::Map);
        note_key_of(parent, parent[keys[i]], origin, created);
      }
      child = parent[keys[i]];
    } else {
      throw ConfigError(origin + ": '" + keys[i - 1] + "' is not a mapping");
    }
    path.push_back(child);
  }
  YAML::Node parent = path.back();
  if (parent.IsSequence()) {
    std::size_t index = 0;
    try {
      index = std::stoul(keys.back());
    } catch (const std::exception&) {
      throw ConfigError(origin + ": '" + keys.back() + "' must be a list index");
    }
    if (index >= parent.size()) throw ConfigError(origin + ": index out of range");
    parent[index] = value;
  } else if (parent.IsMap()) {
    parent[keys.back()] = value;  // a new key is checked like any other by the reader
    note_key_of(parent, value, origin, created);
  } else {
    throw ConfigError(origin + ": the parent is not a mapping");
  }
  return created;
}

OverrideNodes apply_overrides(YAML::Node root, const std::vector<Override>& overrides) {
  auto nodes = std::make_shared<std::vector<OverrideNode>>();
  for (const Override& o : overrides) {
    for (auto& n : apply_override(root, o)) nodes->push_back(std::move(n));
  }
  return nodes;
}

}  // namespace

namespace {

studies::StudyDocument read_document(YAML::Node document, const std::filesystem::path& file, const std::string& text,
                                     const std::vector<Override>& command_line, OverrideNodes overrides,
                                     bool sweep_allowed = true);

std::string emitted(const YAML::Node& document) {
  YAML::Emitter out;
  out << document;
  return std::string(out.c_str()) + "\n";
}

// A sweep's cases are read from copies: the file paths their readers made absolute are
// carried back into the sweep's own document (same key, same file name, now absolute).
void adopt_absolute_paths(YAML::Node sweep, const YAML::Node& one_case) {
  if (sweep.IsMap() && one_case.IsMap()) {
    for (auto entry : sweep) {
      const std::string key = entry.first.Scalar();
      const YAML::Node theirs = one_case[key];
      if (!theirs) continue;
      if (entry.second.IsScalar() && theirs.IsScalar()) {
        const std::filesystem::path ours(entry.second.Scalar()), absolute(theirs.Scalar());
        if (ours.is_relative() && absolute.is_absolute() && ours.filename() == absolute.filename())
          sweep[key] = absolute.string();
      } else {
        adopt_absolute_paths(entry.second, theirs);
      }
    }
  } else if (sweep.IsSequence() && one_case.IsSequence()) {
    for (std::size_t i = 0; i < sweep.size() && i < one_case.size(); ++i) adopt_absolute_paths(sweep[i], one_case[i]);
  }
}

// Shortest text that reads back as the same double.
std::string number_text(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// `sweep:` is a list of one or two axes, each `key` with `values: [...]` or
// `range: {start, stop, count}`. Each case is the document with the axis values set as
// overrides, read in full, so that every case is checked before the batch runs.
studies::StudyDocument read_sweep(const std::string& text, const std::vector<Override>& command_line,
                                  YAML::Node document, MappingReader& root, const std::filesystem::path& file,
                                  studies::StudyDocument result) {
  auto axes = root.mappings("sweep", 2);
  for (auto& axis : axes) {
    studies::SweepAxis a;
    a.key_path = axis.string("key");
    if (a.key_path.rfind("sweep", 0) == 0 || a.key_path == "study") axis.fail("key", "cannot sweep this key");
    // The swept key's own reader checks each value's range, case by case.
    const Number value = Number::any("", "a value of the swept key");
    if (axis.has("values")) {
      a.values = axis.numbers("values", value, 1000);
    } else {
      MappingReader range = axis.mapping("range");
      const double start = range.number("start", value), stop = range.number("stop", value);
      const long count = range.whole_number("count", 2, 1000, "how many values");
      range.finish();
      for (long i = 0; i < count; ++i) a.values.push_back(start + (stop - start) * i / (count - 1));
    }
    axis.finish();
    result.sweep.push_back(std::move(a));
  }
  const std::size_t n0 = result.sweep[0].values.size();
  const std::size_t n1 = result.sweep.size() > 1 ? result.sweep[1].values.size() : 1;
  if (n0 * n1 > 1000) root.fail("sweep", "more than 1000 cases");
  // The first axis varies fastest: each value of the second axis is one block of cases.
  for (std::size_t j = 0; j < n1; ++j) {
    for (std::size_t i = 0; i < n0; ++i) {
      std::vector<Override> overrides{
          {result.sweep[0].key_path, number_text(result.sweep[0].values[i]), "sweep", Override::Kind::kSet}};
      std::vector<double> values{result.sweep[0].values[i]};
      if (result.sweep.size() > 1) {
        overrides.push_back(
            {result.sweep[1].key_path, number_text(result.sweep[1].values[j]), "sweep", Override::Kind::kSet});
        values.push_back(result.sweep[1].values[j]);
      }
      studies::StudyDocument one;
      try {
        // Parsed afresh from the text, so that every untouched value keeps its line and column.
        YAML::Node case_document = parse_yaml_text(text, file.string());
        auto nodes = std::make_shared<std::vector<OverrideNode>>(*apply_overrides(case_document, command_line));
        case_document.remove("sweep");
        for (const Override& o : overrides) {
          for (auto& n : apply_override(case_document, o)) nodes->push_back(std::move(n));
        }
        one = read_document(case_document, file, text, {}, nodes, false);
        if (result.sweep_cases.empty()) adopt_absolute_paths(document, case_document);
      } catch (const ConfigError& e) {
        std::string where = result.sweep[0].key_path + " = " + number_text(values[0]);
        if (values.size() > 1) where += ", " + result.sweep[1].key_path + " = " + number_text(values[1]);
        throw ConfigError(std::string(e.what()) + " (sweep case " + where + ")");
      }
      result.sweep_cases.push_back(std::get<coordinator::TestConfig>(one.study));
      result.sweep_values.push_back(values);
    }
  }
  result.study = result.sweep_cases.front();
  result.effective_yaml = emitted(document);
  // The other keys were checked by every case's own reader.
  return result;
}

}  // namespace

std::string read_config_text(const std::filesystem::path& file) { return read_yaml_file_text(file); }

YAML::Node load_yaml_document(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  YAML::Node document = parse_yaml_text(read_config_text(file), file.string());
  apply_overrides(document, overrides);
  return document;
}

studies::StudyDocument load_study(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  config::InputLog inputs;  // the scenario first, then every file it names (records, matrices, ...)
  studies::StudyDocument document = parse_study(read_config_text(file), file, overrides);
  document.input_files = inputs.files();
  return document;
}

studies::StudyDocument parse_study(const std::string& yaml_text, const std::filesystem::path& file,
                                   const std::vector<Override>& overrides) {
  YAML::Node document = parse_yaml_text(yaml_text, file.string());
  const OverrideNodes nodes = apply_overrides(document, overrides);
  // Sweep cases re-parse the text and re-apply these overrides, keeping every line number.
  return read_document(document, file, yaml_text, overrides, nodes);
}

namespace {

studies::StudyDocument read_document(YAML::Node document, const std::filesystem::path& file, const std::string& text,
                                     const std::vector<Override>& command_line, OverrideNodes overrides,
                                     bool sweep_allowed) {
  MappingReader root(document, file.string(), "", std::move(overrides));
  studies::StudyDocument result;
  result.name = file.stem().string();
  result.description = root.optional_string("description").value_or("");
  const std::string kind = root.string("study");
  if (kind == "rpsd_test") {
    if (root.has("sweep")) {
      // A case still holding a sweep means the key was given twice (YAML keeps both).
      if (!sweep_allowed) root.fail("sweep", "given more than once");
      return read_sweep(text, command_line, document, root, file, std::move(result));
    }
    coordinator::TestConfig scenario = read_test_config(root, file);
    scenario.description = result.description;
    result.study = std::move(scenario);
    root.finish();
    result.effective_yaml = emitted(document);  // after reading: its file paths are absolute now
    return result;
  }
  if (kind == "rpsd_delay_compensation") {
    result.study = read_delay_compensation(root);
    root.finish();
    result.effective_yaml = emitted(document);
    return result;
  }
  const std::filesystem::path servo_file = root.relative_file("servo", "the servo parameter file");
  if (!std::filesystem::exists(servo_file)) root.fail("servo", "no such parameter file: " + servo_file.string());
  servo::ServoSystemParameters servo = load_servo_parameters(servo_file);
  if (kind == "servo_sine_sweep") {
    result.study = read_sine_sweep(root, std::move(servo));
  } else if (kind == "servo_frequency_response") {
    result.study = read_frequency_response(root, std::move(servo));
  } else if (kind == "servo_max_gain") {
    result.study = read_max_gain(root, std::move(servo));
  } else {
    root.fail("study", "unknown study \"" + kind +
                           "\" (expected rpsd_test, rpsd_delay_compensation, servo_sine_sweep, "
                           "servo_frequency_response or servo_max_gain)");
  }
  root.finish();
  result.effective_yaml = emitted(document);
  return result;
}

}  // namespace

}  // namespace rpsd::scenarios
