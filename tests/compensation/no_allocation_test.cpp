// Zero heap allocations on the real-time path: command() and observe() of every compensator,
// update() and estimate() of the online delay estimators, over 100,000 samples each.
//
// This binary replaces the global operator new/delete and the C allocation functions
// (malloc, calloc, realloc and the aligned variants; glibc allows replacing them and exports
// the __libc_* originals) and counts calls while a window is open. Eigen allocates with
// malloc, not operator new, so counting malloc as well catches hidden Eigen temporaries.
#include <gtest/gtest.h>

#include <atomic>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <deque>
#include <memory>
#include <new>

#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/compensation/cross_correlation_delay.h"
#include "rpsd/compensation/frequency_evaluation_index.h"
#include "rpsd/compensation/tracking_indicator.h"

#include "allocation_counter.h"
#include "kind_types.h"

namespace rpsd::compensation {
namespace {

constexpr int kSamples = 100000;
constexpr double kDt = 1.0 / 2048.0;

template <typename F>
long count_allocations(F&& f) {
  rpsd::testing::begin_counting_allocations();
  f();
  return rpsd::testing::end_counting_allocations().total();
}

// A broadband target so that the adaptive schemes really update (and take their O(W) paths).
double target_at(int n) {
  const double t = n * kDt;
  return 0.006 * std::sin(2.0 * 3.14159265358979 * 1.1 * t) + 0.003 * std::sin(2.0 * 3.14159265358979 * 2.7 * t + 1.0) +
         0.0015 * std::sin(2.0 * 3.14159265358979 * 4.9 * t + 2.0);
}

TEST(NoAllocation, TheCounterSeesAllocations) {
  // Guards against a hook that counts nothing.
  const long c = count_allocations([] {
    auto* p = new int(3);
    rpsd::testing::keep(p);
    delete p;
    void* q = std::malloc(16);
    rpsd::testing::keep(q);
    std::free(q);
    std::deque<double> d(10);
  });
  EXPECT_GE(c, 3);
}

// A working example of each compensator kind: its default parameters, or those below where
// the defaults are no working compensator (make_compensator refuses them, and the test says
// so: a new kind is run here without a new line as soon as its defaults work).
template <class Kind>
Kind example_of() {
  return Kind{};
}
template <>
DiscretePhaseLeadParameters example_of() {
  return DiscretePhaseLeadParameters::for_delay(0.04, 5.0, 1.58);
}
template <>
PolynomialExtrapolationParameters example_of() {
  return {3, 0.02};
}
template <>
InverseCompensationParameters example_of() {
  return InverseCompensationParameters{0.02};
}
template <>
AdaptiveInverseCompensationParameters example_of() {
  AdaptiveInverseCompensationParameters p;
  p.proportional_gain_s_per_m2 = 500.0;
  p.integral_gain_per_m2 = 10.0;
  return p;
}
template <>
AdaptiveTimeSeriesParameters example_of() {
  AdaptiveTimeSeriesParameters p;
  p.initial_coefficients = {1.0, 0.0, 0.0};
  return p;
}
template <>
LtiFilterParameters example_of() {
  return LtiFilterParameters{{{1.0, 60.0, 800.0}, {1.0, 90.0, 800.0}}, 0.0};
}

// The external kind's wrapper around a host compensator that passes the target through (the
// kind never runs on a real-time path, but its wrapper adds nothing to a host's own cost).
struct PassingHost final : HostCompensator {
  double command(double target_m) override { return target_m; }
};
struct PassingSource final : ExternalCompensatorSource {
  std::unique_ptr<HostCompensator> make(int) const override { return std::make_unique<PassingHost>(); }
};
template <>
ExternalCompensatorParameters example_of() {
  return ExternalCompensatorParameters{"passing", std::make_shared<PassingSource>()};
}

// Every kind in CompensatorKinds (the registry's list), so a new one is covered by this suite.
template <class Kind>
class EveryCompensatorKind : public ::testing::Test {};
TYPED_TEST_SUITE(EveryCompensatorKind, rpsd::testing::KindTypes<CompensatorKinds>::type, rpsd::testing::KindNames);

TYPED_TEST(EveryCompensatorKind, CommandAndObserveAllocateNothing) {
  std::unique_ptr<CommandCompensator> c;
  ASSERT_NO_THROW(c = make_compensator(example_of<TypeParam>(), kDt))
      << "give example_of<" << TypeParam::kName << "> working parameters";
  c->reset(0.0);
  // The plant: a 40-step delay line in a fixed ring (the test itself must not allocate).
  double line[40] = {};
  double check = 0.0;
  const long allocations = count_allocations([&] {
    for (int n = 0; n < kSamples; ++n) {
      const double x = target_at(n);
      const double u = c->command(x);
      const double measured = line[n % 40];
      line[n % 40] = u;
      c->observe(x, measured);
      check += u + c->compensated_delay_s();
    }
  });
  EXPECT_EQ(allocations, 0) << c->name();
  EXPECT_TRUE(std::isfinite(check)) << c->name();
  if (auto* a = dynamic_cast<AdaptiveTimeSeriesCompensator*>(c.get())) {
    EXPECT_GT(a->accepted_updates(), 1000);  // the O(W) update path ran
  }
}

// The phase lead without prewarping: the plain Tustin path.
TEST(NoAllocation, PhaseLeadWithoutPrewarp) {
  const auto c = make_compensator(DiscretePhaseLeadParameters::for_delay(0.04, 5.0), kDt);
  c->reset(0.0);
  double check = 0.0;
  const long allocations = count_allocations([&] {
    for (int n = 0; n < kSamples; ++n) check += c->command(target_at(n));
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(check));
}

TEST(NoAllocation, OnlineDelayEstimators) {
  TrackingIndicator ti;
  CrossCorrelationDelayEstimator xcorr;
  CrossCorrelationDelayParameters xp;
  xp.window_samples = 2048;
  xp.options.measure = CorrelationMeasure::kPearson;
  xcorr.configure(xp);
  FrequencyEvaluationIndexEstimator fei;
  FrequencyEvaluationIndexParameters fp;
  fp.dt_s = kDt;
  fp.window_samples = 2048;
  fp.evaluation_interval_samples = 64;
  fei.configure(fp);
  FrequencyEvaluationIndexEstimator fei_odd;  // not a multiple of 4: kissfft's other path
  fp.window_samples = 2046;
  fei_odd.configure(fp);
  double check = 0.0;
  const long allocations = count_allocations([&] {
    for (int n = 0; n < kSamples; ++n) {
      const double x = target_at(n), m = target_at(n - 25);
      ti.update(x, m);
      xcorr.update(x, m);
      fei.update(x, m);
      fei_odd.update(x, m);
      const DelayEstimate e = xcorr.estimate();
      check += ti.value_m2() + e.delay_samples + fei.latest().delay_s + fei_odd.latest().delay_s;
    }
  });
  EXPECT_EQ(allocations, 0);
  EXPECT_TRUE(std::isfinite(check));
  EXPECT_NEAR(xcorr.estimate().delay_samples, 25.0, 0.05);
  // The tones are not periodic in the 1 s window: leakage biases FEI's delay (here ~15 %).
  EXPECT_NEAR(fei.latest().delay_s, 25 * kDt, 0.2 * 25 * kDt);
}

}  // namespace
}  // namespace rpsd::compensation
