#include "rpsd/realtime/kernel_preemption.h"

#include <sys/utsname.h>
#include <zlib.h>

#include <array>
#include <fstream>
#include <optional>
#include <sstream>

namespace rpsd::realtime {
namespace {

constexpr std::array<std::pair<std::string_view, PreemptionModel>, 5> kNames{{
    {"none", PreemptionModel::kNone},
    {"voluntary", PreemptionModel::kVoluntary},
    {"full", PreemptionModel::kFull},
    {"lazy", PreemptionModel::kLazy},
    {"rt", PreemptionModel::kRealTime},
}};

std::optional<PreemptionModel> model_named(std::string_view name) {
  for (const auto& [n, m] : kNames) {
    if (n == name) return m;
  }
  return std::nullopt;
}

std::optional<std::string> read_text(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) return std::nullopt;
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) return std::nullopt;
  return text.str();
}

// uname -v: "#1 SMP PREEMPT_DYNAMIC ...", "#1 SMP PREEMPT_RT ...", "#1 SMP PREEMPT ...".
bool version_says(std::string_view version, std::string_view word) {
  std::istringstream words{std::string(version)};
  std::string w;
  while (words >> w) {
    if (w == word) return true;
  }
  return false;
}

// "none voluntary (full) lazy": the active model in parentheses.
std::optional<PreemptionModel> active_in_debugfs(const std::string& text) {
  const auto open = text.find('('), close = text.find(')');
  if (open == std::string::npos || close == std::string::npos || close < open) return std::nullopt;
  return model_named(std::string_view(text).substr(open + 1, close - open - 1));
}

// preempt=MODE among the boot parameters.
std::optional<PreemptionModel> boot_parameter(const std::string& cmdline) {
  std::istringstream words(cmdline);
  std::string w;
  while (words >> w) {
    if (w == "--") break;  // what follows is init's, not the kernel's
    if (w.rfind("preempt=", 0) == 0) return model_named(std::string_view(w).substr(8));
  }
  return std::nullopt;
}

// The build's model in a gzipped kernel configuration: the CONFIG_PREEMPT_* choice set to y.
std::optional<PreemptionModel> configured(const std::filesystem::path& config_gz) {
  gzFile in = gzopen(config_gz.c_str(), "rb");
  if (in == nullptr) return std::nullopt;
  std::optional<PreemptionModel> model;
  std::array<char, 512> line{};
  while (gzgets(in, line.data(), static_cast<int>(line.size())) != nullptr) {
    const std::string_view l(line.data());
    const auto is = [&](std::string_view key) { return l.rfind(key, 0) == 0 && l.substr(key.size(), 2) == "=y"; };
    if (is("CONFIG_PREEMPT_RT")) model = PreemptionModel::kRealTime;
    if (!model && is("CONFIG_PREEMPT_NONE")) model = PreemptionModel::kNone;
    if (!model && is("CONFIG_PREEMPT_VOLUNTARY")) model = PreemptionModel::kVoluntary;
    if (!model && is("CONFIG_PREEMPT_LAZY")) model = PreemptionModel::kLazy;
    if (!model && is("CONFIG_PREEMPT")) model = PreemptionModel::kFull;
  }
  gzclose(in);
  return model;
}

std::string running_version() {
  utsname u{};
  return ::uname(&u) == 0 ? std::string(u.version) : std::string();
}

}  // namespace

std::string_view preemption_name(PreemptionModel model) {
  for (const auto& [n, m] : kNames) {
    if (m == model) return n;
  }
  return "unknown";
}

bool preempts_for_real_time(PreemptionModel model) {
  return model == PreemptionModel::kFull || model == PreemptionModel::kLazy || model == PreemptionModel::kRealTime;
}

KernelPreemption read_kernel_preemption(const KernelFiles& files) {
  const std::string version = files.version.empty() ? running_version() : files.version;
  if (const auto flag = read_text(files.realtime_flag); flag && flag->rfind('1', 0) == 0)
    return {PreemptionModel::kRealTime, files.realtime_flag.string()};
  if (version_says(version, "PREEMPT_RT")) return {PreemptionModel::kRealTime, "uname -v: PREEMPT_RT"};
  if (const auto text = read_text(files.debugfs_preempt)) {
    if (const auto model = active_in_debugfs(*text)) return {*model, files.debugfs_preempt.string()};
  }
  const bool dynamic = version_says(version, "PREEMPT_DYNAMIC");
  if (dynamic) {
    if (const auto cmdline = read_text(files.cmdline)) {
      if (const auto model = boot_parameter(*cmdline))
        return {*model, files.cmdline.string() + ": preempt=" + std::string(preemption_name(*model))};
    }
  }
  if (const auto model = configured(files.config_gz)) {
    return {*model,
            files.config_gz.string() +
                (dynamic ? ": PREEMPT_DYNAMIC booted without preempt=, the build's default" : ": the build's model")};
  }
  if (!dynamic && version_says(version, "PREEMPT")) return {PreemptionModel::kFull, "uname -v: PREEMPT"};
  return {PreemptionModel::kUnknown, dynamic ? "uname -v: PREEMPT_DYNAMIC, its mode not readable here"
                                             : "uname -v: no PREEMPT, so none or voluntary (not told apart)"};
}

}  // namespace rpsd::realtime
