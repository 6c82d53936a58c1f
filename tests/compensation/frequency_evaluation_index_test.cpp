// The frequency-domain evaluation index on a pure delay and a known amplitude scaling,
// offline and online.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "rpsd/compensation/frequency_evaluation_index.h"
#include "test_signals.h"
#include "test_time_step.h"

namespace rpsd::compensation {
namespace {

constexpr int kN = 4096;  // 4 s: bins every 0.25 Hz

struct InOutRecords {
  std::vector<double> in, out;
};

InOutRecords make(const testing::MultiSine& s, double delay_s, double gain, int n = kN, double offset = 0.0) {
  InOutRecords r;
  for (int k = 0; k < n; ++k) {
    r.in.push_back(offset + s(k * kDt));
    r.out.push_back(offset + gain * s(k * kDt - delay_s));
  }
  return r;
}

TEST(FrequencyEvaluationIndex, PureDelayOfOneToneIsRecoveredExactly) {
  // A tone on a bin is periodic over the record: O = I e^{-j w tau} on that bin only, so
  // FEI = e^{-j w tau}, f_eq = f and the delay is tau.
  const testing::MultiSine tone{{0.01}, {1.5}, {0.4}};
  const double tau = 0.0173;  // not a whole number of samples
  const InOutRecords r = make(tone, tau, 1.0);
  const FrequencyEvaluationIndex fei = frequency_evaluation_index(r.in, r.out, kDt);
  ASSERT_TRUE(fei.valid);
  EXPECT_NEAR(fei.amplitude, 1.0, 1e-9);
  EXPECT_NEAR(fei.phase_rad, -2.0 * std::numbers::pi * 1.5 * tau, 1e-9);
  EXPECT_NEAR(fei.equivalent_frequency_hz, 1.5, 1e-9);
  EXPECT_NEAR(fei.delay_s, tau, 1e-9);
}

TEST(FrequencyEvaluationIndex, AmplitudeScalingGivesTheGainAndNoPhase) {
  const testing::MultiSine s{{0.01, 0.004}, {1.0, 3.5}, {0.0, 1.0}};
  const InOutRecords r = make(s, 0.0, 0.7);
  const FrequencyEvaluationIndex fei = frequency_evaluation_index(r.in, r.out, kDt);
  EXPECT_NEAR(fei.amplitude, 0.7, 1e-12);
  EXPECT_NEAR(fei.phase_rad, 0.0, 1e-12);
  EXPECT_NEAR(fei.delay_s, 0.0, 1e-12);
}

TEST(FrequencyEvaluationIndex, TwoTonesCombineAsTheirPowerWeightedSum) {
  // FEI = sum_i A_i^2 g e^{-j w_i tau} / sum_i A_i^2, f_eq = sum_i A_i^2 f_i / sum_i A_i^2.
  const testing::MultiSine s{{0.01, 0.005}, {1.25, 4.0}, {0.2, 2.2}};
  const double tau = 0.021, g = 1.1;
  const InOutRecords r = make(s, tau, g);
  const FrequencyEvaluationIndex fei = frequency_evaluation_index(r.in, r.out, kDt);
  const double p1 = 1e-4, p2 = 2.5e-5;
  const std::complex<double> expected = g *
                                        (p1 * std::polar(1.0, -2.0 * std::numbers::pi * 1.25 * tau) +
                                         p2 * std::polar(1.0, -2.0 * std::numbers::pi * 4.0 * tau)) /
                                        (p1 + p2);
  const double f_eq = (p1 * 1.25 + p2 * 4.0) / (p1 + p2);
  EXPECT_NEAR(std::abs(fei.index - expected), 0.0, 1e-9);
  EXPECT_NEAR(fei.equivalent_frequency_hz, f_eq, 1e-9);
  EXPECT_NEAR(fei.delay_s, -std::arg(expected) / (2.0 * std::numbers::pi * f_eq), 1e-9);
  // Close to, not equal to, tau: the phase of a weighted sum of unit phasors.
  EXPECT_NEAR(fei.delay_s, tau, 0.02 * tau);
}

TEST(FrequencyEvaluationIndex, MeanRemovalIgnoresAnOffset) {
  const testing::MultiSine tone{{0.01}, {2.0}, {0.0}};
  const InOutRecords r = make(tone, 0.01, 1.0, kN, 0.03);
  const FrequencyEvaluationIndex kept = frequency_evaluation_index(r.in, r.out, kDt);
  const FrequencyEvaluationIndex removed = frequency_evaluation_index(r.in, r.out, kDt, true);
  EXPECT_NEAR(removed.delay_s, 0.01, 1e-9);
  EXPECT_NEAR(removed.equivalent_frequency_hz, 2.0, 1e-9);
  // Kept, the offset puts power on the DC bin (f = 0): f_eq drops well below the tone.
  EXPECT_LT(kept.equivalent_frequency_hz, 1.0);
}

TEST(FrequencyEvaluationIndex, OnlineWindowMatchesOfflineOnTheSameSamples) {
  const testing::MultiSine s{{0.01, 0.003}, {1.5, 6.0}, {0.0, 0.5}};
  FrequencyEvaluationIndexParameters p;
  p.dt_s = kDt;
  p.window_samples = 2048;
  p.evaluation_interval_samples = 128;
  FrequencyEvaluationIndexEstimator online;
  online.configure(p);
  EXPECT_FALSE(online.latest().valid);
  const double tau = 0.012;
  const int total = 2048 + 5 * 128;  // ends on an evaluation
  std::vector<double> in, out;
  for (int k = 0; k < total; ++k) {
    in.push_back(s(k * kDt));
    out.push_back(s(k * kDt - tau));
    online.update(in.back(), out.back());
    if (k == 2046) {
      EXPECT_FALSE(online.latest().valid);
    }
    if (k == 2047) {
      EXPECT_TRUE(online.latest().valid);
    }
  }
  const std::span<const double> window_in(in.data() + total - 2048, 2048), window_out(out.data() + total - 2048, 2048);
  const FrequencyEvaluationIndex offline = frequency_evaluation_index(window_in, window_out, kDt);
  EXPECT_NEAR(std::abs(online.latest().index - offline.index), 0.0, 1e-12);
  EXPECT_NEAR(online.latest().delay_s, offline.delay_s, 1e-12);
  // Both tones are on bins of the 2 s window: a two-tone closed form again.
  EXPECT_NEAR(offline.amplitude,
              std::abs(1e-4 * std::polar(1.0, -2.0 * std::numbers::pi * 1.5 * tau) +
                       9e-6 * std::polar(1.0, -2.0 * std::numbers::pi * 6.0 * tau)) /
                  (1e-4 + 9e-6),
              1e-9);
}

TEST(FrequencyEvaluationIndex, RejectsBadInput) {
  std::vector<double> a(10), b(9);
  EXPECT_THROW(frequency_evaluation_index(a, b, kDt), std::invalid_argument);
  EXPECT_THROW(frequency_evaluation_index(a, a, 0.0), std::invalid_argument);
  FrequencyEvaluationIndexParameters p;
  FrequencyEvaluationIndexEstimator e;
  EXPECT_THROW(e.configure(p), std::invalid_argument);        // dt_s unset
  EXPECT_FALSE(frequency_evaluation_index(a, a, kDt).valid);  // no energy
}

}  // namespace
}  // namespace rpsd::compensation
