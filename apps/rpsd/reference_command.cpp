// `rpsd reference [--check FILE]` (hidden): the scenario reference, written from the readers;
// with --check, exit 1 when FILE differs from it (the drift test of docs/scenario-reference.md).
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "rpsd/scenarios/scenario_reference.h"

namespace rpsd::cli {
namespace {

// The first line where the two texts part, counted from 1: where to look in a stale file.
std::size_t first_differing_line(const std::string& a, const std::string& b) {
  std::istringstream in_a(a), in_b(b);
  std::string line_a, line_b;
  for (std::size_t n = 1;; ++n) {
    const bool more_a = static_cast<bool>(std::getline(in_a, line_a));
    const bool more_b = static_cast<bool>(std::getline(in_b, line_b));
    if (more_a != more_b || line_a != line_b || !more_a) return n;
  }
}

}  // namespace

void add_reference(CLI::App& app) {
  auto check = std::make_shared<std::string>();
  auto* reference = app.add_subcommand("reference", "Print the scenario reference (docs/scenario-reference.md)");
  reference->group("");  // hidden: a tool for the documentation, not for a test
  reference->add_option("--check", *check, "Exit 1 if this file differs from the reference")->check(CLI::ExistingFile);
  reference->callback([check] {
    const std::string text = scenarios::scenario_reference();
    if (check->empty()) {
      std::cout << text;
      return;
    }
    std::ifstream in(*check);
    std::stringstream committed;
    committed << in.rdbuf();
    if (committed.str() != text) {
      throw std::runtime_error(*check + " differs from what the readers say (from line " +
                               std::to_string(first_differing_line(committed.str(), text)) +
                               "); regenerate it from the source tree: build/rpsd reference > "
                               "docs/scenario-reference.md");
    }
    std::cout << *check << ": matches the readers\n";
  });
}

}  // namespace rpsd::cli
