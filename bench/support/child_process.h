// Child processes of the bench steps that run rpsd (or ddsperf) as separate programs: started
// with extra environment variables and their output in a file, stopped by signal, and ended
// by the destructor whatever happens. Not real-time safe (benchmark drivers only).
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

namespace rpsd::bench {

// Thrown by waits once this process has been asked to stop (install_stop_handlers).
struct Interrupted : std::runtime_error {
  Interrupted() : std::runtime_error("interrupted (SIGINT or SIGTERM)") {}
};

class ChildProcess {
 public:
  // Starts argv[0] (searched in PATH) with `env` ("NAME=value") added to this process's
  // environment, stdout and stderr appended to `log` (/dev/null when empty). Throws
  // std::runtime_error when fork fails; a program that cannot be executed exits with 127.
  ChildProcess(const std::vector<std::string>& argv, const std::vector<std::string>& env,
               const std::filesystem::path& log);
  // Kills the child (SIGKILL) if it still runs, and reaps it.
  ~ChildProcess();
  ChildProcess(const ChildProcess&) = delete;
  ChildProcess& operator=(const ChildProcess&) = delete;

  pid_t pid() const { return pid_; }
  bool running();
  // Waits up to `timeout_s` for the child to exit; its exit code, or -1 (still running or
  // killed by a signal: see killed_by()). Throws Interrupted once this process has
  // been asked to stop (install_stop_handlers), so that the destructors end the children.
  int wait_for(double timeout_s);
  // Sends `signal` and waits up to `timeout_s` (never throws); SIGKILL after that. The exit
  // code as wait_for gives it.
  int stop(int signal, double timeout_s);
  // The signal that ended the child, or 0.
  int killed_by() const { return signal_; }
  // The command line, words joined by spaces (for reports).
  const std::string& command() const { return command_; }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
  int code_ = -1, signal_ = 0;
  std::string command_;
  bool reap(bool block);
  int wait(double timeout_s, bool interruptible);
};

// SIGINT and SIGTERM no longer end this process at once: waits in ChildProcess throw instead,
// so that every child is ended by its destructor.
void install_stop_handlers();
bool stop_requested();

// The whole content of a text file ("" when it cannot be read).
std::string read_text(const std::filesystem::path& file);

}  // namespace rpsd::bench
