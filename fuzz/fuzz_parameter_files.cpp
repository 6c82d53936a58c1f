// libFuzzer target for the parameter files: servo parameters, servo node files, controller
// emulator files and plugin site emulator files (the readers take a path, so each input is
// written to a file first). The first byte picks the reader. Bad input must end in an exception with a message, never a
// crash, a hang or a sanitizer report.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <fstream>
#include <string>

#include "rpsd/scenarios/plugin_site_file.h"
#include "rpsd/scenarios/servo_node_file.h"
#include "rpsd/scenarios/servo_parameters_file.h"

namespace {

// Beside the shipped node files, so their relative paths (../../examples/servo/...) resolve.
const std::filesystem::path& input_file() {
  static const std::filesystem::path path =
      std::filesystem::path(RPSD_FUZZ_NODES_DIR) / ("fuzz-input-" + std::to_string(::getpid()) + ".yaml");
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const int reader = data[0] % 4;
  {
    std::ofstream out(input_file(), std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
  }
  try {
    if (reader == 0) rpsd::scenarios::load_servo_parameters(input_file());
    if (reader == 1) rpsd::scenarios::load_servo_node(input_file());
    if (reader == 2) rpsd::scenarios::load_controller_emulator(input_file());
    if (reader == 3) rpsd::scenarios::load_plugin_site_emulator(input_file());
  } catch (const std::exception& e) {
    if (std::string(e.what()).empty()) std::abort();
  }
  std::filesystem::remove(input_file());
  return 0;
}
