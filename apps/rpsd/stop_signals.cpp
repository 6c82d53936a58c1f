#include "stop_signals.h"

#include <sys/eventfd.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdint>

namespace rpsd::cli {
namespace {

// The process-wide objects a handler may touch: a lock-free flag and an eventfd, written only
// by the handler (write is async-signal-safe; a full counter cannot happen with one signal).
std::atomic<bool> g_stop_requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);
int g_wake_fd = -1;

void request_stop(int) {
  g_stop_requested.store(true, std::memory_order_relaxed);
  if (g_wake_fd >= 0) {
    const std::uint64_t one = 1;
    const int saved = errno;
    (void)!::write(g_wake_fd, &one, sizeof one);
    errno = saved;
  }
}

bool install() {
  g_wake_fd = ::eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  struct sigaction action {};
  action.sa_handler = request_stop;
  action.sa_flags = SA_RESETHAND;  // the second signal takes its default action
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
  return true;
}

}  // namespace

const std::atomic<bool>& stop_on_signals() {
  static const bool installed = install();
  (void)installed;
  return g_stop_requested;
}

int stop_signal_fd() {
  (void)stop_on_signals();
  return g_wake_fd;
}

}  // namespace rpsd::cli
