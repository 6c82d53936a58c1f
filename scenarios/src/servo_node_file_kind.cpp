#include "rpsd/scenarios/servo_node_file.h"

#include "rpsd/scenarios/yaml_reader.h"

namespace rpsd::scenarios {

bool is_servo_node_file(const std::filesystem::path& file) {
  const YAML::Node document = load_yaml_document(file, {});
  return document.IsMap() && document["node"] && document["actuator"] && !document["study"];
}

}  // namespace rpsd::scenarios
