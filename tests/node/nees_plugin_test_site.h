// What the plugin adapter's tests share: an emulated site on 127.0.0.1 whose actuators follow
// their command exactly (ideal delay 0: the measurement is the proposal), served on its own
// thread, and an adapter configured for it.
#pragma once

#include <array>
#include <atomic>
#include <memory>
#include <thread>
#include <vector>

#include "rpsd/node/nees_plugin_actuator.h"
#include "rpsd/node/nees_plugin_site_emulator.h"
#include "rpsd/servo/pure_delay_plant.h"

namespace rpsd::node::testing {

// One control point, MDL-00-01, its x axis in mm and kN within +/-40 mm.
inline PluginSiteConfig one_point_site() {
  PluginSiteConfig site;
  site.control_points = {{"MDL-00-01", {{"x", "translation", -40.0, 40.0, 1000.0, 0.001}}}};
  return site;
}

// The site's dofs, each an ideal actuator (delay_s later, 0 by default) on a spring of its own.
class EmulatedSite {
 public:
  explicit EmulatedSite(const PluginSiteConfig& config, std::vector<double> stiffness_n_per_m = {},
                        double delay_s = 0.0) {
    for (int d = 0; d < config.channels(); ++d) {
      const double k = d < static_cast<int>(stiffness_n_per_m.size()) ? stiffness_n_per_m[d] : 700.8e3;
      plants_.push_back(std::make_unique<servo::PureDelayPlant>(servo::PureDelayParameters{delay_s, k, 8192.0, {}}));
      pointers_.push_back(plants_.back().get());
    }
    emulator_ = std::make_unique<PluginSiteEmulator>(pointers_, config);
    emulator_->start(std::vector<double>(pointers_.size(), 0.0));
  }
  PluginSiteEmulator& emulator() { return *emulator_; }

 private:
  std::vector<std::unique_ptr<servo::Plant>> plants_;
  std::vector<servo::Plant*> pointers_;
  std::unique_ptr<PluginSiteEmulator> emulator_;
};

// The adapter for a site on 127.0.0.1, one channel per entry of `map`.
inline NeesPluginParameters plugin_adapter_config(const PluginSiteEmulator& site, std::vector<NeesPluginChannel> map) {
  NeesPluginParameters config;
  config.channels = static_cast<int>(map.size());
  config.host = "127.0.0.1";
  config.port = site.port();
  config.local_host = "127.0.0.1";
  config.channel_map = std::move(map);
  config.reply_timeout_s = 10.0;  // generous: a loaded machine must not turn into a fault
  config.rig = {0.127, 156.0e3, 0.3};
  return config;
}

inline std::vector<NeesPluginChannel> mdl_x_in_mm_and_kn() {
  return {{"MDL-00-01", nees_plugin::Axis::kX, nees_plugin::Motion::kTranslation, 1000.0, 0.001}};
}

// Serves the site on its own thread until destroyed.
class ServingSite {
 public:
  explicit ServingSite(PluginSiteEmulator& site)
      : thread_([this, &site] {
          while (!stop_.load()) site.serve(0.01);
        }) {}
  ~ServingSite() {
    stop_.store(true);
    thread_.join();
  }
  ServingSite(const ServingSite&) = delete;
  ServingSite& operator=(const ServingSite&) = delete;

 private:
  std::atomic<bool> stop_{false};
  std::thread thread_;
};

}  // namespace rpsd::node::testing
