// What the Speedgoat link's tests share: an emulated target whose plants are perfect (each
// channel measures its target at the end of a move; the load cell reads 1e5 N/m times that),
// an adapter configured for it on 127.0.0.1 in millimetres and kilonewtons, and a thread
// serving the emulator.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "rpsd/node/speedgoat_actuator.h"
#include "rpsd/node/speedgoat_emulator.h"
#include "rpsd/servo/pure_delay_plant.h"

namespace rpsd::node::testing {

inline SpeedgoatEmulatorConfig target_config(bool udp, int channels = 1) {
  SpeedgoatEmulatorConfig c;
  c.udp = udp;
  for (int ch = 0; ch < channels; ++ch) {
    c.control.push_back({ch, "displacement", 1000.0});
    c.daq.push_back({ch, "displacement", 1000.0});
    c.daq.push_back({ch, "force", 1e-3});
  }
  return c;
}

inline SpeedgoatParameters node_config(std::uint16_t target_port, bool udp, int channels = 1) {
  SpeedgoatParameters p;
  p.channels = channels;
  p.transport = udp ? SpeedgoatTransport::kUdp : SpeedgoatTransport::kTcp;
  p.host = "127.0.0.1";
  p.port = target_port;
  p.local_host = "127.0.0.1";
  p.signals.control.clear();
  for (int ch = 0; ch < channels; ++ch) {
    p.signals.control.push_back(
        {ch, speedgoat::ControlQuantity::kDisplacement, 1000.0, speedgoat::Reference::kAbsolute});
    p.signals.daq.push_back({ch, speedgoat::DaqQuantity::kDisplacement, 1000.0, speedgoat::Reference::kAbsolute});
    p.signals.daq.push_back({ch, speedgoat::DaqQuantity::kForce, 1e-3, speedgoat::Reference::kAbsolute});
  }
  p.reply_timeout_s = 2.0;  // generous: a loaded machine must not turn into a missed handshake
  p.start_timeout_s = 10.0;
  p.rig = {0.25, 1e6, 1.0};
  return p;
}

// Perfect plants behind an emulated target.
struct IdealTarget {
  explicit IdealTarget(const SpeedgoatEmulatorConfig& config) {
    const int channels = static_cast<int>(config.control.size());
    for (int ch = 0; ch < channels; ++ch) {
      owned.push_back(std::make_unique<servo::PureDelayPlant>(servo::PureDelayParameters{0.0, 1e5, 8192.0, {}}));
      plants.push_back(owned.back().get());
    }
    emulator = std::make_unique<SpeedgoatEmulator>(plants, config);
    const std::vector<double> zero(plants.size(), 0.0);
    emulator->start(zero);
  }
  std::vector<std::unique_ptr<servo::PureDelayPlant>> owned;
  std::vector<servo::Plant*> plants;
  std::unique_ptr<SpeedgoatEmulator> emulator;
};

// Serves the emulator on its own thread until destroyed.
class ServingTarget {
 public:
  explicit ServingTarget(SpeedgoatEmulator& emulator)
      : thread_([this, &emulator] {
          while (!stop_.load()) emulator.serve(0.01);
        }) {}
  ~ServingTarget() {
    stop_.store(true);
    thread_.join();
  }
  ServingTarget(const ServingTarget&) = delete;
  ServingTarget& operator=(const ServingTarget&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rpsd::node::testing
