#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "rpsd/output/csv_table.h"

namespace rpsd::output {
namespace {

TEST(CsvTable, WritesHeaderWithUnitsAndRows) {
  const auto file = std::filesystem::temp_directory_path() / ("rpsd-csv-" + std::to_string(::getpid()) + ".csv");
  CsvTable().column("time_s", {0.0, 0.5}).column("force_n", {1.25, -3e6}).write(file);
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "time_s,force_n\n0,1.25\n0.5,-3000000\n");
  std::filesystem::remove(file);
}

TEST(CsvTable, RejectsColumnsOfDifferentLength) {
  CsvTable table;
  table.column("a", {1.0, 2.0});
  EXPECT_THROW(table.column("b", {1.0}), std::logic_error);
}

}  // namespace
}  // namespace rpsd::output
