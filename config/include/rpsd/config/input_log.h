// The files a document's readers opened, each once, in the order first opened: what a run's
// summary.json hashes as its inputs. A log is installed for the current thread while it lives
// (logs nest; the innermost records), and every InputFile adds its file to it, so no reader
// has to remember to report the files it names. Not real-time safe.
#pragma once

#include <filesystem>
#include <vector>

namespace rpsd::config {

class InputLog {
 public:
  InputLog();
  ~InputLog();
  InputLog(const InputLog&) = delete;
  InputLog& operator=(const InputLog&) = delete;

  // Absolute, normalised paths.
  const std::vector<std::filesystem::path>& files() const { return files_; }

  // Adds `file` to the current thread's log, if one is installed and it is not listed yet.
  static void note(const std::filesystem::path& file);

 private:
  std::vector<std::filesystem::path> files_;
  InputLog* outer_ = nullptr;
};

}  // namespace rpsd::config
