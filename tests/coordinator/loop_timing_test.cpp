// The two loop timings (coordinator/loop_timing.h) against a one-DOF loop solved by hand,
// sample by sample: the paper's elastic SDOF (the spring is the specimen), a perfect
// actuator (x_m = command) and central difference written out below in its own few lines.
// rpsd's end of step feeds k x_{n+1} at t_{n+1}; the benchmark's loop commands x_n and feeds
// the force of the exchange before, k x_{n-1}.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "specimen_runs.h"

namespace rpsd::coordinator {
namespace {

using testing::run_steps;
using testing::SdofRun;

struct HandStep {
  double displacement_m, target_m, measured_m;
};

// x+ = x + dt v + dt^2/2 a; (m + dt/2 c) a+ = -R+ - c (v + dt/2 a); v+ = v + dt/2 (a + a+).
std::vector<HandStep> by_hand(const hybrid_test::SpecimenSdof& s, LoopTiming timing, int steps) {
  const double m = s.mass_kg, k = s.stiffness_n_per_m, c = 2.0 * s.damping_ratio * std::sqrt(k * m);
  const double dt = 1.0 / s.control_rate_hz;
  double x = s.initial_displacement_m, v = 0.0, a = -k * x / m;
  double held_target = x, held_force = k * x;  // the start: the specimen holds x0
  std::vector<HandStep> out;
  for (int n = 0; n < steps; ++n) {
    const double next = x + dt * v + 0.5 * dt * dt * a;
    double command = next, fed = 0.0;
    if (timing == LoopTiming::kEndOfStep) {
      fed = k * next;
    } else {
      command = held_target;
      fed = held_force;
      held_force = k * command;  // this exchange's force, fed a step later
      held_target = next;
    }
    const double a_next = (-fed - c * (v + 0.5 * dt * a)) / (m + 0.5 * dt * c);
    v += 0.5 * dt * (a + a_next);
    a = a_next;
    x = next;
    out.push_back({x, command, command});
  }
  return out;
}

SdofRun run_with_timing(const hybrid_test::SpecimenSdof& s, LoopTiming timing,
                        hybrid_test::AssemblyOptions options = {}) {
  hybrid_test::TestConfig config = hybrid_test::specimen_sdof_test(s);
  config.clock.loop_timing = timing;
  return run_steps(config, std::move(options));
}

hybrid_test::SpecimenSdof perfect_sdof() {
  hybrid_test::SpecimenSdof s;  // 7080 kg, 700.8 kN/m, 1.1 %, from 10 mm, 1024 Hz
  s.duration_s = 3.0;
  return s;  // an ideal actuator without delay: x_m is the command
}

TEST(LoopTiming, EachTimingIsTheOneDofLoopSolvedByHand) {
  const auto s = perfect_sdof();
  double largest_difference_m = 0.0;
  for (LoopTiming timing : {LoopTiming::kEndOfStep, LoopTiming::kTargetNowForceDelayed}) {
    SCOPED_TRACE(std::string(loop_timing_name(timing)));
    const SdofRun r = run_with_timing(s, timing);
    ASSERT_EQ(r.outcome, StepOutcome::kOk);
    const auto hand = by_hand(s, timing, static_cast<int>(r.records.size()));
    const auto other =
        by_hand(s, timing == LoopTiming::kEndOfStep ? LoopTiming::kTargetNowForceDelayed : LoopTiming::kEndOfStep,
                static_cast<int>(r.records.size()));
    for (std::size_t n = 0; n < hand.size(); ++n) {
      // 1e-12 of x0: the same arithmetic in another order, rounding only.
      ASSERT_NEAR(r.records[n].displacement_m[0], hand[n].displacement_m, 1e-12 * s.initial_displacement_m) << n;
      ASSERT_NEAR(r.records[n].target_m[0], hand[n].target_m, 1e-12 * s.initial_displacement_m) << n;
      ASSERT_NEAR(r.records[n].measured_m[0], hand[n].measured_m, 1e-12 * s.initial_displacement_m) << n;
      largest_difference_m = std::max(largest_difference_m, std::abs(hand[n].displacement_m - other[n].displacement_m));
    }
  }
  // The two timings are different loops: two samples more on the force make the response
  // drift apart by far more than the tolerance above.
  EXPECT_GT(largest_difference_m, 1e-4 * s.initial_displacement_m);
}

TEST(LoopTiming, TheBenchmarksForceDelayTakesTheDampingTheClosedFormSays) {
  // The benchmark's loop feeds k x(t - 2 dt) (one sample on the target, one on the force):
  // for a light delay tau the restoring force's lag takes omega tau / 2 off the damping ratio
  // (tau k sin(omega tau) / (2 m omega) ~ omega tau / 2 for omega tau << 1). Identified from
  // the decay of the peaks of a free vibration, both timings against it.
  auto s = perfect_sdof();
  s.duration_s = 10.0;
  const double omega = std::sqrt(s.stiffness_n_per_m / s.mass_kg), dt = 1.0 / s.control_rate_hz;
  const auto decay_ratio = [&](LoopTiming timing) {
    const SdofRun r = run_with_timing(s, timing);
    std::vector<double> peaks;
    for (std::size_t n = 1; n + 1 < r.records.size(); ++n) {
      const double x = r.records[n].displacement_m[0];
      if (x > r.records[n - 1].displacement_m[0] && x >= r.records[n + 1].displacement_m[0]) peaks.push_back(x);
    }
    // Logarithmic decrement over the whole record: zeta = ln(x_0 / x_N) / (2 pi N).
    return std::log(peaks.front() / peaks.back()) / (2.0 * std::acos(-1.0) * static_cast<double>(peaks.size() - 1));
  };
  const double end_of_step = decay_ratio(LoopTiming::kEndOfStep);
  const double benchmark = decay_ratio(LoopTiming::kTargetNowForceDelayed);
  // 2e-4: sampled peaks and the integrator's own period error, against a 0.9e-2 shift.
  EXPECT_NEAR(end_of_step - benchmark, omega * 2.0 * dt / 2.0, 2e-4);
}

TEST(LoopTiming, TheReferenceIsTheStructureIntegratedWholeUnderEitherTiming) {
  // The perfect-actuator reference has no loop to time: it is the same under both.
  const auto s = perfect_sdof();
  hybrid_test::AssemblyOptions reference;
  reference.perfect_actuator = true;
  const SdofRun a = run_with_timing(s, LoopTiming::kEndOfStep, reference);
  const SdofRun b = run_with_timing(s, LoopTiming::kTargetNowForceDelayed, reference);
  ASSERT_EQ(a.records.size(), b.records.size());
  for (std::size_t n = 0; n < a.records.size(); ++n)
    ASSERT_EQ(a.records[n].displacement_m[0], b.records[n].displacement_m[0]) << n;
}

TEST(LoopTiming, TheBenchmarksTimingIsRefusedWithMoreThanOneExchangeAStep) {
  auto s = perfect_sdof();
  s.integrator = integrators::NewmarkParameters{};
  hybrid_test::TestConfig config = hybrid_test::specimen_sdof_test(s);
  config.clock.loop_timing = LoopTiming::kTargetNowForceDelayed;
  try {
    hybrid_test::TestAssembly test(config, {});
    FAIL() << "no error";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("target_now_force_delayed needs one exchange per step"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace rpsd::coordinator
