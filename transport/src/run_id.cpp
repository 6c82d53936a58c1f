#include <cstdio>
#include <random>

#include "rpsd/transport/messages.h"

namespace rpsd::transport {

std::uint64_t draw_run_id() {
  std::random_device source;
  std::uint64_t id = 0;
  while (id == 0) id = (static_cast<std::uint64_t>(source()) << 32) ^ source();
  return id;
}

std::string run_id_text(std::uint64_t run_id) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(run_id));
  return text;
}

}  // namespace rpsd::transport
