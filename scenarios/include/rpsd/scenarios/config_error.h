// The one error type of configuration loading: its message names the file, line, column
// and key path, e.g. "rig.yaml:12:3: specimen.mass_kg: expected a positive number, got -3".
#pragma once

#include <stdexcept>

namespace rpsd::scenarios {

class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace rpsd::scenarios
