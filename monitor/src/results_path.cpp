#include "rpsd/monitor/results_path.h"

#include <algorithm>
#include <array>
#include <system_error>

namespace rpsd::monitor {

std::optional<std::filesystem::path> resolve_under(const std::filesystem::path& root, std::string_view relative) {
  namespace fs = std::filesystem;
  if (relative.find('\0') != std::string_view::npos) return std::nullopt;
  const fs::path rel{std::string(relative)};
  if (rel.has_root_path()) return std::nullopt;
  for (const fs::path& part : rel) {
    if (part == "..") return std::nullopt;
  }
  std::error_code ec;
  const fs::path base = fs::canonical(root, ec);
  if (ec) return std::nullopt;
  const fs::path target = fs::canonical(base / rel, ec);  // follows every link
  if (ec) return std::nullopt;
  // Component by component: /results-old is not under /results.
  auto b = base.begin();
  auto t = target.begin();
  for (; b != base.end(); ++b, ++t) {
    if (t == target.end() || *t != *b) return std::nullopt;
  }
  return target;
}

bool servable_file_name(std::string_view name) {
  if (name.empty() || name.front() == '.' || name.find('/') != std::string_view::npos ||
      name.find('\\') != std::string_view::npos || name.find('\0') != std::string_view::npos) {
    return false;
  }
  static constexpr std::array<std::string_view, 6> kExtensions{".csv", ".json", ".yaml", ".md", ".png", ".txt"};
  return std::any_of(kExtensions.begin(), kExtensions.end(), [&](std::string_view ext) {
    return name.size() > ext.size() && name.substr(name.size() - ext.size()) == ext;
  });
}

}  // namespace rpsd::monitor
