// The viewer's list: every folder rpsd wrote under --results, what its summary says it is,
// whether it has a time history; links are not followed.
#include "rpsd/monitor/results_catalog.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <fstream>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;

TEST(ResultsCatalog, ListsTestsSweepsCasesAndSiteServers) {
  const fs::path base = fs::temp_directory_path() / ("rpsd-monitor-catalog-" + std::to_string(::getpid()));
  fs::remove_all(base);
  const fs::path root = base / "results";
  fs::create_directories(root / "sweep" / "case_000");
  fs::create_directories(root / "site");
  fs::create_directories(root / "empty");
  fs::create_directories(base / "elsewhere");
  std::ofstream(root / "sweep" / "summary.json")
      << R"({"study":"rpsd_test_sweep","result":"completed","scenario":"s.yaml"})";
  std::ofstream(root / "sweep" / "case_000" / "summary.json") << R"({"study":"rpsd_test","result":"stopped"})";
  std::ofstream(root / "sweep" / "case_000" / "time_history.csv") << "step\n";
  std::ofstream(root / "site" / "summary.json") << R"({"kind":"site_server","result":"completed"})";
  std::ofstream(root / "site" / "time_history.csv") << "step\n";
  std::ofstream(base / "elsewhere" / "summary.json") << R"({"study":"rpsd_test"})";
  fs::create_directory_symlink(base / "elsewhere", root / "link");
  std::ofstream(root / "broken.json");
  fs::create_directories(root / "broken");
  std::ofstream(root / "broken" / "summary.json") << "not json";

  const std::vector<ResultsFolder> list = list_results_folders(root);
  ASSERT_EQ(list.size(), 4u);
  EXPECT_EQ(list[0].path, "broken");
  EXPECT_EQ(list[0].kind, "unknown");
  EXPECT_EQ(list[1].path, "site");
  EXPECT_EQ(list[1].kind, "site_server");
  EXPECT_TRUE(list[1].has_time_history);
  EXPECT_EQ(list[2].path, "sweep");
  EXPECT_EQ(list[2].kind, "rpsd_test_sweep");
  EXPECT_EQ(list[2].scenario, "s.yaml");
  EXPECT_FALSE(list[2].has_time_history);
  EXPECT_EQ(list[3].path, "sweep/case_000");
  EXPECT_EQ(list[3].result, "stopped");
  EXPECT_TRUE(list[3].has_time_history);
  CatalogOptions shallow;
  shallow.max_depth = 1;
  EXPECT_EQ(list_results_folders(root, shallow).size(), 3u);
  fs::remove_all(base);
}

}  // namespace
}  // namespace rpsd::monitor
