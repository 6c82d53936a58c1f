// Any plant behind a channel's converters: the command through the D/A, the displacement and
// force through their A/D converters. A D/A at its limit counts as a fully open servovalve for
// the run-away guard. The D/A's output ramps from one converted command to the next (a command
// to a servo controller's ramp generator), or holds each one over its period (a controller's
// own output to the servovalve: feedback_controlled_plant.h).
#pragma once

#include <memory>

#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/plant.h"

namespace rpsd::servo {

class ConvertedPlant final : public Plant {
 public:
  enum class Output { kRamp, kHold };

  // Not real-time safe.
  ConvertedPlant(std::unique_ptr<Plant> plant, const ChannelConverters& converters, Output output = Output::kRamp);

  // The plant at rest holding displacement_m; the noise restarts from its seeds. Real-time safe.
  void reset(double displacement_m) override;
  // command_start_m is not used: the ramp starts from the D/A's last output.
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  PlantMeasurement measure() const override { return measured_; }
  // The plant's own answer: the converters stand between it and the node, not the specimen.
  bool accepts_external_load() const noexcept override { return plant_->accepts_external_load(); }
  void set_external_load_n(double force_n) noexcept override { plant_->set_external_load_n(force_n); }
  const Plant& plant() const { return *plant_; }
  // The D/A's range in plant units (infinite without saturation).
  double command_limit() const { return command_limit_; }

 private:
  void read_sensors(bool command_saturated);

  std::unique_ptr<Plant> plant_;
  Output output_;
  double command_limit_;
  SignalConverter command_, displacement_, force_;
  double last_command_m_ = 0.0;  // the D/A's last output
  PlantMeasurement measured_;
};

}  // namespace rpsd::servo
