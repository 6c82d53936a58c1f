// Test helpers: the repository's ground-motion records (data/ground-motions) and a
// per-test temporary directory for malformed files.
#pragma once

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rpsd::ground_motion::testing {

inline std::filesystem::path source_dir() {
  if (const char* env = std::getenv("RPSD_SOURCE_DIR"); env != nullptr && *env != '\0') return env;
  return RPSD_TEST_SOURCE_DIR;
}

// $RPSD_SOURCE_DIR/data/ground-motions/NAME
inline std::filesystem::path shared_record(const std::string& name) {
  return source_dir() / "data" / "ground-motions" / name;
}

inline std::string read_text(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A fresh directory per test, removed afterwards.
class TempDirTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("rpsd-gm-" + std::to_string(::getpid()) + "-" + info->test_suite_name() + "-" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto path = dir_ / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }

  std::filesystem::path dir_;
};

}  // namespace rpsd::ground_motion::testing
