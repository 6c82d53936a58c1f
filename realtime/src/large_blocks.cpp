#include "rpsd/realtime/large_blocks.h"

#include <malloc.h>

#include <climits>

namespace rpsd::realtime {

bool map_large_blocks_separately(std::size_t threshold_bytes) {
  if (threshold_bytes == 0 || threshold_bytes > static_cast<std::size_t>(INT_MAX)) return false;
  // Setting the threshold explicitly also turns off glibc's dynamic adjustment of it.
  return mallopt(M_MMAP_THRESHOLD, static_cast<int>(threshold_bytes)) == 1;
}

}  // namespace rpsd::realtime
