// libFuzzer target: commands from the network into a servo node's controller. The input is
// read as a sequence of command samples with arbitrary fields (ids, runs, writers, ends of
// run, control periods, steps, channel counts, NaN and infinite displacements, control modes and
// forces: these channels are in displacement control, so a force mode must fault) interleaved with
// ticks and releases of the run. Whatever arrives, the actuator must only ever be commanded
// within the stroke, by at most the increment per tick, with finite values, and every command
// must be counted as accepted, dropped by one reason, or an end of run.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include "rpsd/node/servo_node_controller.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/simulated_actuator.h"

namespace node = rpsd::node;
namespace servo = rpsd::servo;
namespace transport = rpsd::transport;

namespace {

constexpr int kChannels = 2;
constexpr double kStroke = 0.025, kIncrement = 0.002, kVelocity = 0.5, kPeriod = 1.0 / 1024.0;

template <typename T>
T take(const std::uint8_t*& data, std::size_t& size) {
  T value{};
  const std::size_t n = size < sizeof(T) ? size : sizeof(T);
  std::memcpy(&value, data, n);
  data += n;
  size -= n;
  return value;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  node::ServoNodeConfig config;
  config.test_id = 7;
  config.site_id = 1;
  config.channels = kChannels;
  config.control_period_s = kPeriod;
  config.command_timeout_periods = 4;
  for (int c = 0; c < kChannels; ++c) config.limits[c] = {kStroke, kVelocity, 1e9, kIncrement};
  servo::PureDelayPlant a({0.0, 1e5, 8192.0, {}}), b({0.0, 1e5, 8192.0, {}});
  servo::Plant* plants[] = {&a, &b};
  servo::SimulatedActuator actuator(plants);
  node::ServoNodeController controller(config, actuator);
  const double start[kChannels] = {0.0, 0.0};
  controller.start(start);

  std::uint64_t commands = 0;
  double previous[kChannels] = {0.0, 0.0};
  transport::FeedbackSample feedback;
  while (size > 0) {
    const auto what = take<std::uint8_t>(data, size);
    if (what & 1u) {
      transport::CommandSample command;
      // Mostly the right ids, so the deeper checks are reached; the fuzzer picks the rest.
      command.test_id = (what & 2u) ? take<std::uint32_t>(data, size) : 7;
      command.site_id = (what & 4u) ? take<std::uint32_t>(data, size) : 1;
      command.step = take<std::int64_t>(data, size);
      command.time_s = take<double>(data, size);
      command.channels = (what & 8u) ? take<std::uint8_t>(data, size) : kChannels;
      for (int c = 0; c < kChannels; ++c) command.displacement_m[c] = take<double>(data, size);
      command.run_id = (what & 16u) ? take<std::uint64_t>(data, size) : 0x7e57;
      command.writer = (what & 32u) ? take<std::uint64_t>(data, size) : 1;
      command.end_of_run = (what & 64u) != 0;
      command.control_period_s = (what & 128u) ? take<double>(data, size) : kPeriod;
      const auto modes = take<std::uint8_t>(data, size);
      for (int c = 0; c < kChannels; ++c) {
        command.control_mode[c] = static_cast<std::uint8_t>((modes >> (2 * c)) & 3u);
        if (modes & 0x80u) command.force_n[c] = take<double>(data, size);
      }
      const bool faulted = controller.faulted();
      const node::CommandVerdict verdict = controller.accept(command);
      if (verdict == node::CommandVerdict::kModeMismatch && !controller.faulted()) __builtin_trap();
      if (verdict == node::CommandVerdict::kAccepted && (modes & 0x0fu) != 0) __builtin_trap();
      if (faulted && !controller.faulted()) __builtin_trap();
      ++commands;
    } else {
      if (what & 2u) controller.release_run();
      controller.tick(feedback);
      const auto applied = controller.command_m();
      for (int c = 0; c < kChannels; ++c) {
        if (!std::isfinite(applied[c]) || std::abs(applied[c]) > kStroke) __builtin_trap();
        if (std::abs(applied[c] - previous[c]) > kIncrement * (1.0 + 1e-12)) __builtin_trap();
        previous[c] = applied[c];
      }
    }
  }
  const auto& counters = controller.counters();
  if (counters.accepted + counters.dropped_total() + counters.dropped(node::CommandVerdict::kEndOfRun) != commands) {
    __builtin_trap();
  }
  return 0;
}
