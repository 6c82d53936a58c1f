// SIGINT and SIGTERM as a request to stop in order: the handler only sets a flag, which the
// test loop reads after every step, and makes a descriptor readable, which a server polls
// beside its sockets so that no wait outlasts the request. A second signal ends the process
// at once.
#pragma once

#include <atomic>

namespace rpsd::cli {

// Installs the handlers (once) and returns the flag they set.
const std::atomic<bool>& stop_on_signals();
// A descriptor that becomes readable (and stays so) when the flag is set; -1 if the system
// refused one (then only the flag tells). Installs the handlers too.
int stop_signal_fd();

}  // namespace rpsd::cli
