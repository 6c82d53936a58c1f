#include "rpsd/monitor/results_catalog.h"

#include <algorithm>
#include <fstream>
#include <system_error>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;

std::string text_of(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_string() ? it->get<std::string>() : std::string();
}

ResultsFolder describe(const fs::path& root, const fs::path& dir) {
  ResultsFolder f;
  f.path = fs::relative(dir, root).generic_string();
  if (f.path == ".") f.path.clear();
  std::error_code ec;
  f.has_time_history = fs::is_regular_file(dir / "time_history.csv", ec);
  f.kind = "unknown";
  std::ifstream in(dir / "summary.json");
  const nlohmann::json summary = nlohmann::json::parse(in, nullptr, false);
  if (summary.is_object()) {
    f.kind = text_of(summary, "study");
    if (f.kind.empty()) f.kind = text_of(summary, "kind");
    if (f.kind.empty()) f.kind = "unknown";
    f.result = text_of(summary, "result");
    f.scenario = text_of(summary, "scenario");
  }
  return f;
}

void walk(const fs::path& root, const fs::path& dir, int depth, const CatalogOptions& options,
          std::vector<ResultsFolder>& out) {
  if (out.size() >= options.max_folders) return;
  std::error_code ec;
  if (fs::is_regular_file(dir / "summary.json", ec)) out.push_back(describe(root, dir));
  if (depth >= options.max_depth) return;
  std::vector<fs::path> children;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    // Links are not followed: a link out of the results folder is not listed (nor served).
    if (it->is_directory(ec) && !it->is_symlink(ec)) children.push_back(it->path());
  }
  std::sort(children.begin(), children.end());
  for (const fs::path& child : children) walk(root, child, depth + 1, options, out);
}

}  // namespace

std::vector<ResultsFolder> list_results_folders(const fs::path& root, const CatalogOptions& options) {
  std::vector<ResultsFolder> out;
  std::error_code ec;
  if (!fs::is_directory(root, ec)) return out;
  walk(root, root, 0, options, out);
  std::sort(out.begin(), out.end(), [](const ResultsFolder& a, const ResultsFolder& b) { return a.path < b.path; });
  return out;
}

nlohmann::json catalog_json(const std::vector<ResultsFolder>& folders) {
  nlohmann::json list = nlohmann::json::array();
  for (const ResultsFolder& f : folders) {
    list.push_back({{"path", f.path},
                    {"kind", f.kind},
                    {"result", f.result},
                    {"scenario", f.scenario},
                    {"has_time_history", f.has_time_history}});
  }
  return nlohmann::json{{"folders", std::move(list)}};
}

}  // namespace rpsd::monitor
