// The host check's arithmetic (host_floor.h): the empty loop's tally from a pacer's counts,
// the steal time from /proc/stat, and the CPU idle states from a sysfs tree, each against
// values worked out by hand on a fake pacer, a fake /proc/stat line and a fake sysfs tree.
#include "rpsd/realtime/host_floor.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace rpsd::realtime {
namespace {

// Pacer's interface on a scripted clock: every 250th cycle wakes 3 periods late (an overrun
// that skips 2 deadlines), the others 1 us late plus 1 us per 100 cycles.
class FakePacer {
 public:
  static constexpr std::int64_t kPeriodNs = 1'000'000;
  void start() { cycles_ = overruns_ = skipped_ = 0; }
  std::int64_t wait_next() {
    ++cycles_;
    if (cycles_ % 250 == 0) {
      ++overruns_;
      skipped_ += 2;
      return 3 * kPeriodNs;
    }
    return 1'000 + 1'000 * (cycles_ / 100);
  }
  std::int64_t cycles() const { return cycles_; }
  std::int64_t overruns() const { return overruns_; }
  std::int64_t skipped_deadlines() const { return skipped_; }

 private:
  std::int64_t cycles_ = 0, overruns_ = 0, skipped_ = 0;
};

TEST(HostFloor, TheTallyCountsEveryCycleAndThePacersOverruns) {
  FakePacer pacer;
  const EmptyLoopFloor floor = tally_empty_loop(pacer, 1000, 1000);
  EXPECT_EQ(floor.rate_hz, 1000);
  EXPECT_EQ(floor.cycles, 1000);
  EXPECT_EQ(floor.overruns, 4);  // cycles 250, 500, 750, 1000
  EXPECT_EQ(floor.skipped_deadlines, 8);
  EXPECT_DOUBLE_EQ(floor.overruns_percent(), 0.4);
  EXPECT_EQ(floor.wakeup.count, 1000);
  // The late wake-ups are the largest: 3 ms exactly (the histogram keeps the exact maximum).
  EXPECT_DOUBLE_EQ(floor.wakeup.max_s, 3e-3);
  EXPECT_LE(floor.wakeup.p50_s, floor.wakeup.p99_s);
  EXPECT_LE(floor.wakeup.p99_s, floor.wakeup.p999_s);
  EXPECT_LE(floor.wakeup.p999_s, floor.wakeup.max_s);
  // The median wake-up is cycle ~500's: 1 us + 5 us, to the 1 us bin.
  EXPECT_NEAR(floor.wakeup.p50_s, 6e-6, 1.01e-6);
}

TEST(HostFloor, NoCyclesIsNoOverrunPercentNotADivisionByZero) { EXPECT_EQ(EmptyLoopFloor{}.overruns_percent(), 0.0); }

TEST(HostFloor, StealTimeIsTheStolenShareOfTheCpuTimeBetweenTwoReadings) {
  // user nice system idle iowait irq softirq steal guest guest_nice: total 1000, steal 10.
  const CpuTimes before = parse_cpu_times("cpu  500 0 200 250 20 10 10 10 0 0\ncpu0 1 2 3\n");
  EXPECT_EQ(before.total, 1000);
  EXPECT_EQ(before.steal, 10);
  // 200 jiffies later, 30 of them stolen: 15 %.
  const CpuTimes after = parse_cpu_times("cpu  600 0 250 270 20 10 10 40 0 0");
  EXPECT_EQ(after.total, 1200);
  EXPECT_DOUBLE_EQ(steal_percent(before, after), 15.0);
  EXPECT_EQ(steal_percent(before, before), 0.0);
  // A kernel without the steal column: no steal.
  EXPECT_EQ(parse_cpu_times("cpu 1 2 3 4").steal, 0);
  EXPECT_THROW(parse_cpu_times("intr 1 2 3"), std::runtime_error);
}

TEST(HostFloor, TheEmptyLoopRunsSecondsTimesRateCycles) {
  // A count, not a time: 20 ms at 1024 Hz is 20 cycles however late each wake-up is.
  const EmptyLoopFloor floor = measure_empty_loop(1024, 0.02, false);
  EXPECT_EQ(floor.cycles, 20);
  EXPECT_EQ(floor.wakeup.count, 20);
  EXPECT_GE(floor.overruns, 0);
  EXPECT_LE(floor.overruns, floor.cycles);
  EXPECT_GE(floor.steal_percent, 0.0);
  EXPECT_THROW(measure_empty_loop(0, 1.0, false), std::invalid_argument);
  EXPECT_THROW(measure_empty_loop(1024, 0.0, false), std::invalid_argument);
}

void write(const std::filesystem::path& file, const std::string& text) {
  std::filesystem::create_directories(file.parent_path());
  std::ofstream(file) << text << '\n';
}

TEST(HostFloor, IdleStatesAreReadInTheirOrderFromSysfs) {
  namespace fs = std::filesystem;
  const fs::path root = fs::temp_directory_path() / ("rpsd-host-floor-" + std::to_string(::getpid()));
  fs::remove_all(root);
  write(root / "cpuidle" / "current_driver", "intel_idle");
  // Eleven states, so that state10 must come after state9 (not after state1 as names sort).
  for (int n = 0; n <= 10; ++n) {
    const fs::path state = root / "cpu0" / "cpuidle" / ("state" + std::to_string(n));
    write(state / "name", "C" + std::to_string(n));
    write(state / "latency", std::to_string(10 * n));
    write(state / "disable", n == 2 ? "1" : "0");
  }
  write(root / "cpu1" / "cpuidle" / "state0" / "name", "POLL");
  fs::create_directories(root / "cpufreq");  // not a CPU
  fs::create_directories(root / "cpu2");     // a CPU without cpuidle

  const IdleStates idle = read_idle_states(root.string());
  EXPECT_EQ(idle.driver, "intel_idle");
  EXPECT_EQ(idle.cpus, 2);
  ASSERT_EQ(idle.states.size(), 11u);
  EXPECT_EQ(idle.states[10].name, "C10");
  EXPECT_EQ(idle.states[10].exit_latency_us, 100);
  EXPECT_TRUE(idle.states[2].disabled);
  EXPECT_FALSE(idle.states[3].disabled);
  if (::geteuid() == 0) {
    EXPECT_TRUE(idle.states[0].can_be_disabled);  // root may write any file
  }
  fs::remove_all(root);

  // A host without cpuidle: nothing listed, no error.
  const IdleStates none = read_idle_states((root / "absent").string());
  EXPECT_TRUE(none.driver.empty());
  EXPECT_EQ(none.cpus, 0);
  EXPECT_TRUE(none.states.empty());
}

}  // namespace
}  // namespace rpsd::realtime
