#include "rpsd/scenarios/study_file.h"

#include <charconv>
#include <cmath>

#include "rpsd/config/input_log.h"
#include "rpsd/hybrid_test/monte_carlo.h"
#include "rpsd/scenarios/ground_motion_section.h"
#include "rpsd/scenarios/hybrid_test_file.h"
#include "rpsd/scenarios/yaml_reader.h"
#include "study_sections.h"

namespace rpsd::scenarios {

std::optional<integrators::IntegratorConfig> default_integrator(std::string_view name) {
  return integrators::default_integrator_config(name);
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

// "a.0.b" as {"a", "0", "b"}.
std::vector<std::string> key_path_parts(const std::string& key_path) {
  std::vector<std::string> keys;
  std::size_t start = 0;
  for (std::size_t dot; (dot = key_path.find('.', start)) != std::string::npos; start = dot + 1) {
    keys.push_back(key_path.substr(start, dot - start));
  }
  keys.push_back(key_path.substr(start));
  return keys;
}

// Walks key.path (mapping keys, or list indices as numbers) and replaces the value there; a
// missing mapping on the way is created (ground_motion.trim.end_s=5 without a trim). Returns
// the nodes the command line put in, so that an error in one names its override.
std::vector<OverrideNode> apply_override(YAML::Node root, const Override& o) {
  const std::string origin = origin_of(o);
  const std::vector<std::string> keys = key_path_parts(o.key_path);
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
                                     const hybrid_test::ExternalParts& external, bool sweep_allowed = true);

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
std::string round_trip_text(double v) {
  char buffer[32];
  const auto end = std::to_chars(buffer, buffer + sizeof buffer, v).ptr;
  return std::string(buffer, end);
}

// One case of a batch (a sweep's case, a Monte Carlo run): the document parsed afresh from the
// text, so that every untouched value keeps its line and column, with the command line's
// overrides, without the batch key, with the case's own values; read in full. The first case
// carries the file paths its readers made absolute back into the batch's document.
studies::StudyDocument read_case(const std::string& text, const std::filesystem::path& file,
                                 const std::vector<Override>& command_line, const char* batch_key,
                                 const std::vector<Override>& overrides, YAML::Node batch_document, bool first,
                                 const hybrid_test::ExternalParts& external) {
  YAML::Node case_document = parse_yaml_text(text, file.string());
  auto nodes = std::make_shared<std::vector<OverrideNode>>(*apply_overrides(case_document, command_line));
  case_document.remove(batch_key);
  for (const Override& o : overrides) {
    for (auto& n : apply_override(case_document, o)) nodes->push_back(std::move(n));
  }
  studies::StudyDocument one = read_document(case_document, file, text, {}, nodes, external, false);
  if (first) adopt_absolute_paths(batch_document, case_document);
  return one;
}

// `sweep:` is a list of one or two axes, each `key` with `values: [...]` or
// `range: {start, stop, count}`. Each case is the document with the axis values set as
// overrides, read in full, so that every case is checked before the batch runs.
studies::StudyDocument read_sweep(const std::string& text, const std::vector<Override>& command_line,
                                  YAML::Node document, MappingReader& root, const std::filesystem::path& file,
                                  studies::StudyDocument result, const hybrid_test::ExternalParts& external) {
  result.sweep = study_sections::sweep(root);
  const std::size_t n0 = result.sweep[0].values.size();
  const std::size_t n1 = result.sweep.size() > 1 ? result.sweep[1].values.size() : 1;
  if (n0 * n1 > 1000) root.fail("sweep", "more than 1000 cases");
  // The first axis varies fastest: each value of the second axis is one block of cases.
  for (std::size_t j = 0; j < n1; ++j) {
    for (std::size_t i = 0; i < n0; ++i) {
      std::vector<Override> overrides{
          {result.sweep[0].key_path, round_trip_text(result.sweep[0].values[i]), "sweep", Override::Kind::kSet}};
      std::vector<double> values{result.sweep[0].values[i]};
      if (result.sweep.size() > 1) {
        overrides.push_back(
            {result.sweep[1].key_path, round_trip_text(result.sweep[1].values[j]), "sweep", Override::Kind::kSet});
        values.push_back(result.sweep[1].values[j]);
      }
      studies::StudyDocument one;
      try {
        one = read_case(text, file, command_line, "sweep", overrides, document, result.sweep_cases.empty(), external);
      } catch (const ConfigError& e) {
        std::string where = result.sweep[0].key_path + " = " + round_trip_text(values[0]);
        if (values.size() > 1) where += ", " + result.sweep[1].key_path + " = " + round_trip_text(values[1]);
        throw ConfigError(std::string(e.what()) + " (sweep case " + where + ")");
      }
      result.sweep_cases.push_back(std::get<hybrid_test::TestConfig>(one.study));
      result.sweep_values.push_back(values);
      result.case_yaml.push_back(one.effective_yaml);
    }
  }
  result.study = result.sweep_cases.front();
  result.effective_yaml = emitted(document);
  // The other keys were checked by every case's own reader.
  return result;
}

// The number at key.path in the document (mapping keys, or list indices as numbers).
std::optional<double> number_at(const YAML::Node& root, const std::string& key_path) {
  YAML::Node node = YAML::Clone(root);
  for (const std::string& key : key_path_parts(key_path)) {
    if (node.IsSequence()) {
      std::size_t index = 0;
      if (std::from_chars(key.data(), key.data() + key.size(), index).ec != std::errc() || index >= node.size())
        return std::nullopt;
      node.reset(node[index]);  // rebind: `=` would write into the tree
    } else if (node.IsMap() && node[key]) {
      node.reset(node[key]);
    } else {
      return std::nullopt;
    }
  }
  double value = 0.0;
  if (!node.IsScalar() || !YAML::convert<double>::decode(node, value)) return std::nullopt;
  return value;
}

// `monte_carlo:` runs, each the document with the perturbed keys (and the noise seed) set as
// overrides and read in full, so that every run is checked before the batch runs.
studies::StudyDocument read_monte_carlo(const std::string& text, const std::vector<Override>& command_line,
                                        YAML::Node document, MappingReader& root, const std::filesystem::path& file,
                                        studies::StudyDocument result, const hybrid_test::ExternalParts& external) {
  hybrid_test::MonteCarloConfig config = study_sections::monte_carlo(root);
  for (auto& p : config.parameters) {
    const auto nominal = number_at(document, p.key_path);
    if (!nominal) root.fail("monte_carlo", "parameters: " + p.key_path + " is not a number in this scenario");
    p.nominal = *nominal;
    for (const auto& also : p.also_key_paths) {
      const auto value = number_at(document, also);
      if (!value || *value != p.nominal) {
        root.fail("monte_carlo", "parameters: " + also + " takes " + p.key_path +
                                     "'s draw, so the scenario must give it " + round_trip_text(p.nominal) + " too");
      }
    }
  }
  const auto draws = hybrid_test::draw_monte_carlo(config);
  for (int run = 0; run < config.runs; ++run) {
    std::vector<Override> overrides;
    for (std::size_t i = 0; i < config.parameters.size(); ++i) {
      overrides.push_back(
          {config.parameters[i].key_path, round_trip_text(draws[run][i]), "monte_carlo", Override::Kind::kSet});
      for (const auto& also : config.parameters[i].also_key_paths) {
        overrides.push_back({also, round_trip_text(draws[run][i]), "monte_carlo", Override::Kind::kSet});
      }
    }
    if (!config.noise_seed_key.empty()) {
      overrides.push_back({config.noise_seed_key, std::to_string(config.seed + static_cast<std::uint64_t>(run) + 1),
                           "monte_carlo", Override::Kind::kSet});
    }
    studies::StudyDocument one;
    try {
      one =
          read_case(text, file, command_line, "monte_carlo", overrides, document, result.sweep_cases.empty(), external);
    } catch (const ConfigError& e) {
      std::string where;
      for (const auto& o : overrides) where += (where.empty() ? "" : ", ") + o.key_path + " = " + o.value;
      throw ConfigError(std::string(e.what()) + " (monte_carlo run " + std::to_string(run + 1) + ": " + where + ")");
    }
    result.sweep_cases.push_back(std::get<hybrid_test::TestConfig>(one.study));
    result.sweep_values.push_back(draws[run]);
    result.case_yaml.push_back(one.effective_yaml);
  }
  result.monte_carlo = std::move(config);
  result.study = result.sweep_cases.front();
  result.effective_yaml = emitted(document);
  return result;
}

}  // namespace

std::string read_config_text(const std::filesystem::path& file) { return read_yaml_file_text(file); }

YAML::Node load_yaml_document(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  YAML::Node document = parse_yaml_text(read_config_text(file), file.string());
  apply_overrides(document, overrides);
  return document;
}

MappingReader load_root_reader(const std::filesystem::path& file, const std::vector<Override>& overrides) {
  YAML::Node document = parse_yaml_text(read_config_text(file), file.string());
  const OverrideNodes nodes = apply_overrides(document, overrides);
  return MappingReader(document, file.string(), "", nodes);
}

studies::StudyDocument load_study(const std::filesystem::path& file, const std::vector<Override>& overrides,
                                  const hybrid_test::ExternalParts& external) {
  config::InputLog inputs;  // the scenario first, then every file it names (records, matrices, ...)
  studies::StudyDocument document = parse_study(read_config_text(file), file, overrides, external);
  document.input_files = inputs.files();
  return document;
}

studies::StudyDocument parse_study(const std::string& yaml_text, const std::filesystem::path& file,
                                   const std::vector<Override>& overrides, const hybrid_test::ExternalParts& external) {
  YAML::Node document = parse_yaml_text(yaml_text, file.string());
  const OverrideNodes nodes = apply_overrides(document, overrides);
  // Sweep cases re-parse the text and re-apply these overrides, keeping every line number.
  return read_document(document, file, yaml_text, overrides, nodes, external);
}

namespace {

studies::StudyDocument read_document(YAML::Node document, const std::filesystem::path& file, const std::string& text,
                                     const std::vector<Override>& command_line, OverrideNodes overrides,
                                     const hybrid_test::ExternalParts& external, bool sweep_allowed) {
  MappingReader root(document, file.string(), "", std::move(overrides));
  studies::StudyDocument result;
  result.name = file.stem().string();
  const std::string kind = study_sections::study_kind(root, result.description);
  if (kind == "rpsd_test") {
    if (root.has("sweep") && root.has("monte_carlo")) root.fail("monte_carlo", "give either sweep or monte_carlo");
    if (root.has("sweep")) {
      // A case still holding a sweep means the key was given twice (YAML keeps both).
      if (!sweep_allowed) root.fail("sweep", "given more than once");
      return read_sweep(text, command_line, document, root, file, std::move(result), external);
    }
    if (root.has("monte_carlo")) {
      if (!sweep_allowed) root.fail("monte_carlo", "given more than once");
      return read_monte_carlo(text, command_line, document, root, file, std::move(result), external);
    }
    hybrid_test::TestConfig scenario = read_test_config(root, file, external);
    scenario.description = result.description;
    result.study = std::move(scenario);
    root.finish();
    result.effective_yaml = emitted(document);  // after reading: its file paths are absolute now
    return result;
  }
  if (kind == "rpsd_delay_compensation") {
    result.study = study_sections::delay_compensation(root);
    root.finish();
    result.effective_yaml = emitted(document);
    return result;
  }
  const auto servo = root.file("servo", "the servo-system parameter file (relative to this file)");
  if (kind == "servo_sine_sweep") {
    result.study = study_sections::sine_sweep(root, *servo);
  } else if (kind == "servo_frequency_response") {
    result.study = study_sections::frequency_response(root, *servo);
  } else {
    result.study = study_sections::max_gain(root, *servo);
  }
  root.finish();
  result.effective_yaml = emitted(document);
  return result;
}

}  // namespace

}  // namespace rpsd::scenarios
