// An output folder holds one run's files, and each file is whole or absent.
#include "rpsd/output/results_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

namespace rpsd::output {
namespace {

namespace fs = std::filesystem;

class ResultsFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    root_ = fs::temp_directory_path() / ("rpsd-results-" + std::to_string(getpid()) + "-" +
                                         ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(root_);
    fs::create_directories(root_);
  }
  void TearDown() override { fs::remove_all(root_); }
  static void touch(const fs::path& file, const std::string& text = "x") {
    fs::create_directories(file.parent_path());
    std::ofstream(file) << text;
  }
  static std::string read(const fs::path& file) {
    std::ifstream in(file);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }
  fs::path root_;
};

TEST_F(ResultsFolder, AMissingFolderIsCreatedAndAnEmptyOneIsUsed) {
  prepare_results_folder(root_ / "a" / "b", false);
  EXPECT_TRUE(fs::is_directory(root_ / "a" / "b"));
  prepare_results_folder(root_ / "a" / "b", false);  // empty: fine
}

TEST_F(ResultsFolder, AFolderHoldingAnythingIsRefusedUnlessReplaced) {
  touch(root_ / "run" / "summary.json");
  try {
    prepare_results_folder(root_ / "run", false);
    FAIL() << "a non-empty folder was accepted";
  } catch (const OutputFolderInUse& e) {
    EXPECT_NE(std::string(e.what()).find("--replace"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(fs::exists(root_ / "run" / "summary.json"));  // refused means untouched
}

TEST_F(ResultsFolder, ReplaceClearsEverythingAnEarlierRunLeft) {
  // What a sweep leaves: its summary, its table and plot, a folder per case.
  touch(root_ / "run" / "summary.json");
  touch(root_ / "run" / "sweep.csv");
  touch(root_ / "run" / "sweep.png");
  touch(root_ / "run" / "case_000" / "time_history.csv");
  prepare_results_folder(root_ / "run", true);
  EXPECT_TRUE(fs::is_directory(root_ / "run"));
  EXPECT_TRUE(fs::is_empty(root_ / "run"));
}

TEST_F(ResultsFolder, ReplaceNeverClearsAFolderRpsdDidNotWrite) {
  touch(root_ / "home" / "thesis.tex");
  EXPECT_THROW(prepare_results_folder(root_ / "home", true), OutputFolderInUse);
  EXPECT_TRUE(fs::exists(root_ / "home" / "thesis.tex"));
}

TEST_F(ResultsFolder, AFileIsNotAFolder) {
  touch(root_ / "file");
  EXPECT_THROW(prepare_results_folder(root_ / "file", true), OutputFolderInUse);
  EXPECT_EQ(read(root_ / "file"), "x");
}

TEST_F(ResultsFolder, AFileIsReplacedWholeAndNoTemporaryStays) {
  touch(root_ / "summary.json", "old");
  write_file_whole(root_ / "summary.json", "new\n");
  EXPECT_EQ(read(root_ / "summary.json"), "new\n");
  int files = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(root_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(ResultsFolder, AFileThatCannotBeWrittenIsNamedWithTheReason) {
  try {
    write_file_whole(root_ / "missing-folder" / "summary.json", "{}");
    FAIL() << "no error";
  } catch (const ResultsNotWritten& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("missing-folder/summary.json"), std::string::npos) << text;
    EXPECT_NE(text.find("No such file or directory"), std::string::npos) << text;
  }
}

TEST_F(ResultsFolder, TheReservedSummaryIsValidJsonOfTheReservedSize) {
  reserve_summary(root_ / "summary.json", R"({"result": "running"})");
  EXPECT_EQ(fs::file_size(root_ / "summary.json"), kSummaryReservedBytes);
  EXPECT_EQ(nlohmann::json::parse(read(root_ / "summary.json")).at("result"), "running");
  write_summary(root_ / "summary.json", R"({"result": "completed"})");
  EXPECT_EQ(nlohmann::json::parse(read(root_ / "summary.json")).at("result"), "completed");
}

}  // namespace
}  // namespace rpsd::output
