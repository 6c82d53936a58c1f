// Reads a study file (any `study:` kind, an `rpsd_test` with its sweep too) into a
// studies::StudyDocument, with `--set` overrides applied first. Parameter and record files a
// study names are relative to the study file.
#pragma once

#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rpsd/scenarios/yaml_reader.h"

#include "rpsd/hybrid_test/external_parts.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/studies/study_config.h"

namespace rpsd::scenarios {

// A `--set key.path=value` override; the value is read as YAML (a number, a word, a list).
struct Override {
  std::string key_path;
  std::string value;
  std::string origin;  // how errors name it ("--set #2"); "--set" when empty
  // kRecord: `value` is a record ({file, format}) that replaces the ground motion's record and
  // keeps its processing (trim, baseline correction, scaling, padding).
  enum class Kind { kSet, kRecord } kind = Kind::kSet;
};

// Parses "key.path=value"; throws ConfigError naming the text when there is no '='.
Override parse_override(const std::string& text);
// A configuration file's text (ConfigError naming the file if it cannot be read).
std::string read_config_text(const std::filesystem::path& file);
// A configuration file parsed, with the overrides applied (ConfigError with file and line).
YAML::Node load_yaml_document(const std::filesystem::path& file, const std::vector<Override>& overrides);
// The same file's root reader: an error in a value an override gave names the override
// ("--set #2 (key=value)"), one in the file names the file, line and column.
MappingReader load_root_reader(const std::filesystem::path& file, const std::vector<Override>& overrides);

// The default-parameter integrator for a scheme name (central_difference, newmark, hht_alpha,
// generalized_alpha, alpha_os, chang, chen_ricles, kolay_ricles_alpha); nullopt if unknown.
std::optional<integrators::IntegratorConfig> default_integrator(std::string_view name);

// Reads a study file; every error names file, line, column and key path. `external`: the
// compensators and structures a host program gives for `kind: external` (none from the
// command line: such a file is refused at the name). Not real-time safe.
studies::StudyDocument load_study(const std::filesystem::path& file, const std::vector<Override>& overrides = {},
                                  const hybrid_test::ExternalParts& external = {});

// The same from YAML text; `as_file` names it in messages and anchors relative paths.
studies::StudyDocument parse_study(const std::string& yaml_text, const std::filesystem::path& as_file,
                                   const std::vector<Override>& overrides = {},
                                   const hybrid_test::ExternalParts& external = {});

// `points` values from start to stop, equally spaced in log10. Both must be positive.
std::vector<double> log_spaced(double start, double stop, int points);

}  // namespace rpsd::scenarios
