#include "allocation_counter.h"

#include <atomic>
#include <cstddef>
#include <cstdlib>
#include <new>

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);
void __libc_free(void*);
}

namespace {
// Only the thread that opened the window is counted: the rule is that the real-time thread
// allocates nothing, while helper threads (the recorder's writer) may.
thread_local bool t_counting = false;
std::atomic<long> g_news{0};
std::atomic<long> g_c_allocations{0};

inline void count(std::atomic<long>& counter) {
  if (t_counting) {
    counter.fetch_add(1, std::memory_order_relaxed);
    // Set this to find the allocation in a debugger (the abort shows its stack).
    if (std::getenv("RPSD_ABORT_ON_ALLOCATION")) std::abort();
  }
}

void* new_impl(std::size_t n) {
  count(g_news);
  if (void* p = __libc_malloc(n == 0 ? 1 : n)) return p;
  throw std::bad_alloc();
}

void* new_aligned_impl(std::size_t n, std::align_val_t alignment) {
  count(g_news);
  const auto a = static_cast<std::size_t>(alignment);
  if (void* p = __libc_memalign(a, (n + a - 1) / a * a)) return p;
  throw std::bad_alloc();
}
}  // namespace

namespace rpsd::testing {
void begin_counting_allocations() {
  g_news = 0;
  g_c_allocations = 0;
  t_counting = true;
}
void* volatile g_kept = nullptr;
void keep(void* pointer) { g_kept = pointer; }
AllocationCounts end_counting_allocations() {
  t_counting = false;
  return {g_news.load(), g_c_allocations.load()};
}
}  // namespace rpsd::testing

extern "C" {
void* malloc(std::size_t n) noexcept {
  count(g_c_allocations);
  return __libc_malloc(n);
}
void* calloc(std::size_t c, std::size_t n) noexcept {
  count(g_c_allocations);
  return __libc_calloc(c, n);
}
void* realloc(void* p, std::size_t n) noexcept {
  count(g_c_allocations);
  return __libc_realloc(p, n);
}
void free(void* p) noexcept { __libc_free(p); }
void* memalign(std::size_t a, std::size_t n) noexcept {
  count(g_c_allocations);
  return __libc_memalign(a, n);
}
void* aligned_alloc(std::size_t a, std::size_t n) noexcept {
  count(g_c_allocations);
  return __libc_memalign(a, n);
}
int posix_memalign(void** p, std::size_t a, std::size_t n) noexcept {
  count(g_c_allocations);
  *p = __libc_memalign(a, n);
  return *p ? 0 : 12;  // ENOMEM
}
}

void* operator new(std::size_t n) { return new_impl(n); }
void* operator new[](std::size_t n) { return new_impl(n); }
void* operator new(std::size_t n, const std::nothrow_t&) noexcept {
  count(g_news);
  return __libc_malloc(n == 0 ? 1 : n);
}
void* operator new[](std::size_t n, const std::nothrow_t&) noexcept {
  count(g_news);
  return __libc_malloc(n == 0 ? 1 : n);
}
void* operator new(std::size_t n, std::align_val_t a) { return new_aligned_impl(n, a); }
void* operator new[](std::size_t n, std::align_val_t a) { return new_aligned_impl(n, a); }
void operator delete(void* p) noexcept { __libc_free(p); }
void operator delete[](void* p) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t) noexcept { __libc_free(p); }
void operator delete(void* p, std::align_val_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::align_val_t) noexcept { __libc_free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { __libc_free(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { __libc_free(p); }
