// Any plant behind a channel's converters: the command through the D/A (its ramp from one
// converted command to the next), the displacement and force through their A/D converters.
// A D/A at its limit counts as a fully open servovalve for the run-away guard.
#pragma once

#include <memory>

#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/plant.h"

namespace rpsd::servo {

class ConvertedPlant final : public Plant {
 public:
  // Not real-time safe.
  ConvertedPlant(std::unique_ptr<Plant> plant, const ChannelConverters& converters);

  // The plant at rest holding displacement_m; the noise restarts from its seeds. Real-time safe.
  void reset(double displacement_m) override;
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  PlantMeasurement measure() const override { return measured_; }
  const Plant& plant() const { return *plant_; }

 private:
  void read_sensors(bool command_saturated);

  std::unique_ptr<Plant> plant_;
  SignalConverter command_, displacement_, force_;
  double last_command_m_ = 0.0;  // the D/A's last output
  PlantMeasurement measured_;
};

}  // namespace rpsd::servo
