// Keeps large memory blocks out of the heap so that a long real-time run does not grow.
//
// glibc serves a block of 128 KiB or more with its own mapping, but after the first such block
// is freed it raises that threshold to the block's size, and from then on large blocks come
// from the heap. Cyclone DDS's receive thread replaces its receive buffer whenever the buffer
// is used up (every 20 minutes or so at 1024 Hz with the default 1 MiB, every 2 minutes with
// 128 KiB) and frees the old one; from the heap, small allocations took over the freed space
// and each new buffer extended the heap (with memory locked, resident at once): the
// coordinator grew by one buffer each time (2026-11-21, bench/realtime_long_run).
#pragma once

#include <cstddef>

namespace rpsd::realtime {

// Blocks of `threshold_bytes` or more get a mapping of their own from now on, returned to
// the system when freed, and the threshold no longer moves. Process-wide; not real-time safe.
// Returns false if glibc refused the setting.
bool map_large_blocks_separately(std::size_t threshold_bytes = 64 * 1024);

}  // namespace rpsd::realtime
