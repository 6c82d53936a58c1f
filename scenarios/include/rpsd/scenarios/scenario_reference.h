// The scenario reference (docs/scenario-reference.md), written from the readers themselves:
// each section's reader runs on a config::KeyTable, which lists every key it asks for with
// its type, unit, default, range and meaning. `rpsd reference` prints it; a test fails when
// the committed file differs. Not real-time safe.
#pragma once

#include <set>
#include <string>

namespace rpsd::scenarios {

// The whole reference, Markdown.
std::string scenario_reference();

// The key column of every table ("experimental[].dof"): what the agreement test holds the
// readers to.
std::set<std::string> scenario_reference_keys();

}  // namespace rpsd::scenarios
