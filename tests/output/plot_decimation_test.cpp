#include "rpsd/output/plot_decimation.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace rpsd::output {
namespace {

const PlottedQuantity kSecond = [](const CsvRow& row) { return row.at(1); };

// 10,000 rows of a slow sine with one-row spikes (+5 and -7) in the middle of two buckets: the
// spikes, the first and the last row are kept, and no more than 2 rows per bucket and
// quantity (plus the ends).
TEST(PlotDecimation, KeepsEveryPeakAndAtMostTwoRowsPerBucket) {
  std::vector<CsvRow> rows;
  for (int i = 0; i < 10000; ++i) rows.push_back({static_cast<double>(i), std::sin(i * 1e-3)});
  rows[4321][1] = 5.0;
  rows[7777][1] = -7.0;
  const auto kept = rows_keeping_peaks(rows, {kSecond}, 100);
  EXPECT_LE(kept.size(), 2u * 100u + 2u);
  EXPECT_TRUE(std::is_sorted(kept.begin(), kept.end()));
  for (std::size_t r : {std::size_t{0}, std::size_t{4321}, std::size_t{7777}, std::size_t{9999}})
    EXPECT_NE(std::find(kept.begin(), kept.end(), r), kept.end()) << r;
  // Every bucket's extremes: the kept rows' maximum per bucket is the bucket's maximum.
  for (int b = 0; b < 100; ++b) {
    double bucket_max = -1e9, kept_max = -1e9;
    for (int i = b * 100; i < (b + 1) * 100; ++i) bucket_max = std::max(bucket_max, rows[i][1]);
    for (std::size_t r : kept)
      if (static_cast<int>(r) / 100 == b) kept_max = std::max(kept_max, rows[r][1]);
    EXPECT_EQ(kept_max, bucket_max) << b;
  }
}

// A derived quantity (a difference of columns) keeps its own peaks, which no single column has.
TEST(PlotDecimation, KeepsThePeaksOfADerivedQuantity) {
  std::vector<CsvRow> rows;
  for (int i = 0; i < 1000; ++i) rows.push_back({1.0, 1.0});
  rows[500][1] = 1.5;
  rows[500][0] = 1.5;  // equal: no difference here
  rows[600][0] = 0.9;  // a difference of 0.1 in a bucket of equal rows
  const auto kept = rows_keeping_peaks(rows, {[](const CsvRow& r) { return r.at(1) - r.at(0); }}, 10);
  EXPECT_NE(std::find(kept.begin(), kept.end(), 600u), kept.end());
}

// A short table is drawn whole (nothing written); a long one keeps its header and its lines
// verbatim.
TEST(PlotDecimation, WritesOnlyLongTablesAndKeepsTheirLines) {
  const auto dir = std::filesystem::temp_directory_path() / "rpsd-plot-decimation";
  std::filesystem::create_directories(dir);
  const auto write = [&](int rows) {
    std::ofstream out(dir / "table.csv");
    out << "step,value\n";
    for (int i = 0; i < rows; ++i) out << i << ',' << (i == rows / 2 ? 9.5 : 0.25) << '\n';
  };
  write(40);
  EXPECT_FALSE(write_rows_keeping_peaks(read_csv_table(dir / "table.csv"), dir / "short.csv", {kSecond}, 10));
  EXPECT_FALSE(std::filesystem::exists(dir / "short.csv"));
  write(1000);
  ASSERT_TRUE(write_rows_keeping_peaks(read_csv_table(dir / "table.csv"), dir / "long.csv", {kSecond}, 10));
  std::ifstream in(dir / "long.csv");
  std::string line, text;
  std::getline(in, line);
  EXPECT_EQ(line, "step,value");
  int lines = 0;
  while (std::getline(in, line)) text += line + '\n', ++lines;
  EXPECT_LE(lines, 22);
  EXPECT_NE(text.find("500,9.5\n"), std::string::npos);
  EXPECT_NE(text.find("999,0.25\n"), std::string::npos);
}

// The zoom: every row within the half window of the largest magnitude (here a negative one),
// and no other.
TEST(PlotDecimation, TheZoomHoldsTheRowsAroundTheLargestMagnitude) {
  const auto dir = std::filesystem::temp_directory_path() / "rpsd-plot-decimation";
  std::filesystem::create_directories(dir);
  {
    std::ofstream out(dir / "zoom-source.csv");
    out << "time_s,value\n";
    for (int i = 0; i < 100; ++i) out << 0.1 * i << ',' << (i == 60 ? -3.0 : (i == 20 ? 2.0 : 0.0)) << '\n';
  }
  ASSERT_TRUE(write_rows_around_peak(
      read_csv_table(dir / "zoom-source.csv"), dir / "zoom.csv", kSecond, [](const CsvRow& r) { return r.at(0); },
      0.25));
  const RecordedCsv zoom = read_csv_table(dir / "zoom.csv");
  ASSERT_EQ(zoom.rows.size(), 5u);  // 5.8, 5.9, 6.0, 6.1, 6.2 s
  EXPECT_NEAR(zoom.rows.front()[0], 5.8, 1e-12);
  EXPECT_EQ(zoom.rows[2][1], -3.0);
  EXPECT_NEAR(zoom.rows.back()[0], 6.2, 1e-12);
}

}  // namespace
}  // namespace rpsd::output
