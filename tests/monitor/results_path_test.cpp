// The viewer serves files under --results only: no `..`, no absolute path, no link out,
// no sibling whose name starts like the results folder's.
#include "rpsd/monitor/results_path.h"

#include <gtest/gtest.h>

#include <unistd.h>
#include <fstream>

namespace rpsd::monitor {
namespace {

namespace fs = std::filesystem;

class ResultsPath : public ::testing::Test {
 protected:
  void SetUp() override {
    base_ = fs::temp_directory_path() / ("rpsd-monitor-path-" + std::to_string(::getpid()));
    fs::remove_all(base_);
    fs::create_directories(base_ / "results" / "test-1");
    fs::create_directories(base_ / "results-old");
    std::ofstream(base_ / "results" / "test-1" / "summary.json") << "{}";
    std::ofstream(base_ / "results-old" / "secret.csv") << "x";
    std::ofstream(base_ / "outside.csv") << "x";
    fs::create_symlink(base_ / "outside.csv", base_ / "results" / "test-1" / "link.csv");
    fs::create_directory_symlink(base_, base_ / "results" / "up");
  }
  void TearDown() override { fs::remove_all(base_); }
  fs::path root() const { return base_ / "results"; }
  fs::path base_;
};

TEST_F(ResultsPath, AFolderOrFileUnderTheRootResolves) {
  EXPECT_EQ(resolve_under(root(), ""), fs::canonical(root()));
  EXPECT_EQ(resolve_under(root(), "test-1"), fs::canonical(root() / "test-1"));
  EXPECT_EQ(resolve_under(root(), "test-1/summary.json"), fs::canonical(root() / "test-1" / "summary.json"));
  EXPECT_EQ(resolve_under(root(), "./test-1"), fs::canonical(root() / "test-1"));
}

TEST_F(ResultsPath, EscapesAreRefused) {
  EXPECT_FALSE(resolve_under(root(), ".."));
  EXPECT_FALSE(resolve_under(root(), "test-1/../../outside.csv"));
  EXPECT_FALSE(resolve_under(root(), "test-1/.."));  // `..` is refused even where it stays inside
  EXPECT_FALSE(resolve_under(root(), (base_ / "outside.csv").string()));
  EXPECT_FALSE(resolve_under(root(), "/etc/passwd"));
  EXPECT_FALSE(resolve_under(root(), "test-1/link.csv"));  // a link out
  EXPECT_FALSE(resolve_under(root(), "up/outside.csv"));   // a folder link out
  EXPECT_FALSE(resolve_under(root(), "../results-old/secret.csv"));
  EXPECT_FALSE(resolve_under(root(), std::string_view("test-1\0/x", 9)));
  EXPECT_FALSE(resolve_under(root(), "missing"));
}

TEST(ResultsFileName, OnlyOneNameOfAResultKind) {
  EXPECT_TRUE(servable_file_name("time_history.csv"));
  EXPECT_TRUE(servable_file_name("summary.json"));
  EXPECT_TRUE(servable_file_name("effective-scenario.yaml"));
  EXPECT_FALSE(servable_file_name(""));
  EXPECT_FALSE(servable_file_name(".csv"));
  EXPECT_FALSE(servable_file_name("../x.csv"));
  EXPECT_FALSE(servable_file_name("a/b.csv"));
  EXPECT_FALSE(servable_file_name("record.gp"));
  EXPECT_FALSE(servable_file_name("id_rsa"));
}

}  // namespace
}  // namespace rpsd::monitor
