// Large blocks get their own mapping, given back when freed, even after glibc would have
// raised its threshold: the mechanism that keeps a long run's heap from growing.
#include "rpsd/realtime/large_blocks.h"

#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>
#include <cstring>

namespace rpsd::realtime {
namespace {

std::size_t mapped_bytes() { return mallinfo2().hblkhd; }

// Allocates and touches a block, so the compiler cannot drop the allocation.
void* touched_block(std::size_t bytes) {
  void* p = std::malloc(bytes);
  if (p) std::memset(p, 1, bytes);
  return p;
}

TEST(LargeBlocks, AFreedLargeBlockGoesBackToTheSystemAndTheThresholdStays) {
  ASSERT_TRUE(map_large_blocks_separately(64 * 1024));
  // Without the setting, freeing this mapped 1 MiB block would raise glibc's threshold to
  // 1 MiB, and the 256 KiB block below would come from the heap.
  std::free(touched_block(1024 * 1024));
  const std::size_t before = mapped_bytes();
  void* block = touched_block(256 * 1024);
  ASSERT_NE(block, nullptr);
  EXPECT_GE(mapped_bytes(), before + 256 * 1024);  // a mapping of its own
  std::free(block);
  EXPECT_EQ(mapped_bytes(), before);  // and unmapped when freed
}

TEST(LargeBlocks, RefusesAThresholdGlibcCannotTake) {
  EXPECT_FALSE(map_large_blocks_separately(0));
  EXPECT_FALSE(map_large_blocks_separately(std::size_t{1} << 40));
}

}  // namespace
}  // namespace rpsd::realtime
