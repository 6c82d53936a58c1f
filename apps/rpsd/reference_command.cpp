// `rpsd reference [--check FILE]` (hidden): the scenario reference, written from the readers;
// with --check, exit 1 when FILE differs from it (the drift test of docs/scenario-reference.md).
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "commands.h"
#include "rpsd/scenarios/scenario_reference.h"

namespace rpsd::cli {

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
      throw std::runtime_error(*check +
                               " differs from what the readers say; regenerate it: rpsd reference > "
                               "docs/scenario-reference.md");
    }
    std::cout << *check << ": matches the readers\n";
  });
}

}  // namespace rpsd::cli
