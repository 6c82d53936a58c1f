// The benchmark criteria J1-J9, the final tracking indicator and the energy error against
// closed forms: CriteriaAccumulator and channel_criteria() fed synthetic step records built
// from sines with a known delay, amplitude error or offset.
//
// The signals: a sine of period P = 400 samples (5 Hz at 2000 Hz), N = 4000 samples (ten
// periods). The signed tracking delay searches -400..400 samples and sums over the last
// W = N - 800 = 3200 samples, eight whole periods, so with x_t = A sin(theta k),
// x_m = A sin(theta (k - d)) its product sum is exactly S(j) = (W A^2 / 2) cos(theta (j - d)):
// the second harmonic sums to zero. J1, the benchmark's, searches 0..49 whole samples over
// W = N - 49 products, not whole periods, which moves S(j) by a ripple far below a sample's step.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <vector>

#include "rpsd/compensation/tracking_indicator.h"
#include "rpsd/coordinator/run_criteria.h"

namespace rpsd::coordinator {
namespace {

constexpr double kRateHz = 2000.0;
constexpr int kPeriod = 400;    // samples, 5 Hz
constexpr int kSamples = 4000;  // ten whole periods
constexpr double kTheta = 2.0 * std::numbers::pi / kPeriod;
constexpr double kMsPerSample = 1e3 / kRateHz;

// Relative error of a percentage against its closed form.
double relative(double value, double expected) { return std::abs(value - expected) / std::abs(expected); }

// The records of a test: channel c's target and measured at step k.
std::vector<StepRecord> channel_records(int channels, int samples, const std::function<double(int c, int k)>& target,
                                        const std::function<double(int c, int k)>& measured) {
  std::vector<StepRecord> records(static_cast<std::size_t>(samples));
  for (int k = 0; k < samples; ++k) {
    StepRecord& r = records[static_cast<std::size_t>(k)];
    r.step = k;
    r.time_s = k / kRateHz;
    r.channels = static_cast<std::uint8_t>(channels);
    for (int c = 0; c < channels; ++c) {
      r.target_m[c] = target(c, k);
      r.measured_m[c] = measured(c, k);
    }
  }
  return records;
}

void expect_same(double a, double b, const char* what) {
  if (std::isnan(a) || std::isnan(b)) {
    EXPECT_TRUE(std::isnan(a) && std::isnan(b)) << what;
  } else {
    EXPECT_EQ(a, b) << what;
  }
}

// Channel c's criteria from the accumulator fed step by step; criteria() and
// channel_criteria() of the kept records must give the same numbers bit for bit.
ChannelCriteria evaluate_channel(const std::vector<StepRecord>& records, int channels, int c) {
  CriteriaAccumulator sums(channels, 0, kRateHz);
  for (const auto& r : records) sums.add_test(r);
  EXPECT_EQ(sums.test_steps(), static_cast<std::int64_t>(records.size()));
  const ChannelCriteria a = sums.channel(c);
  const Criteria whole = sums.criteria();
  const ChannelCriteria kept = channel_criteria(records, c, kRateHz);
  EXPECT_EQ(whole.channels.size(), static_cast<std::size_t>(channels));
  for (const ChannelCriteria& b : {whole.channels[static_cast<std::size_t>(c)], kept}) {
    expect_same(a.j1_tracking_delay_ms, b.j1_tracking_delay_ms, "J1");
    expect_same(a.tracking_delay_ms, b.tracking_delay_ms, "tracking delay");
    EXPECT_EQ(a.tracking_delay_at_window_edge, b.tracking_delay_at_window_edge);
    expect_same(a.j2_rms_tracking_error_percent, b.j2_rms_tracking_error_percent, "J2");
    expect_same(a.j3_peak_tracking_error_percent, b.j3_peak_tracking_error_percent, "J3");
    expect_same(a.final_tracking_indicator_m2, b.final_tracking_indicator_m2, "TI");
  }
  return a;
}

// The benchmark's J1 written out: the first j in 0..49 maximising
// sum_{k=49}^{N-1} x_m(k) x_t(k - j), in samples (channel 0).
int j1_by_definition(const std::vector<StepRecord>& r) {
  int best_lag = 0;
  double best = 0.0;
  for (int j = 0; j <= 49; ++j) {
    double sum = 0.0;
    for (std::size_t k = 49; k < r.size(); ++k)
      sum += r[k].measured_m[0] * r[k - static_cast<std::size_t>(j)].target_m[0];
    if (j == 0 || sum > best) {
      best = sum;
      best_lag = j;
    }
  }
  return best_lag;
}

// A pure delay of d samples on a sine: e = x_m - x_t = -2 A sin(theta d / 2) cos(theta (k - d / 2)),
// so over whole periods RMS(e) / RMS(x_t) = 2 |sin(theta d / 2)|.
double delay_error_percent(double d) { return 200.0 * std::abs(std::sin(kTheta * d / 2.0)); }

TEST(TestCriteria, J1IsAWholeSampleDelayOfASineInMillisecondsAndJ2J3FollowTheDelayedSine) {
  // Channel 0 lags 20 samples (10 ms), channel 1 (another amplitude) 7 samples (3.5 ms).
  const double amplitude[] = {0.01, 0.004};
  const int delay[] = {20, 7};
  const auto records = channel_records(
      2, kSamples, [&](int c, int k) { return amplitude[c] * std::sin(kTheta * k); },
      [&](int c, int k) { return amplitude[c] * std::sin(kTheta * (k - delay[c])); });
  for (int c = 0; c < 2; ++c) {
    SCOPED_TRACE(c);
    const ChannelCriteria cc = evaluate_channel(records, 2, c);
    // J1 is a whole number of samples: exactly the delay.
    EXPECT_EQ(cc.j1_tracking_delay_ms, delay[c] * kMsPerSample);
    // 1e-9 ms: S(j) is exact up to rounding of 3200-term sums, which the parabola's
    // 1 / curvature ~ 1 / theta^2 amplifies to ~1e-12 ms (seen); far below a sample (0.5 ms).
    EXPECT_NEAR(cc.tracking_delay_ms, delay[c] * kMsPerSample, 1e-9);
    EXPECT_FALSE(cc.tracking_delay_at_window_edge);
    // 1e-9 relative: the closed forms are exact over whole periods, only rounding remains.
    EXPECT_LT(relative(cc.j2_rms_tracking_error_percent, delay_error_percent(delay[c])), 1e-9);
    // The peak of |cos(theta (k - d / 2))| falls on a sample for even d (k = d / 2); for odd d
    // the nearest samples are half a sample off, so the sampled peak is cos(theta / 2) of it.
    const double sampled_peak = delay[c] % 2 == 0 ? 1.0 : std::cos(kTheta / 2.0);
    EXPECT_LT(relative(cc.j3_peak_tracking_error_percent, delay_error_percent(delay[c]) * sampled_peak), 1e-9);
  }
}

TEST(TestCriteria, TheTrackingDelayRefinesAFractionalDelayByTheParabolaThroughThePeakAndItsNeighbours) {
  // With S(j) proportional to cos(theta (j - d)) and n the nearest whole lag, the parabola's
  // vertex is n + tan(theta (d - n)) / (2 tan(theta / 2)), within 1e-5 samples of d here.
  const double delay[] = {20.3, 20.7, 133.5};
  const auto records = channel_records(
      3, kSamples, [&](int, int k) { return 0.01 * std::sin(kTheta * k); },
      [&](int c, int k) { return 0.01 * std::sin(kTheta * (k - delay[c])); });
  for (int c = 0; c < 3; ++c) {
    SCOPED_TRACE(c);
    const double n = std::round(delay[c]);
    const double vertex = n + std::tan(kTheta * (delay[c] - n)) / (2.0 * std::tan(kTheta / 2.0));
    const ChannelCriteria cc = evaluate_channel(records, 3, c);
    // 1e-9 ms: rounding only, as for a whole-sample delay (above); tight enough to tell the
    // vertex from the true delay, which differ by up to 2e-6 ms here.
    EXPECT_NEAR(cc.tracking_delay_ms, vertex * kMsPerSample, 1e-9);
    // 1e-5 samples: the vertex's bias, |delta| theta^2 / 12 ~ 1e-5 samples at most here.
    EXPECT_NEAR(cc.tracking_delay_ms, delay[c] * kMsPerSample, 1e-5 * kMsPerSample);
    // J1 (the benchmark's) is the nearest whole sample, and 49 where the delay lies beyond.
    EXPECT_EQ(cc.j1_tracking_delay_ms, std::min(n, 49.0) * kMsPerSample);
    // 1e-9 relative: RMS over whole periods is exact for any delay.
    EXPECT_LT(relative(cc.j2_rms_tracking_error_percent, delay_error_percent(delay[c])), 1e-9);
  }
}

TEST(TestCriteria, TheTrackingDelayIsNanUntilTheRecordIsLongerThanTwiceTheLagSearch) {
  // The search runs over +-200 ms = +-400 samples; the delay needs more than 802 samples (the
  // 800 the window spans, and three products for a peak and its neighbours).
  const auto delayed = [](int samples) {
    return channel_records(
        1, samples, [](int, int k) { return 0.01 * std::sin(kTheta * k); },
        [](int, int k) { return 0.01 * std::sin(kTheta * (k - 20)); });
  };
  const auto short_records = delayed(802);
  EXPECT_TRUE(std::isnan(evaluate_channel(short_records, 1, 0).tracking_delay_ms));
  EXPECT_TRUE(std::isfinite(evaluate_channel(delayed(803), 1, 0).tracking_delay_ms));
  // J1 (0..49 samples) is found long before, as its definition gives it.
  EXPECT_EQ(evaluate_channel(short_records, 1, 0).j1_tracking_delay_ms, j1_by_definition(short_records) * kMsPerSample);
  // Half a sample (0.25 ms) over 401 products: not whole half-periods, and the second
  // harmonic left over moves the refined peak by a fraction of a sample.
  EXPECT_NEAR(evaluate_channel(delayed(1201), 1, 0).tracking_delay_ms, 20 * kMsPerSample, 0.5 * kMsPerSample);
}

TEST(TestCriteria, AMeasurementAheadOfItsTargetHasANegativeTrackingDelayAndAJ1OfZero) {
  // x_m leads by 7 samples = 3.5 ms: the signed delay is -3.5 ms inside its window; J1,
  // which searches 0..49 only, sits at its edge, 0 (the over-compensated two-storey test).
  const auto records = channel_records(
      1, kSamples, [](int, int k) { return 0.01 * std::sin(kTheta * k); },
      [](int, int k) { return 0.01 * std::sin(kTheta * (k + 7)); });
  const ChannelCriteria cc = evaluate_channel(records, 1, 0);
  EXPECT_NEAR(cc.tracking_delay_ms, -3.5, 1e-9);  // rounding only, as above
  EXPECT_FALSE(cc.tracking_delay_at_window_edge);
  EXPECT_EQ(cc.j1_tracking_delay_ms, 0.0);
}

TEST(TestCriteria, ATrackingDelayBeyondTheWindowIsFlaggedAtItsEdge) {
  // A slow sine (period 4000 samples) 500 samples late, 250 ms, beyond the 200 ms window, and
  // its mirror 500 samples early: S(j) = cos(theta (j - d)) is largest at the window's near edge.
  constexpr int kSlowPeriod = 4000;
  const double theta = 2.0 * std::numbers::pi / kSlowPeriod;
  for (int shift : {500, -500}) {
    SCOPED_TRACE(shift);
    const auto records = channel_records(
        1, 3 * kSlowPeriod + 800, [&](int, int k) { return 0.01 * std::sin(theta * k); },
        [&](int, int k) { return 0.01 * std::sin(theta * (k - shift)); });
    const ChannelCriteria cc = evaluate_channel(records, 1, 0);
    EXPECT_TRUE(cc.tracking_delay_at_window_edge);
    EXPECT_EQ(cc.tracking_delay_ms, (shift > 0 ? 400 : -400) * kMsPerSample);
  }
  // Inside the window, no flag (the sine of the other tests, 20 samples late).
  const auto inside = channel_records(
      1, kSamples, [](int, int k) { return 0.01 * std::sin(kTheta * k); },
      [](int, int k) { return 0.01 * std::sin(kTheta * (k - 20)); });
  EXPECT_FALSE(evaluate_channel(inside, 1, 0).tracking_delay_at_window_edge);
}

TEST(TestCriteria, J1IsTheBenchmarksWholeSampleLagAt4096Hz) {
  // At the benchmark's 4096 Hz: 7 samples late is 7 / 4096 s; 7.4 samples reads 7, 7.6 reads
  // 8 (the nearest whole sample); 60 samples, beyond its 0..49, reads 49.
  constexpr double kRate = 4096.0;
  const double theta = 2.0 * std::numbers::pi / 512.0;  // 8 Hz
  const double delay[] = {7.0, 7.4, 7.6, 60.0};
  const double expected[] = {7.0, 7.0, 8.0, 49.0};
  for (int c = 0; c < 4; ++c) {
    SCOPED_TRACE(delay[c]);
    CriteriaAccumulator sums(1, 0, kRate);
    StepRecord r;
    r.channels = 1;
    for (int k = 0; k < 49 + 4096; ++k) {  // J1 sums 4096 products: eight whole periods
      r.target_m[0] = 0.01 * std::sin(theta * k);
      r.measured_m[0] = 0.01 * std::sin(theta * (k - delay[c]));
      sums.add_test(r);
    }
    EXPECT_EQ(sums.channel(0).j1_tracking_delay_ms, 1e3 * expected[c] / kRate);
  }
}

TEST(TestCriteria, J2AndJ3OfAnAmplitudeErrorAreItsPercentage) {
  // x_m = (1 + e) x_t: e x_t is the error, so J2 = J3 = 100 |e| for any target; channel 1's
  // target has an offset and another frequency.
  const double error[] = {0.05, -0.03};
  const auto target = [](int c, int k) {
    return c == 0 ? 0.01 * std::sin(kTheta * k) : 0.002 + 0.006 * std::sin(2.0 * kTheta * k);
  };
  const auto records =
      channel_records(2, kSamples, target, [&](int c, int k) { return (1.0 + error[c]) * target(c, k); });
  for (int c = 0; c < 2; ++c) {
    SCOPED_TRACE(c);
    const ChannelCriteria cc = evaluate_channel(records, 2, c);
    // 1e-9 relative: exact up to rounding.
    EXPECT_LT(relative(cc.j2_rms_tracking_error_percent, 100.0 * std::abs(error[c])), 1e-9);
    EXPECT_LT(relative(cc.j3_peak_tracking_error_percent, 100.0 * std::abs(error[c])), 1e-9);
    // No delay: J1's correlation peaks at lag 0, its edge; the signed delay's in the middle of
    // its window, where S(j) is even about 0 and the parabola's vertex is 0 (rounding only).
    EXPECT_EQ(cc.j1_tracking_delay_ms, 0.0);
    EXPECT_NEAR(cc.tracking_delay_ms, 0.0, 1e-9);
    EXPECT_FALSE(cc.tracking_delay_at_window_edge);
  }
}

TEST(TestCriteria, J2IsARawRmsRatioAndJ3DividesByThePeakOfTheTarget) {
  // x_t = B + A sin(theta k), x_m = B + A sin(theta (k - d)): the error has no offset but the
  // raw RMS of the target is sqrt(B^2 + A^2 / 2) and its peak B + A, so
  // J2 = 2 |sin(theta d / 2)| (A / sqrt 2) / sqrt(B^2 + A^2 / 2), J3 = 2 A |sin(theta d / 2)| / (B + A).
  // Mean-removed RMS would give 2 |sin(theta d / 2)| instead.
  const double offset = 0.02, amplitude = 0.01;
  const int delay = 20;
  const auto records = channel_records(
      1, kSamples, [&](int, int k) { return offset + amplitude * std::sin(kTheta * k); },
      [&](int, int k) { return offset + amplitude * std::sin(kTheta * (k - delay)); });
  const ChannelCriteria cc = evaluate_channel(records, 1, 0);
  const double rms_target = std::sqrt(offset * offset + amplitude * amplitude / 2.0);
  // 1e-9 relative: exact over whole periods up to rounding.
  EXPECT_LT(relative(cc.j2_rms_tracking_error_percent,
                     delay_error_percent(delay) * (amplitude / std::sqrt(2.0)) / rms_target),
            1e-9);
  EXPECT_LT(relative(cc.j3_peak_tracking_error_percent, delay_error_percent(delay) * amplitude / (offset + amplitude)),
            1e-9);
  // The offset adds W B^2 to every lag's product sum alike: the delay is unchanged (1e-9 ms as
  // above). J1's W = N - 49 products are not whole periods: the offset's cross terms move its
  // peak, and it is the argmax its definition gives, summed here directly.
  EXPECT_NEAR(cc.tracking_delay_ms, delay * kMsPerSample, 1e-9);
  EXPECT_EQ(cc.j1_tracking_delay_ms, j1_by_definition(records) * kMsPerSample);
  EXPECT_NE(j1_by_definition(records), delay);  // the case is not trivial
}

TEST(TestCriteria, TheFinalTrackingIndicatorIsTheLastRecordsValue) {
  // The records carry the tracking indicator of their own target and measured; for
  // d_m = A sin(theta (k - d)) it grows by A^2 / 2 sin(theta) sin(theta d) a step, so after
  // N samples it is (N - 1) A^2 / 2 sin(theta) sin(theta d): positive for a lag (channel 0),
  // negative and falling for a lead (channel 1), so the last value is not the largest.
  const double amplitude = 0.01;
  const int delay[] = {20, -12};
  auto records = channel_records(
      2, kSamples, [&](int, int k) { return amplitude * std::sin(kTheta * k); },
      [&](int c, int k) { return amplitude * std::sin(kTheta * (k - delay[c])); });
  compensation::TrackingIndicator ti[2];
  for (auto& r : records) {
    for (int c = 0; c < 2; ++c) {
      ti[c].update(r.target_m[c], r.measured_m[c]);
      r.tracking_indicator_m2[c] = ti[c].value_m2();
    }
  }
  for (int c = 0; c < 2; ++c) {
    SCOPED_TRACE(c);
    const double expected =
        (kSamples - 1) * amplitude * amplitude / 2.0 * std::sin(kTheta) * std::sin(kTheta * delay[c]);
    const ChannelCriteria cc = evaluate_channel(records, 2, c);
    // 1e-9 relative: the per-step increment is exact; 4000 trapezoids add rounding only.
    EXPECT_LT(relative(cc.final_tracking_indicator_m2, expected), 1e-9);
    EXPECT_EQ(cc.final_tracking_indicator_m2, records.back().tracking_indicator_m2[c]);
  }
}

TEST(TestCriteria, TheEnergyErrorIsInputLessKineticDampingAndRestoringAtTheLastStep) {
  // Input 3 t, kinetic t, damping t^2, restoring t / 2: at the end 1.5 t - t^2, negative at
  // t = 3999 / 2000 s; earlier steps (positive error below t = 1.5 s) do not count.
  auto records = channel_records(
      1, kSamples, [](int, int k) { return 0.01 * std::sin(kTheta * k); },
      [](int, int k) { return 0.01 * std::sin(kTheta * k); });
  for (auto& r : records) {
    r.input_energy_j = 3.0 * r.time_s;
    r.kinetic_energy_j = r.time_s;
    r.damping_energy_j = r.time_s * r.time_s;
    r.restoring_energy_j = 0.5 * r.time_s;
  }
  CriteriaAccumulator sums(1, 0, kRateHz);
  for (const auto& r : records) sums.add_test(r);
  const double t = (kSamples - 1) / kRateHz;
  // 1e-12 J: four terms of order 1 J, rounding only.
  EXPECT_NEAR(sums.criteria().energy_error_j, 1.5 * t - t * t, 1e-12);
  // And a perfect tracker has J2 = J3 = 0 and a tracking indicator of 0.
  const ChannelCriteria cc = sums.channel(0);
  EXPECT_EQ(cc.j2_rms_tracking_error_percent, 0.0);
  EXPECT_EQ(cc.j3_peak_tracking_error_percent, 0.0);
  EXPECT_EQ(cc.final_tracking_indicator_m2, 0.0);
}

// Recorded-DOF pairs: the reference's DOF d at step k and the test's.
struct DofRuns {
  std::vector<StepRecord> test, reference;
};

DofRuns dof_records(int dofs, const std::function<double(int d, int k)>& reference,
                    const std::function<double(int d, int k)>& test) {
  DofRuns runs;
  runs.test.resize(kSamples);
  runs.reference.resize(kSamples);
  for (int k = 0; k < kSamples; ++k) {
    StepRecord& t = runs.test[static_cast<std::size_t>(k)];
    StepRecord& r = runs.reference[static_cast<std::size_t>(k)];
    t.step = r.step = k;
    t.dofs = r.dofs = static_cast<std::uint8_t>(dofs);
    for (int d = 0; d < dofs; ++d) {
      r.displacement_m[d] = reference(d, k);
      t.displacement_m[d] = test(d, k);
    }
    // Unused DOFs beyond the recorded ones hold values that must not count.
    for (int d = dofs; d < kMaxRecordedDofs; ++d) {
      r.displacement_m[d] = 1.0 + d;
      t.displacement_m[d] = -5.0 - d;
    }
  }
  return runs;
}

// The DOF criteria through both add_pair overloads, which must agree bit for bit.
std::vector<DofCriteria> evaluate_dofs(const DofRuns& runs, int dofs) {
  CriteriaAccumulator by_record(1, dofs, kRateHz), by_span(1, dofs, kRateHz);
  for (std::size_t k = 0; k < runs.test.size(); ++k) {
    by_record.add_pair(runs.test[k], runs.reference[k]);
    by_span.add_pair(std::span<const double>(runs.test[k].displacement_m.data(), static_cast<std::size_t>(dofs)),
                     runs.reference[k]);
  }
  const Criteria a = by_record.criteria(), b = by_span.criteria();
  EXPECT_EQ(a.dofs.size(), static_cast<std::size_t>(dofs));
  EXPECT_EQ(b.dofs.size(), static_cast<std::size_t>(dofs));
  for (std::size_t d = 0; d < a.dofs.size() && d < b.dofs.size(); ++d) {
    EXPECT_EQ(a.dofs[d].rms_error_percent, b.dofs[d].rms_error_percent) << d;
    EXPECT_EQ(a.dofs[d].peak_error_percent, b.dofs[d].peak_error_percent) << d;
    EXPECT_EQ(a.dofs[d].peak_displacement_m, b.dofs[d].peak_displacement_m) << d;
    EXPECT_EQ(a.dofs[d].reference_peak_displacement_m, b.dofs[d].reference_peak_displacement_m) << d;
  }
  return a.dofs;
}

const double kFloorAmplitude[] = {0.01, 0.02, 0.03};

TEST(TestCriteria, J4ToJ9OfProportionalErrorsAreTheirPercentageDofByDof) {
  // Floor d's test = (1 + e_d) reference: J(4 + d) = J(7 + d) = 100 |e_d|, with e_d different
  // per floor so that a swapped or reused DOF shows.
  const double error[] = {0.01, -0.02, 0.04};
  const auto reference = [](int d, int k) { return kFloorAmplitude[d] * std::sin(kTheta * k); };
  const auto dofs =
      evaluate_dofs(dof_records(3, reference, [&](int d, int k) { return (1.0 + error[d]) * reference(d, k); }), 3);
  ASSERT_EQ(dofs.size(), 3u);
  for (int d = 0; d < 3; ++d) {
    SCOPED_TRACE(d);
    // 1e-9 relative: exact up to rounding.
    EXPECT_LT(relative(dofs[d].rms_error_percent, 100.0 * std::abs(error[d])), 1e-9);
    EXPECT_LT(relative(dofs[d].peak_error_percent, 100.0 * std::abs(error[d])), 1e-9);
    // The peaks fall on samples (k = P / 4 + m P / 2): exact up to rounding of sin(pi / 2).
    EXPECT_LT(relative(dofs[d].peak_displacement_m, (1.0 + error[d]) * kFloorAmplitude[d]), 1e-12);
    EXPECT_LT(relative(dofs[d].reference_peak_displacement_m, kFloorAmplitude[d]), 1e-12);
  }
}

TEST(TestCriteria, J4ToJ6AreRmsRatiosAndJ7ToJ9PeakRatiosOfAConstantOffset) {
  // Floor d's test = reference + c_d: RMS(e) = |c_d| against RMS(reference) = A_d / sqrt 2,
  // peak(e) = |c_d| against A_d, so J(4 + d) = 100 sqrt 2 |c_d| / A_d and J(7 + d) = 100 |c_d| / A_d.
  const double offset[] = {0.001, -0.0005, 0.0024};
  const auto reference = [](int d, int k) { return kFloorAmplitude[d] * std::sin(kTheta * k); };
  const auto dofs =
      evaluate_dofs(dof_records(3, reference, [&](int d, int k) { return reference(d, k) + offset[d]; }), 3);
  ASSERT_EQ(dofs.size(), 3u);
  for (int d = 0; d < 3; ++d) {
    SCOPED_TRACE(d);
    const double ratio = std::abs(offset[d]) / kFloorAmplitude[d];
    // 1e-9 relative: exact over whole periods up to rounding.
    EXPECT_LT(relative(dofs[d].rms_error_percent, 100.0 * std::sqrt(2.0) * ratio), 1e-9);
    EXPECT_LT(relative(dofs[d].peak_error_percent, 100.0 * ratio), 1e-9);
    EXPECT_LT(relative(dofs[d].peak_displacement_m, kFloorAmplitude[d] + std::abs(offset[d])), 1e-12);
  }
}

TEST(TestCriteria, J4ToJ9OfADelayedResponseFollowTheDelayedSine) {
  // Floor d's test lags its reference by an even number of samples: J(4 + d) = J(7 + d) =
  // 200 |sin(theta d / 2)| (the error's peak falls on a sample).
  const int delay[] = {4, 10, 30};
  const auto dofs =
      evaluate_dofs(dof_records(
                        3, [](int d, int k) { return kFloorAmplitude[d] * std::sin(kTheta * k); },
                        [&](int d, int k) { return kFloorAmplitude[d] * std::sin(kTheta * (k - delay[d])); }),
                    3);
  ASSERT_EQ(dofs.size(), 3u);
  for (int d = 0; d < 3; ++d) {
    SCOPED_TRACE(d);
    // 1e-9 relative: exact over whole periods up to rounding.
    EXPECT_LT(relative(dofs[d].rms_error_percent, delay_error_percent(delay[d])), 1e-9);
    EXPECT_LT(relative(dofs[d].peak_error_percent, delay_error_percent(delay[d])), 1e-9);
  }
}

}  // namespace
}  // namespace rpsd::coordinator

namespace rpsd::coordinator {
namespace {

TEST(TestCriteria, AnExperimentalFloorIsJudgedOnItsMeasuredDisplacementAsThePaperDefinesJ4AndJ7) {
  // Floor 1 is channel 1's DOF (specimen scale 2: measured = 2 x model). Its numerical
  // displacement equals the reference, its measured one is (1 + 3 %) of 2 x reference: the
  // paper's J4 = J7 = 3 %, where the numerical y_n would give 0. Floor 2 stays numerical.
  const auto reference = [](int d, int k) { return kFloorAmplitude[d] * std::sin(kTheta * k); };
  DofRuns runs = dof_records(2, reference, reference);
  for (int k = 0; k < kSamples; ++k) {
    StepRecord& t = runs.test[static_cast<std::size_t>(k)];
    t.channels = 2;
    t.measured_m[0] = 5.0;  // another channel's: must not count
    t.measured_m[1] = 2.0 * 1.03 * reference(0, k);
  }
  CriteriaAccumulator by_record(2, 2, kRateHz, {{1, 2.0}, {}}), by_span(2, 2, kRateHz, {{1, 2.0}, {}});
  for (std::size_t k = 0; k < runs.test.size(); ++k) {
    by_record.add_pair(runs.test[k], runs.reference[k]);
    std::array<double, 2> floors{};
    by_span.floor_displacements(runs.test[k], floors);
    by_span.add_pair(floors, runs.reference[k]);
  }
  for (const Criteria& c : {by_record.criteria(), by_span.criteria()}) {
    ASSERT_EQ(c.dofs.size(), 2u);
    EXPECT_LT(relative(c.dofs[0].rms_error_percent, 3.0), 1e-9);
    EXPECT_LT(relative(c.dofs[0].peak_error_percent, 3.0), 1e-9);
    EXPECT_LT(relative(c.dofs[0].peak_displacement_m, 1.03 * kFloorAmplitude[0]), 1e-12);
    EXPECT_EQ(c.dofs[1].rms_error_percent, 0.0);
  }
  EXPECT_THROW(CriteriaAccumulator(1, 1, kRateHz, {{1, 1.0}}), std::invalid_argument);
  EXPECT_THROW(CriteriaAccumulator(1, 1, kRateHz, {{0, 0.0}}), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::coordinator
