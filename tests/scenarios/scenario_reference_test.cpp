// docs/scenario-reference.md and the readers agree: the readers, run over every YAML file
// of the repository (examples/, tests/), accept no key the reference lacks, and every key
// the reference lists is accepted on one of them. The reference is written by running the
// readers on a key table, so a disagreement means a branch the listing does not take (a
// has() where an optional_* read belongs) or a table the reference files under the wrong
// path.
#include <gtest/gtest.h>

#include <yaml-cpp/yaml.h>
#include <filesystem>
#include <set>
#include <string>

#include "../servo/paper_rig.h"
#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/plugin_site_file.h"
#include "rpsd/scenarios/scenario_reference.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/scenarios/site_server_file.h"
#include "rpsd/scenarios/study_file.h"
#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {
namespace {

namespace fs = std::filesystem;

// Sections that take another section's keys, as the reference says in words.
const std::vector<std::pair<std::string, std::string>> kSameKeysAs = {
    {"plant.", "servo."},           // rpsd_delay_compensation's plant
    {"actuator.servo.", "servo."},  // the node's and the emulator's plant
    {"whole_structure_damping.", "structure.damping."},
};

std::string as_listed(const std::string& key) {
  for (const auto& [from, to] : kSameKeysAs) {
    if (key.rfind(from, 0) == 0) return to + key.substr(from.size());
  }
  return key;
}

// Reads the file with the reader its top-level keys call for.
void read(const fs::path& file) {
  const YAML::Node root = load_yaml_file(file);
  if (root["study"]) {
    (void)load_study(file);
  } else if (root["node"]) {
    (void)load_servo_node(file);
  } else if (root["udp"]) {
    (void)load_controller_emulator(file);
  } else if (root["plugin_site"]) {
    (void)load_plugin_site_emulator(file);
  } else if (root["target"]) {
    (void)load_speedgoat_emulator(file);
  } else if (root["listen"]) {
    (void)load_site_server(file);
  } else {
    (void)load_servo_parameters(file);
  }
}

// A file meant to be refused still tells which keys were accepted before the error.
void read_any(const fs::path& file) {
  try {
    read(file);
  } catch (const ConfigError&) {
  }
}

fs::path reference_files() { return testing::source_dir() / "tests/scenarios/data/reference"; }

// Every key the readers accept on the repository's files, as the reference writes it.
std::set<std::string> accepted_keys() {
  std::set<std::string> log;
  log_accepted_keys(&log);
  for (const char* dir : {"examples", "tests"}) {
    for (const auto& entry : fs::recursive_directory_iterator(testing::source_dir() / dir)) {
      if (entry.is_regular_file() && entry.path().extension() == ".yaml") read_any(entry.path());
    }
  }
  log_accepted_keys(nullptr);
  std::set<std::string> keys;
  for (const auto& key : log) keys.insert(as_listed(key));
  return keys;
}

std::string lines(const std::set<std::string>& keys) {
  std::string text;
  for (const auto& key : keys) text += "  " + key + "\n";
  return text;
}

TEST(ScenarioReference, ListsEveryKeyTheReadersAccept) {
  const std::set<std::string> listed = scenario_reference_keys();
  std::set<std::string> unlisted;
  for (const auto& key : accepted_keys()) {
    if (!listed.contains(key)) unlisted.insert(key);
  }
  EXPECT_TRUE(unlisted.empty()) << "keys a reader accepts that docs/scenario-reference.md lacks:\n" << lines(unlisted);
}

TEST(ScenarioReference, ListsOnlyKeysTheReadersAccept) {
  const std::set<std::string> accepted = accepted_keys();
  std::set<std::string> unread;
  for (const auto& key : scenario_reference_keys()) {
    if (!accepted.contains(key)) unread.insert(key);
  }
  EXPECT_TRUE(unread.empty()) << "keys docs/scenario-reference.md lists that no reader accepted on the "
                                 "repository's YAML files (a wrong path, or a file to add under "
                                 "tests/scenarios/data/reference/):\n"
                              << lines(unread);
}

// They are there for their keys: one refused would hide those after its error.
TEST(ScenarioReference, ItsCoverageFilesAreRead) {
  for (const auto& entry : fs::directory_iterator(reference_files())) {
    if (entry.path().extension() == ".yaml") {
      EXPECT_NO_THROW(read(entry.path())) << entry.path();
    }
  }
}

}  // namespace
}  // namespace rpsd::scenarios
