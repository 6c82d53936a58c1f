// Keeps large memory blocks out of the heap so that a long real-time run does not grow: otherwise glibc
// serves them from the heap once the first one is freed, and each receive buffer Cyclone DDS replaces
// extends the heap. What happened and how it was found: docs/realtime.md
#pragma once

#include <cstddef>

namespace rpsd::realtime {

// Blocks of `threshold_bytes` or more get a mapping of their own from now on, returned to
// the system when freed, and the threshold no longer moves. Process-wide; not real-time safe.
// Returns false if glibc refused the setting.
bool map_large_blocks_separately(std::size_t threshold_bytes = 64 * 1024);

}  // namespace rpsd::realtime
