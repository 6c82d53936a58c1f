// Counts heap allocations made while a window is open, to prove that a real-time path
// allocates nothing. Linking rpsd_test_allocation_counter replaces the global operator
// new/delete and the C allocation functions (Eigen allocates with malloc, not new); glibc
// allows this and exports the originals as __libc_*. Link it only into test binaries.
#pragma once

namespace rpsd::testing {

struct AllocationCounts {
  long operator_new = 0;
  long c_allocations = 0;  // malloc, calloc, realloc and the aligned variants
  long total() const { return operator_new + c_allocations; }
};

// Opens the counting window on the calling thread (counts restart at zero); allocations
// by other threads are not counted.
void begin_counting_allocations();
// Closes the window and returns what was counted while it was open.
AllocationCounts end_counting_allocations();

// Keeps a pointer observable so that the compiler cannot elide a new/delete or
// malloc/free pair in a test that checks the counter itself.
void keep(void* pointer);

}  // namespace rpsd::testing
