// libFuzzer target for the scenario parser: any YAML text, read as if it were a file in
// scenarios/ (so relative paths to parameter and record files resolve as for the shipped
// scenarios). Bad input must end in an exception with a message, never a crash, a hang or a
// sanitizer report. ConfigError is the rule; other std::exceptions from deeper checks are
// accepted as long as they carry a message.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <exception>
#include <string>

#include "rpsd/scenarios/config_error.h"
#include "rpsd/scenarios/study_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    rpsd::scenarios::parse_study(text, RPSD_FUZZ_SCENARIO_ANCHOR);
  } catch (const rpsd::scenarios::ConfigError& e) {
    if (std::string(e.what()).empty()) std::abort();
  } catch (const std::exception& e) {
    if (std::string(e.what()).empty()) std::abort();
  }
  return 0;
}
