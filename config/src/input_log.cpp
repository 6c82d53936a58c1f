#include "rpsd/config/input_log.h"

#include <algorithm>

namespace rpsd::config {
namespace {

thread_local InputLog* current_log = nullptr;

}  // namespace

InputLog::InputLog() : outer_(current_log) { current_log = this; }

InputLog::~InputLog() { current_log = outer_; }

void InputLog::note(const std::filesystem::path& file) {
  if (current_log == nullptr) return;
  const std::filesystem::path path = std::filesystem::absolute(file).lexically_normal();
  auto& files = current_log->files_;
  if (std::find(files.begin(), files.end(), path) == files.end()) files.push_back(path);
}

}  // namespace rpsd::config
