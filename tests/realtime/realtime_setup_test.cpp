// The loop's own CPU (RealTimeRequest::loop_cpu): the calling thread is pinned to it and only
// to it; a CPU the host lacks is a refusal reported, not a failure; one beyond any host is a
// programming error.
#include "rpsd/realtime/realtime_setup.h"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>

#include <stdexcept>
#include <string>
#include <thread>

namespace rpsd::realtime {
namespace {

RealTimeRequest pin_only(int cpu) {
  RealTimeRequest r;
  r.lock_memory = false;
  r.fifo_priority = 0;
  r.keep_cpus_awake = false;
  r.loop_cpu = cpu;
  return r;
}

// The CPUs the calling thread may run on.
cpu_set_t allowed() {
  cpu_set_t cpus;
  CPU_ZERO(&cpus);
  pthread_getaffinity_np(pthread_self(), sizeof cpus, &cpus);
  return cpus;
}

TEST(RealTimeSetup, TheLoopIsPinnedToItsCpuAndOnlyToIt) {
  const cpu_set_t before = allowed();
  for (int cpu = 0; cpu < CPU_SETSIZE; ++cpu) {
    if (!CPU_ISSET(cpu, &before)) continue;
    // On a thread of its own: the test's other threads keep every CPU.
    std::thread([cpu] {
      const RealTimeSetupReport report = apply_realtime(pin_only(cpu));
      EXPECT_EQ(report.pinned_cpu, cpu);
      EXPECT_EQ(report.refused, "");
      const cpu_set_t now = allowed();
      EXPECT_EQ(CPU_COUNT(&now), 1);
      EXPECT_TRUE(CPU_ISSET(cpu, &now));
      EXPECT_EQ(sched_getcpu(), cpu);
    }).join();
  }
}

TEST(RealTimeSetup, AnUnpinnedLoopKeepsEveryCpu) {
  const cpu_set_t before = allowed();
  std::thread([&before] {
    const RealTimeSetupReport report = apply_realtime(pin_only(-1));
    EXPECT_EQ(report.pinned_cpu, -1);
    const cpu_set_t now = allowed();
    EXPECT_TRUE(CPU_EQUAL(&now, &before));
  }).join();
}

TEST(RealTimeSetup, ACpuTheHostLacksIsARefusalNotAFailure) {
  std::thread([] {
    const RealTimeSetupReport report = apply_realtime(pin_only(CPU_SETSIZE - 1));
    EXPECT_EQ(report.pinned_cpu, -1);
    EXPECT_NE(report.refused.find("pinning the loop to CPU " + std::to_string(CPU_SETSIZE - 1) + " refused"),
              std::string::npos)
        << report.refused;
  }).join();
}

TEST(RealTimeSetup, ACpuBeyondAnyHostIsAProgrammingError) {
  EXPECT_THROW(apply_realtime(pin_only(CPU_SETSIZE)), std::invalid_argument);
  EXPECT_THROW(apply_realtime(pin_only(-2)), std::invalid_argument);
}

}  // namespace
}  // namespace rpsd::realtime
