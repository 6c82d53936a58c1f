// SIGINT and SIGTERM as a request to stop in order: the handler only sets a flag, which the
// test loop reads after every step. A second signal ends the process at once.
#pragma once

#include <atomic>

namespace rpsd::cli {

// Installs the handlers (once) and returns the flag they set.
const std::atomic<bool>& stop_on_signals();

}  // namespace rpsd::cli
