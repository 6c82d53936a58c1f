#include "rpsd/scenarios/servo_parameters_file.h"

#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {

servo::ServoSystemParameters load_servo_parameters(const std::filesystem::path& file) {
  MappingReader root(load_yaml_file(file), file.string(), "");
  return servo::read_servo_parameters(root);
}

}  // namespace rpsd::scenarios
