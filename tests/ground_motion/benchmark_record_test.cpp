// The RTHS benchmark's own El Centro record (data/ground-motions/rths-benchmark-elcentro.txt)
// as rpsd reads it, against the published facts of its source, ElCentroAccelNoScaling.mat:
// 2060 rows at 0.02 s, 41.18 s in all, 5 s of zeros before and after the motion, and its peak
// of 3.1349 m/s^2 at 7.02 s.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>

#include "rpsd/ground_motion/text_readers.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

TEST(BenchmarkRecord, ReadsAsItsSourceFilePublishesIt) {
  TimeAccelerationOptions options;
  options.unit = AccelerationUnit::kMPerS2;
  const GroundMotionRecord r = read_time_acceleration(testing::shared_record("rths-benchmark-elcentro.txt"), options);
  const std::vector<double>& a = r.acceleration_m_per_s2;
  ASSERT_EQ(a.size(), 2060u);
  EXPECT_NEAR(r.dt_s, 0.02, 1e-12);
  EXPECT_NEAR(r.dt_s * static_cast<double>(a.size() - 1), 41.18, 1e-9);
  EXPECT_TRUE(r.description.empty());  // the time column starts at 0
  std::size_t peak = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::abs(a[i]) > std::abs(a[peak])) peak = i;
  EXPECT_EQ(peak, 351u);  // 7.02 s
  EXPECT_NEAR(std::abs(a[peak]), 3.1349, 5e-5);
  EXPECT_EQ(a[peak], -3.134930197);  // the file's own digits
  // Zeros for the first 5 s (rows at 0 .. 4.98 s) and the last 5 s (36.20 .. 41.18 s); the
  // motion starts at 5.00 s and ends at 36.18 s.
  for (std::size_t i = 0; i < 250; ++i) EXPECT_EQ(a[i], 0.0) << i;
  for (std::size_t i = 1810; i < 2060; ++i) EXPECT_EQ(a[i], 0.0) << i;
  EXPECT_NE(a[250], 0.0);
  EXPECT_NE(a[1809], 0.0);
}

}  // namespace
}  // namespace rpsd::ground_motion
