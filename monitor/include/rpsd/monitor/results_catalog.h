// The output folders under --results the viewer lists: every folder rpsd wrote (it holds a
// summary.json) — a test, a sweep and its cases, a Monte Carlo batch and its runs, a study,
// a site server — with what its summary says it is and whether it has a time history.
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace rpsd::monitor {

struct ResultsFolder {
  std::string path;      // relative to the results folder, '/'-separated; "" for the folder itself
  std::string kind;      // summary.json's "study" or "kind" ("rpsd_test", "rpsd_test_sweep", "site_server", ...)
  std::string result;    // "completed", "stopped", "running", ...
  std::string scenario;  // the scenario file it ran, when the summary says
  bool has_time_history = false;
};

struct CatalogOptions {
  int max_depth = 4;               // folders below the results folder
  std::size_t max_folders = 2000;  // listed at most (a results folder of many batches)
};

// Sorted by path. Folders it cannot read, and summaries that are not JSON, are listed with
// kind "unknown" rather than refused: the viewer shows what is there.
std::vector<ResultsFolder> list_results_folders(const std::filesystem::path& root, const CatalogOptions& options = {});
nlohmann::json catalog_json(const std::vector<ResultsFolder>& folders);

}  // namespace rpsd::monitor
