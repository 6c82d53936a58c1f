// PEER AT2 reader: the four shared records parse to the README's NPTS and DT and to the
// reference sheet's PGA; the NGA-West2 and Peknold (8F10.5) forms; units from line 3;
// malformed files fail with the file name and the line (and column) in the message.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/record_error.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

using testing::read_text;
using testing::shared_record;
using testing::TempDirTest;

struct SharedRecord {
  const char* file;
  RecordFormat format;
  std::size_t npts;
  double dt_s;
  double pga_g;           // the sample of largest magnitude, as printed in the file
  std::size_t pga_index;  // t = index * dt
  const char* event;      // on line 2
  double first_g;         // first and last values, as printed
  double last_g;
};

// NPTS and DT: data/ground-motions/README.md. PGA: reference sheet section 5
// (I-ELC180 -0.312881 g at 2.15 s, NIS000 -0.5093 g, STM090 -0.8832 g); the full digits,
// the index and HCH090's peak were read from the files.
const SharedRecord shared_records[] = {
    {"I-ELC180.AT2", RecordFormat::kPeerAt2NgaWest1, 4000, 0.01, -0.312881, 215, "IMPERIAL VALLEY", -0.640318E-02,
     0.945934E-04},
    {"NIS000.AT2", RecordFormat::kPeerAt2Old, 4096, 0.01, -0.5093376, 725, "KOBE", -0.7551815E-06, 0.4017524E-04},
    {"STM090.AT2", RecordFormat::kPeerAt2Old, 2000, 0.02, -0.8832189, 490, "NORTHRIDGE", 0.2289108E-02, -0.3995931E-03},
    {"HCH090.AT2", RecordFormat::kPeerAt2Old, 7818, 0.005, 0.2465262, 1690, "LOMA PRIETA", -0.3956862E-03,
     0.2829374E-03},
};

TEST(GroundMotionAt2, SharedRecordsParseToTheirNptsDtAndPga) {
  for (const auto& expected : shared_records) {
    SCOPED_TRACE(expected.file);
    const auto record = read_peer_at2(shared_record(expected.file));
    EXPECT_EQ(record.format, expected.format);
    EXPECT_EQ(record.original_unit, AccelerationUnit::kG);
    EXPECT_EQ(record.size(), expected.npts);
    EXPECT_EQ(record.dt_s, expected.dt_s);
    ASSERT_EQ(record.header_lines.size(), 4u);
    EXPECT_NE(record.description.find(expected.event), std::string::npos) << record.description;
    const double g = kStandardGravityMPerS2;
    EXPECT_DOUBLE_EQ(record.acceleration_m_per_s2.front(), expected.first_g * g);
    EXPECT_DOUBLE_EQ(record.acceleration_m_per_s2.back(), expected.last_g * g);
    const auto pga = peak_ground_acceleration(record);
    EXPECT_DOUBLE_EQ(pga.value_m_per_s2, expected.pga_g * g);
    EXPECT_EQ(pga.index, expected.pga_index);
    EXPECT_DOUBLE_EQ(pga.time_s, static_cast<double>(expected.pga_index) * expected.dt_s);
  }
}

TEST(GroundMotionAt2, ElCentroPeakIsMinus0312881gAt215s) {
  const auto record = read_peer_at2(shared_record("I-ELC180.AT2"));
  const auto pga = peak_ground_acceleration(record);
  EXPECT_NEAR(pga.value_m_per_s2 / kStandardGravityMPerS2, -0.312881, 1e-15);
  EXPECT_NEAR(pga.time_s, 2.15, 1e-12);
}

TEST(GroundMotionAt2, NgaWest2HeaderWithTrailingComma) {
  const std::string text =
      "PEER NGA STRONG MOTION DATABASE RECORD\r\n"
      "Chi-Chi, Taiwan, 9/20/1999, TCU065, E\r\n"
      "ACCELERATION TIME SERIES IN UNITS OF G\r\n"
      "NPTS=    7, DT=   .0050 SEC,\r\n"
      "  1.0000000E-03  2.0000000E-03 -3.0000000E-03  4.0000000E-03  5.0000000E-03\r\n"
      " -6.0000000E-03  7.0000000E-03\r\n";
  const auto record = parse_peer_at2(text, "west2.AT2");
  EXPECT_EQ(record.format, RecordFormat::kPeerAt2NgaWest2);
  EXPECT_EQ(record.size(), 7u);
  EXPECT_EQ(record.dt_s, 0.005);
  EXPECT_DOUBLE_EQ(record.acceleration_m_per_s2[6], 7e-3 * kStandardGravityMPerS2);
  EXPECT_EQ(record.description, "Chi-Chi, Taiwan, 9/20/1999, TCU065, E");
}

TEST(GroundMotionAt2, PeknoldEightF10Form) {
  // The header of OpenSees EXAMPLES/ExampleScripts/elCentro.AT2 (units "(g)" on line 3),
  // its first 11 values, NPTS reduced to match.
  const std::string text =
      "Data for El Centro 1940 North South Component (Peknold Version)\n"
      "1559 points at equal spacing of 0.02 sec Points are listed in the format of 8F10.5\n"
      "The units are (g)\n"
      "NPTS=    11, DT= .02000 SEC\n"
      "   0.00630   0.00364   0.00099   0.00428   0.00758   0.01087   0.00682   0.00277\n"
      "  -0.00128   0.00368   0.00864\n";
  const auto record = parse_peer_at2(text, "elCentro.AT2");
  EXPECT_EQ(record.format, RecordFormat::kPeerAt2Old);
  EXPECT_EQ(record.original_unit, AccelerationUnit::kG);
  ASSERT_EQ(record.size(), 11u);
  EXPECT_EQ(record.dt_s, 0.02);
  EXPECT_DOUBLE_EQ(record.acceleration_m_per_s2[8], -0.00128 * kStandardGravityMPerS2);
}

std::string header_with_units(const std::string& line3) {
  return "PEER STRONG MOTION DATABASE RECORD\nEVENT, STATION, 000\n" + line3 +
         "\nNPTS=     3, DT= .01000 SEC\n  100.0  -50.0  25.0\n";
}

TEST(GroundMotionAt2, UnitsFromLine3) {
  const auto cm = parse_peer_at2(header_with_units("ACCELERATION TIME HISTORY IN UNITS OF CM/S/S"), "cm.AT2");
  EXPECT_EQ(cm.original_unit, AccelerationUnit::kCmPerS2);
  EXPECT_DOUBLE_EQ(cm.acceleration_m_per_s2[0], 1.0);
  const auto gal = parse_peer_at2(header_with_units("Acceleration in units of gal"), "gal.AT2");
  EXPECT_EQ(gal.original_unit, AccelerationUnit::kCmPerS2);
  const auto m = parse_peer_at2(header_with_units("ACCELERATION, UNITS: M/S^2"), "m.AT2");
  EXPECT_EQ(m.original_unit, AccelerationUnit::kMPerS2);
  EXPECT_DOUBLE_EQ(m.acceleration_m_per_s2[1], -50.0);
}

TEST(GroundMotionAt2, Line3WithoutUnitsNeedsAnExplicitUnit) {
  const std::string text = header_with_units("ACCELERATION TIME HISTORY");
  try {
    parse_peer_at2(text, "nounits.AT2");
    FAIL() << "no error";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find("nounits.AT2:3: expected the units on line 3"), std::string::npos) << e.what();
  }
  At2ReadOptions options;
  options.unit_if_unstated = AccelerationUnit::kCmPerS2;
  EXPECT_DOUBLE_EQ(parse_peer_at2(text, "nounits.AT2", options).acceleration_m_per_s2[0], 1.0);
  // A unit stated on line 3 wins over the fallback.
  EXPECT_DOUBLE_EQ(
      parse_peer_at2(header_with_units("ACCELERATION IN UNITS OF G"), "g.AT2", options).acceleration_m_per_s2[2],
      25.0 * kStandardGravityMPerS2);
}

TEST(GroundMotionAt2, VelocityFileIsRejected) {
  EXPECT_THROW(parse_peer_at2(header_with_units("VELOCITY TIME HISTORY IN UNITS OF CM/S"), "v.VT2"), RecordError);
}

// Malformed copies of I-ELC180.AT2 written to a temporary directory.
class GroundMotionAt2Malformed : public TempDirTest {
 protected:
  std::vector<std::string> lines() const {
    std::vector<std::string> out;
    std::string text = read_text(shared_record("I-ELC180.AT2"));
    std::size_t start = 0;
    while (start < text.size()) {
      const auto end = text.find('\n', start);
      out.push_back(text.substr(start, end - start));
      if (end == std::string::npos) break;
      start = end + 1;
    }
    return out;
  }
  static std::string join(const std::vector<std::string>& lines) {
    std::string text;
    for (const auto& line : lines) text += line + "\n";
    return text;
  }
  // The message of the RecordError that reading `text` as NAME throws.
  std::string error_for(const std::string& name, const std::string& text) {
    path_ = write(name, text);
    try {
      read_peer_at2(path_);
    } catch (const RecordError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error for " << name;
    return {};
  }
  // "…/NAME:LINE:" must open the message.
  void expect_located(const std::string& message, int line) const {
    const std::string prefix = path_.string() + ":" + std::to_string(line) + ":";
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << "expected prefix " << prefix << " in: " << message;
  }
  std::filesystem::path path_;
};

TEST_F(GroundMotionAt2Malformed, TruncatedFileNamesItsLastLineAndTheCount) {
  auto l = lines();
  ASSERT_EQ(l.size(), 804u);  // 4 header lines + 800 lines of 5 values
  l.resize(801);              // 797 data lines: 3985 values
  const auto message = error_for("truncated.AT2", join(l));
  expect_located(message, 801);
  EXPECT_NE(message.find("expected NPTS=4000 values (line 4), got only 3985"), std::string::npos) << message;
}

TEST_F(GroundMotionAt2Malformed, BadNumberNamesLineColumnAndToken) {
  auto l = lines();
  l[9] = "  -0.640318E-02  -0.602871E-02   0.53O416E-03   0.774326E-02   0.689038E-02";
  const auto message = error_for("badnumber.AT2", join(l));
  expect_located(message, 10);
  EXPECT_NE(message.find(":10:34: expected an acceleration value (value 28 of NPTS=4000), got "
                         "\"0.53O416E-03\""),
            std::string::npos)
      << message;
}

TEST_F(GroundMotionAt2Malformed, NonFiniteValueIsABadNumber) {
  auto l = lines();
  l[4] = "  nan  -0.602871E-02   0.530416E-03   0.774326E-02   0.689038E-02";
  const auto message = error_for("nan.AT2", join(l));
  expect_located(message, 5);
  EXPECT_NE(message.find("got \"nan\""), std::string::npos) << message;
}

TEST_F(GroundMotionAt2Malformed, NptsLargerThanTheDataIsTruncation) {
  auto l = lines();
  l[3] = "4001    0.0100    NPTS, DT";
  const auto message = error_for("npts-large.AT2", join(l));
  expect_located(message, 804);
  EXPECT_NE(message.find("expected NPTS=4001 values (line 4), got only 4000"), std::string::npos) << message;
}

TEST_F(GroundMotionAt2Malformed, NptsSmallerThanTheDataNamesTheExtraValue) {
  auto l = lines();
  l[3] = "3999    0.0100    NPTS, DT";
  const auto message = error_for("npts-small.AT2", join(l));
  expect_located(message, 804);
  EXPECT_NE(message.find("expected the end of the data after NPTS=3999 values (line 4), got one "
                         "more value \"0.945934E-04\""),
            std::string::npos)
      << message;
}

TEST_F(GroundMotionAt2Malformed, EmptyFile) {
  const auto message = error_for("empty.AT2", "");
  expect_located(message, 1);
  EXPECT_NE(message.find("empty file"), std::string::npos) << message;
  expect_located(error_for("blank.AT2", "\n  \n\t\n\n\n\n"), 1);
}

TEST_F(GroundMotionAt2Malformed, HeaderMissing) {
  auto l = lines();
  l.erase(l.begin(), l.begin() + 4);
  const auto message = error_for("noheader.AT2", join(l));
  expect_located(message, 1);
  EXPECT_NE(message.find("the header is missing"), std::string::npos) << message;
}

TEST_F(GroundMotionAt2Malformed, FileEndsInTheHeader) {
  auto l = lines();
  l.resize(3);
  const auto message = error_for("short.AT2", join(l));
  expect_located(message, 3);
  EXPECT_NE(message.find("ends after 3 header lines"), std::string::npos) << message;
}

TEST_F(GroundMotionAt2Malformed, BadNptsDtLine) {
  auto l = lines();
  l[3] = "NPTS=  abc, DT= .01000 SEC";
  auto message = error_for("badline4.AT2", join(l));
  expect_located(message, 4);
  EXPECT_NE(message.find("NPTS"), std::string::npos) << message;

  l[3] = "NPTS=  4000, DT= -.01000 SEC";
  message = error_for("negativedt.AT2", join(l));
  expect_located(message, 4);
  EXPECT_NE(message.find("expected DT as a positive number of seconds, got \"-.01000\""), std::string::npos) << message;

  l[3] = "0    0.0100    NPTS, DT";
  message = error_for("zeronpts.AT2", join(l));
  expect_located(message, 4);
  EXPECT_NE(message.find("expected NPTS as a positive whole number, got \"0\""), std::string::npos) << message;

  l[3] = "4000    0.0100    NPTS, DT  extra";
  expect_located(error_for("extra.AT2", join(l)), 4);
}

TEST_F(GroundMotionAt2Malformed, MissingFileNamesThePath) {
  path_ = dir_ / "absent.AT2";
  try {
    read_peer_at2(path_);
    FAIL() << "no error";
  } catch (const RecordError& e) {
    EXPECT_NE(std::string(e.what()).find(path_.string() + ": does not exist"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::ground_motion
