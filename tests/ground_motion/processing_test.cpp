// Processing: scaling (exact target PGA), trim and pad lengths, resampling (exact on integer
// upsampling, within the linear-interpolation error bound on a smooth signal), baseline
// correction (an imposed drift is removed exactly), exact integration.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/processing.h"
#include "rpsd/ground_motion/record_error.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

using testing::shared_record;

const GroundMotionRecord& el_centro() {
  static const GroundMotionRecord record = read_peer_at2(shared_record("I-ELC180.AT2"));
  return record;
}

GroundMotionRecord sampled(double dt, std::size_t n, const std::function<double(double)>& f) {
  GroundMotionRecord r;
  r.source = "test signal";
  r.dt_s = dt;
  for (std::size_t i = 0; i < n; ++i) r.acceleration_m_per_s2.push_back(f(static_cast<double>(i) * dt));
  return r;
}

TEST(GroundMotionProcessing, ScaleByFactor) {
  ScaleOptions o;
  o.factor = 0.4;
  const auto scaled = scale(el_centro(), o);
  ASSERT_EQ(scaled.size(), el_centro().size());
  for (std::size_t i = 0; i < scaled.size(); ++i) {
    EXPECT_EQ(scaled.acceleration_m_per_s2[i], 0.4 * el_centro().acceleration_m_per_s2[i]);
  }
  EXPECT_EQ(scaled.processing_steps.back(), "scaled by 0.4");
}

TEST(GroundMotionProcessing, ScaleToTargetPgaIsExact) {
  for (const double target : {0.4 * kStandardGravityMPerS2, 1.0, 3.5, 12.345}) {
    ScaleOptions o;
    o.target_pga_m_per_s2 = target;
    const auto scaled = scale(el_centro(), o);
    const auto pga = peak_ground_acceleration(scaled);
    EXPECT_NEAR(std::abs(pga.value_m_per_s2), target, 2e-16 * target) << target;
    EXPECT_LT(pga.value_m_per_s2, 0.0);  // the sign of El Centro's peak is kept
    EXPECT_EQ(pga.index, 215u);
  }
}

TEST(GroundMotionProcessing, ScaleOptionErrors) {
  ScaleOptions none;
  EXPECT_THROW(scale(el_centro(), none), RecordError);
  ScaleOptions both;
  both.factor = 1.0;
  both.target_pga_m_per_s2 = 1.0;
  EXPECT_THROW(scale(el_centro(), both), RecordError);
  ScaleOptions to_pga;
  to_pga.target_pga_m_per_s2 = 1.0;
  EXPECT_THROW(scale(sampled(0.01, 10, [](double) { return 0.0; }), to_pga), RecordError);
  to_pga.target_pga_m_per_s2 = -1.0;
  EXPECT_THROW(scale(el_centro(), to_pga), RecordError);
}

TEST(GroundMotionProcessing, TrimKeepsTheSamplesInsideTheWindow) {
  TrimOptions o;
  o.start_s = 1.0;
  o.end_s = 11.0;
  const auto trimmed = trim(el_centro(), o);
  ASSERT_EQ(trimmed.size(), 1001u);
  EXPECT_EQ(trimmed.acceleration_m_per_s2.front(), el_centro().acceleration_m_per_s2[100]);
  EXPECT_EQ(trimmed.acceleration_m_per_s2.back(), el_centro().acceleration_m_per_s2[1100]);
  EXPECT_DOUBLE_EQ(trimmed.duration_s(), 10.0);

  o.start_s = 1.005;  // between samples: the first kept sample is at 1.01 s
  o.end_s = 1.995;
  const auto between = trim(el_centro(), o);
  ASSERT_EQ(between.size(), 99u);
  EXPECT_EQ(between.acceleration_m_per_s2.front(), el_centro().acceleration_m_per_s2[101]);

  o.start_s = 0.0;
  o.end_s.reset();
  EXPECT_EQ(trim(el_centro(), o).size(), 4000u);
  o.end_s = 40.0;  // the last sample is at 39.99 s
  EXPECT_THROW(trim(el_centro(), o), RecordError);
  o.start_s = 5.0;
  o.end_s = 4.0;
  EXPECT_THROW(trim(el_centro(), o), RecordError);
  o.start_s = -1.0;
  o.end_s = 4.0;
  EXPECT_THROW(trim(el_centro(), o), RecordError);
}

TEST(GroundMotionProcessing, PadAddsZeros) {
  PadOptions o;
  o.before_s = 1.0;
  o.after_s = 2.5;
  const auto padded = pad(el_centro(), o);
  ASSERT_EQ(padded.size(), 100u + 4000u + 250u);
  for (std::size_t i = 0; i < 100; ++i) EXPECT_EQ(padded.acceleration_m_per_s2[i], 0.0);
  for (std::size_t i = 4100; i < padded.size(); ++i) EXPECT_EQ(padded.acceleration_m_per_s2[i], 0.0);
  EXPECT_EQ(padded.acceleration_m_per_s2[100], el_centro().acceleration_m_per_s2[0]);
  EXPECT_EQ(padded.acceleration_m_per_s2[4099], el_centro().acceleration_m_per_s2[3999]);
  EXPECT_DOUBLE_EQ(padded.duration_s(), el_centro().duration_s() + 3.5);
  o.after_s = -1.0;
  EXPECT_THROW(pad(el_centro(), o), RecordError);
}

TEST(GroundMotionProcessing, IntegerUpsamplingReproducesTheOriginalSamplesExactly) {
  for (const GroundMotionRecord& record : {el_centro(), read_peer_at2(shared_record("HCH090.AT2"))}) {
    for (const int factor : {2, 4, 5, 10}) {
      SCOPED_TRACE(record.source + " x" + std::to_string(factor));
      ResampleOptions o;
      o.dt_s = record.dt_s / factor;
      const auto fine = resample(record, o);
      ASSERT_EQ(fine.size(), (record.size() - 1) * static_cast<std::size_t>(factor) + 1);
      for (std::size_t i = 0; i < record.size(); ++i) {
        ASSERT_EQ(fine.acceleration_m_per_s2[i * static_cast<std::size_t>(factor)], record.acceleration_m_per_s2[i]);
      }
      if (factor == 2) {  // midpoints are the averages
        for (std::size_t i = 0; i + 1 < record.size(); ++i) {
          const double a = record.acceleration_m_per_s2[i];
          const double b = record.acceleration_m_per_s2[i + 1];
          ASSERT_NEAR(fine.acceleration_m_per_s2[2 * i + 1], 0.5 * (a + b), 4e-16 * (std::abs(a) + std::abs(b)));
        }
      }
    }
  }
}

TEST(GroundMotionProcessing, ResamplingASineIsWithinTheLinearInterpolationBound) {
  // 1 Hz sine sampled at 100 Hz, resampled to the integrator step 1/1024 s (ratio 10.24).
  const double w = 2.0 * std::numbers::pi;
  const auto coarse = sampled(0.01, 1001, [&](double t) { return std::sin(w * t); });
  ResampleOptions o;
  o.dt_s = 1.0 / 1024.0;
  const auto fine = resample(coarse, o);
  ASSERT_EQ(fine.size(), 10241u);  // floor(10 s * 1024) + 1
  double worst = 0.0;
  for (std::size_t i = 0; i < fine.size(); ++i) {
    worst = std::max(worst, std::abs(fine.acceleration_m_per_s2[i] - std::sin(w * static_cast<double>(i) * o.dt_s)));
  }
  const double bound = (w * 0.01) * (w * 0.01) / 8.0;  // dt^2 / 8 max|a''| = 4.93e-4
  EXPECT_LE(worst, bound);
  EXPECT_GT(worst, 0.5 * bound);  // and the bound is the right size (measured 4.9e-4)
  RecordProperty("sine_resampling_max_error", std::to_string(worst));
}

TEST(GroundMotionProcessing, DownsamplingNeedsConsent) {
  ResampleOptions o;
  o.dt_s = 0.02;
  EXPECT_THROW(resample(el_centro(), o), RecordError);
  o.allow_downsampling = true;
  const auto coarse = resample(el_centro(), o);
  ASSERT_EQ(coarse.size(), 2000u);
  EXPECT_EQ(coarse.acceleration_m_per_s2[1000], el_centro().acceleration_m_per_s2[2000]);
}

TEST(GroundMotionProcessing, IntegrationIsExactForPiecewiseLinearAcceleration) {
  const double c0 = 0.3;
  const double c1 = -0.05;
  const auto drift = sampled(0.01, 2001, [&](double t) { return c0 + c1 * t; });
  const auto integrals = velocity_and_displacement(drift);
  for (std::size_t i = 0; i < drift.size(); i += 100) {
    const double t = static_cast<double>(i) * 0.01;
    EXPECT_NEAR(integrals.velocity_m_per_s[i], c0 * t + c1 * t * t / 2.0, 1e-12);
    EXPECT_NEAR(integrals.displacement_m[i], c0 * t * t / 2.0 + c1 * t * t * t / 6.0, 1e-11);
  }
}

TEST(GroundMotionProcessing, PolynomialBaselineCorrectionRemovesAnImposedDriftExactly) {
  // El Centro plus an offset and a linear drift in acceleration: displacement drift of
  // c0 t^2 / 2 + c1 t^3 / 6 (about 40 m and -107 m at the end).
  const double c0 = 0.05;
  const double c1 = -0.01;
  GroundMotionRecord drifting = el_centro();
  for (std::size_t i = 0; i < drifting.size(); ++i) {
    drifting.acceleration_m_per_s2[i] += c0 + c1 * static_cast<double>(i) * drifting.dt_s;
  }
  const BaselineCorrectionOptions o;  // cubic displacement fit
  const auto clean = baseline_correct(el_centro(), o);
  const auto corrected = baseline_correct(drifting, o);
  double worst = 0.0;
  for (std::size_t i = 0; i < clean.size(); ++i) {
    worst = std::max(worst, std::abs(corrected.acceleration_m_per_s2[i] - clean.acceleration_m_per_s2[i]));
  }
  EXPECT_LT(worst, 1e-12);  // the drift leaves no trace (round-off only)

  // Drift alone is removed to round-off, and so is its displacement.
  const auto pure = sampled(0.01, 4000, [&](double t) { return c0 + c1 * t; });
  const auto nothing = baseline_correct(pure, o);
  const auto d = velocity_and_displacement(nothing).displacement_m;
  for (std::size_t i = 0; i < pure.size(); ++i) {
    ASSERT_LT(std::abs(nothing.acceleration_m_per_s2[i]), 1e-13);
    ASSERT_LT(std::abs(d[i]), 1e-9);
  }
}

TEST(GroundMotionProcessing, MeanRemoval) {
  GroundMotionRecord offset = el_centro();
  for (double& a : offset.acceleration_m_per_s2) a += 0.2;
  BaselineCorrectionOptions o;
  o.method = BaselineMethod::kRemoveMean;
  const auto a = baseline_correct(offset, o);
  const auto b = baseline_correct(el_centro(), o);
  double sum = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_NEAR(a.acceleration_m_per_s2[i], b.acceleration_m_per_s2[i], 1e-14);
    sum += a.acceleration_m_per_s2[i];
  }
  EXPECT_NEAR(sum / static_cast<double>(a.size()), 0.0, 1e-15);
  o.method = BaselineMethod::kPolynomialDisplacement;
  o.polynomial_order = 7;
  EXPECT_THROW(baseline_correct(el_centro(), o), RecordError);
}

TEST(GroundMotionProcessing, AccelerationAtInterpolatesLinearly) {
  const auto& r = el_centro();
  EXPECT_NEAR(acceleration_at(r, 2.15), r.acceleration_m_per_s2[215], 1e-14);
  EXPECT_NEAR(acceleration_at(r, 2.155), 0.5 * (r.acceleration_m_per_s2[215] + r.acceleration_m_per_s2[216]), 1e-14);
  EXPECT_EQ(acceleration_at(r, -0.1), 0.0);
  EXPECT_EQ(acceleration_at(r, 40.5), 0.0);
  EXPECT_EQ(acceleration_at(r, r.duration_s()), r.acceleration_m_per_s2.back());
}

}  // namespace
}  // namespace rpsd::ground_motion
