// What a host program (the `rpsd` Python module, or a C++ program) gives a test beside its
// file: the compensators and structures a scenario names with `kind: external`, by name. The
// scenario reader takes it (scenarios::load_study) and puts each named source into the typed
// configuration of every run it reads (the test, each case of a sweep or a Monte Carlo
// batch), so the sources travel wherever the configuration goes and no file can set one. The
// command line gives none: a file naming one is refused where it names it (exit 2).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>

#include "rpsd/compensation/external_compensator.h"
#include "rpsd/substructure/external_structure.h"

namespace rpsd::hybrid_test {

struct ExternalParts {
  std::map<std::string, std::shared_ptr<const compensation::ExternalCompensatorSource>, std::less<>> compensators;
  std::map<std::string, std::shared_ptr<const substructure::ExternalStructureSource>, std::less<>> structures;
};

}  // namespace rpsd::hybrid_test
