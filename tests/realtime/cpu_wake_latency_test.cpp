// The PM QoS request that keeps the CPUs out of slow idle states: in force while the hold
// lives, released when it ends, and a refusal reported rather than thrown.
#include "rpsd/realtime/cpu_wake_latency.h"

#include <unistd.h>

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>

#include "rpsd/realtime/realtime_setup.h"

namespace rpsd::realtime {
namespace {

bool can_request() { return ::access(kPmQosDevice, W_OK) == 0; }

// Whether a process other than this one has the PM QoS device open. ctest runs other tests
// beside this one, and a real-time loop among them holds the CPUs awake while it runs; then
// the limit stays 0 after this test's own hold ends, and the release cannot be seen.
bool another_process_holds_the_device() {
  namespace fs = std::filesystem;
  const std::string self = std::to_string(::getpid());
  std::error_code ec;
  for (const auto& proc : fs::directory_iterator("/proc", ec)) {
    const std::string pid = proc.path().filename();
    if (pid == self || pid.find_first_not_of("0123456789") != std::string::npos) continue;
    for (const auto& fd : fs::directory_iterator(proc.path() / "fd", ec)) {
      if (fs::read_symlink(fd.path(), ec) == kPmQosDevice) return true;
    }
  }
  return false;
}

TEST(CpuWakeLatencyHold, TheLimitIsZeroWhileTheHoldLivesAndReleasedAfter) {
  if (!can_request()) GTEST_SKIP() << kPmQosDevice << " is not writable here (needs root)";
  {
    CpuWakeLatencyHold hold(0);
    ASSERT_TRUE(hold.held()) << hold.refused();
    EXPECT_EQ(current_cpu_wake_latency_limit_us(), 0);
    CpuWakeLatencyHold moved = std::move(hold);  // the request moves with the file
    EXPECT_FALSE(hold.held());
    EXPECT_TRUE(moved.held());
    EXPECT_EQ(current_cpu_wake_latency_limit_us(), 0);
  }
  if (current_cpu_wake_latency_limit_us() == 0) {
    // Either this hold was not released, or another test's loop holds one now.
    if (another_process_holds_the_device())
      GTEST_SKIP() << "another process holds the CPUs awake; the release cannot be seen";
    EXPECT_GT(current_cpu_wake_latency_limit_us(), 0) << "the request outlived its hold";
  }
}

TEST(CpuWakeLatencyHold, ARealTimeRequestHoldsAndSaysSo) {
  if (!can_request()) GTEST_SKIP() << kPmQosDevice << " is not writable here (needs root)";
  RealTimeSetupReport report;
  {
    const CpuWakeLatencyHold hold = hold_cpus_awake(RealTimeRequest{}, report);
    EXPECT_TRUE(hold.held());
    EXPECT_TRUE(report.cpus_kept_awake);
    EXPECT_EQ(report.refused, "");
    EXPECT_EQ(current_cpu_wake_latency_limit_us(), 0);
  }
  RealTimeRequest off;
  off.keep_cpus_awake = false;
  RealTimeSetupReport left_alone;
  const CpuWakeLatencyHold none = hold_cpus_awake(off, left_alone);
  EXPECT_FALSE(none.held());
  EXPECT_FALSE(left_alone.cpus_kept_awake);
  EXPECT_EQ(left_alone.refused, "");
}

TEST(CpuWakeLatencyHold, ARefusalIsReportedNotThrown) {
  const CpuWakeLatencyHold hold(0, "/nonexistent/cpu_dma_latency");
  EXPECT_FALSE(hold.held());
  EXPECT_EQ(hold.refused(), "/nonexistent/cpu_dma_latency: No such file or directory");
}

}  // namespace
}  // namespace rpsd::realtime
