// Plain-text and two-column readers: value order, columns, comments, unit conversion,
// dt inference and the errors (file:line[:column]).
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>
#include <string>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/ground_motion/text_readers.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

using testing::shared_record;
using testing::TempDirTest;

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const RecordError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no RecordError";
  return {};
}

PlainTextOptions plain(double dt, AccelerationUnit unit) {
  PlainTextOptions o;
  o.dt_s = dt;
  o.unit = unit;
  return o;
}

TEST(GroundMotionPlainText, OneValuePerLineInG) {
  const auto r = parse_plain_text("0.1\n-0.2\n0.3\n", "one.txt", plain(0.02, AccelerationUnit::kG));
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r.format, RecordFormat::kPlainText);
  EXPECT_EQ(r.dt_s, 0.02);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[1], -0.2 * 9.80665);
  EXPECT_DOUBLE_EQ(r.duration_s(), 0.04);
}

TEST(GroundMotionPlainText, ManyValuesPerLineAreReadInOrder) {
  // 6 per line in E11.4 and cm/s^2, like OpenFresco's elc.dat; a short last line.
  const std::string text =
      " 1.0000E+00 2.0000E+00 3.0000E+00 4.0000E+00 5.0000E+00 6.0000E+00\n"
      " 7.0000E+00-8.0000E+00\n";
  // "7.0000E+00-8.0000E+00": Fortran fields that touch are not split: an error, on line 2.
  const auto message = message_of([&] { parse_plain_text(text, "elc.dat", plain(0.02, AccelerationUnit::kCmPerS2)); });
  EXPECT_EQ(message.rfind("elc.dat:2:2: expected an acceleration value", 0), 0u) << message;

  const auto r =
      parse_plain_text(" 1.0000E+00 2.0000E+00 3.0000E+00 4.0000E+00 5.0000E+00 6.0000E+00\n 7.0000E+00 -8.0D+00\n",
                       "elc.dat", plain(0.02, AccelerationUnit::kCmPerS2));
  ASSERT_EQ(r.size(), 8u);
  for (int i = 0; i < 7; ++i) EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[i], (i + 1) * 0.01);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[7], -0.08);
}

TEST(GroundMotionPlainText, UnitConversion) {
  EXPECT_DOUBLE_EQ(to_m_per_s2(AccelerationUnit::kG), 9.80665);
  EXPECT_DOUBLE_EQ(to_m_per_s2(AccelerationUnit::kMPerS2), 1.0);
  EXPECT_DOUBLE_EQ(to_m_per_s2(AccelerationUnit::kCmPerS2), 0.01);
  const std::string text = "981.0\n";
  EXPECT_DOUBLE_EQ(parse_plain_text(text, "a", plain(0.01, AccelerationUnit::kCmPerS2)).acceleration_m_per_s2[0], 9.81);
  EXPECT_DOUBLE_EQ(parse_plain_text(text, "a", plain(0.01, AccelerationUnit::kMPerS2)).acceleration_m_per_s2[0], 981.0);
  EXPECT_DOUBLE_EQ(parse_plain_text(text, "a", plain(0.01, AccelerationUnit::kG)).acceleration_m_per_s2[0],
                   981.0 * 9.80665);
}

TEST(GroundMotionPlainText, CommentsBlankLinesHeaderAndColumn) {
  const std::string text =
      "station XYZ, three components\n"
      "# t   ns    ew    ud\n"
      "0.00, 0.1, 0.2, 0.3\n"
      "\n"
      "0.01; 0.4; 0.5; 0.6\r\n"
      "% trailing comment\n"
      "0.02  0.7  0.8  0.9\n";
  PlainTextOptions o = plain(0.01, AccelerationUnit::kMPerS2);
  o.skip_lines = 1;
  o.column = 2;
  o.expected_points = 3;
  const auto r = parse_plain_text(text, "table.txt", o);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[0], 0.2);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[1], 0.5);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[2], 0.8);

  o.expected_points = 4;
  EXPECT_EQ(
      message_of([&] { parse_plain_text(text, "table.txt", o); }).rfind("table.txt:7: expected 4 values, got 3", 0),
      0u);
  o.expected_points.reset();
  o.skip_lines = 0;
  EXPECT_EQ(message_of([&] {
              parse_plain_text(text, "table.txt", o);
            }).rfind("table.txt:1:1: expected a number (set skip_lines", 0),
            0u);
  o.skip_lines = 1;
  EXPECT_EQ(message_of([&] {
              parse_plain_text(text + "0.03 1.0 1.1\n", "table.txt", o);
            }).rfind("table.txt:8: expected 4 columns like line 3, got 3", 0),
            0u);
}

TEST(GroundMotionPlainText, OptionErrors) {
  EXPECT_NE(message_of([] {
              parse_plain_text("1\n", "x.txt", plain(0.0, AccelerationUnit::kG));
            }).find("x.txt: expected dt_s"),
            std::string::npos);
  PlainTextOptions no_unit;
  no_unit.dt_s = 0.01;
  EXPECT_NE(message_of([&] {
              parse_plain_text("1\n", "x.txt", no_unit);
            }).find("x.txt: the acceleration units must be declared"),
            std::string::npos);
  EXPECT_EQ(message_of([] {
              parse_plain_text("# nothing\n\n", "x.txt", plain(0.01, AccelerationUnit::kG));
            }).rfind("x.txt:2: expected acceleration values, got none", 0),
            0u);
  // 1e308 is a double, 1e308 g is not.
  EXPECT_EQ(message_of([] {
              parse_plain_text("0\n 1e308\n", "x.txt", plain(0.01, AccelerationUnit::kG));
            }).rfind("x.txt:2:2: expected an acceleration value of finite size in m/s^2, got \"1e308\"", 0),
            0u);
  EXPECT_EQ(message_of([] {
              parse_plain_text("", "x.txt", plain(0.01, AccelerationUnit::kG));
            }).rfind("x.txt:1: expected acceleration values, got none", 0),
            0u);
}

TimeAccelerationOptions two_column(AccelerationUnit unit) {
  TimeAccelerationOptions o;
  o.unit = unit;
  return o;
}

TEST(GroundMotionTimeAcceleration, InfersDtAndConvertsUnits) {
  const std::string text = "time_s,acc_g\n0.000,0.0\n0.005,0.1\n0.010,-0.2\n0.015,0.05\n";
  auto o = two_column(AccelerationUnit::kG);
  o.skip_lines = 1;
  const auto r = parse_time_acceleration(text, "tA.csv", o);
  EXPECT_EQ(r.format, RecordFormat::kTimeAcceleration);
  ASSERT_EQ(r.size(), 4u);
  EXPECT_DOUBLE_EQ(r.dt_s, 0.005);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[2], -0.2 * 9.80665);
  EXPECT_TRUE(r.description.empty());
}

TEST(GroundMotionTimeAcceleration, NonZeroStartMovesTheOrigin) {
  const auto r = parse_time_acceleration("10.0 1\n10.5 2\n11.0 3\n", "late.txt", two_column(AccelerationUnit::kMPerS2));
  EXPECT_DOUBLE_EQ(r.dt_s, 0.5);
  EXPECT_EQ(r.description, "time column starts at 10 s");
}

TEST(GroundMotionTimeAcceleration, ColumnsCanBeChosen) {
  auto o = two_column(AccelerationUnit::kCmPerS2);
  o.time_column = 2;
  o.acceleration_column = 0;
  const auto r = parse_time_acceleration("5 9 0.0\n6 9 0.1\n", "c.txt", o);
  EXPECT_DOUBLE_EQ(r.dt_s, 0.1);
  EXPECT_DOUBLE_EQ(r.acceleration_m_per_s2[1], 0.06);
}

TEST(GroundMotionTimeAcceleration, Errors) {
  const auto o = two_column(AccelerationUnit::kG);
  // Off the uniform grid by 0.3 dt on line 3 (dt inferred from first and last: 0.01).
  auto message =
      message_of([&] { parse_time_acceleration("0.00 1\n0.01 1\n0.023 1\n0.03 1\n0.04 1\n", "uneven.txt", o); });
  EXPECT_EQ(message.rfind("uneven.txt:3: expected the uniform time 0.02 s (dt = 0.01 s", 0), 0u) << message;
  // Within the tolerance: printed times rounded to 6 decimals, dt = 1/1024 s; the
  // inferred dt is then off by at most the rounding (5e-7 s) over 49 steps, 1e-8 s.
  std::string rounded;
  for (int i = 0; i < 50; ++i) {
    char line[64];
    std::snprintf(line, sizeof line, "%.6f %d\n", i / 1024.0, i);
    rounded += line;
  }
  EXPECT_NEAR(parse_time_acceleration(rounded, "rounded.txt", o).dt_s, 1.0 / 1024.0, 1.1e-8);

  message = message_of([&] { parse_time_acceleration("0 1\n0.01 1\n0.01 2\n", "dup.txt", o); });
  EXPECT_EQ(message.rfind("dup.txt:3:1: expected a time greater than 0.01 s (line 2)", 0), 0u) << message;
  message = message_of([&] { parse_time_acceleration("0 1\n", "one.txt", o); });
  EXPECT_EQ(message.rfind("one.txt:1: expected at least two time/acceleration rows", 0), 0u) << message;
  message = message_of([&] { parse_time_acceleration("0 1\n0.01\n", "narrow.txt", o); });
  EXPECT_EQ(message.rfind("narrow.txt:2: expected at least 2 columns", 0), 0u) << message;
  message = message_of([&] { parse_time_acceleration("t a\n0 1\n", "hdr.txt", o); });
  EXPECT_EQ(message.rfind("hdr.txt:1:1: expected a time in s (set skip_lines", 0), 0u) << message;
  message = message_of([&] { parse_time_acceleration("0 1\n0.01 1e999\n", "big.txt", o); });
  EXPECT_EQ(message.rfind("big.txt:2:6: expected an acceleration value, got \"1e999\"", 0), 0u) << message;
}

class GroundMotionTextFiles : public TempDirTest {};

// The El Centro AT2 written as a two-column CSV (time with 3 decimals, value with 6
// significant digits, as in the AT2) and as a 1-per-line file reads back to the same record.
TEST_F(GroundMotionTextFiles, ElCentroRoundTripsThroughBothTextFormats) {
  const auto at2 = read_peer_at2(shared_record("I-ELC180.AT2"));
  std::string csv = "t (s),a (g)\n";
  std::string one_per_line;
  for (std::size_t i = 0; i < at2.size(); ++i) {
    char line[80];
    const double g = at2.acceleration_m_per_s2[i] / kStandardGravityMPerS2;
    std::snprintf(line, sizeof line, "%.3f,%.6E\n", static_cast<double>(i) * 0.01, g);
    csv += line;
    std::snprintf(line, sizeof line, "%.6E\n", g);
    one_per_line += line;
  }
  auto o = two_column(AccelerationUnit::kG);
  o.skip_lines = 1;
  const auto from_csv = read_time_acceleration(write("elc.csv", csv), o);
  const auto from_txt = read_plain_text(write("elc.txt", one_per_line), plain(0.01, AccelerationUnit::kG));
  ASSERT_EQ(from_csv.size(), 4000u);
  ASSERT_EQ(from_txt.size(), 4000u);
  EXPECT_NEAR(from_csv.dt_s, 0.01, 1e-15);
  for (std::size_t i = 0; i < at2.size(); ++i) {
    EXPECT_DOUBLE_EQ(from_csv.acceleration_m_per_s2[i], at2.acceleration_m_per_s2[i]);
    EXPECT_DOUBLE_EQ(from_txt.acceleration_m_per_s2[i], at2.acceleration_m_per_s2[i]);
  }
  EXPECT_EQ(from_csv.source, (dir_ / "elc.csv").string());
}

}  // namespace
}  // namespace rpsd::ground_motion
