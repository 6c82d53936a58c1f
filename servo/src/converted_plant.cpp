#include "rpsd/servo/converted_plant.h"

#include <limits>
#include <stdexcept>

namespace rpsd::servo {

ConvertedPlant::ConvertedPlant(std::unique_ptr<Plant> plant, const ChannelConverters& converters, Output output)
    : plant_(std::move(plant)),
      output_(output),
      command_limit_(converters.command.saturation_v > 0.0
                         ? converters.command.saturation_v * converters.command.units_per_volt
                         : std::numeric_limits<double>::infinity()),
      command_(converters.command),
      displacement_(converters.displacement),
      force_(converters.force) {
  if (!plant_) throw std::invalid_argument("ConvertedPlant: no plant");
  converters.validate();
  reset(0.0);
}

void ConvertedPlant::read_sensors(bool command_saturated) {
  const PlantMeasurement m = plant_->measure();
  measured_ = {displacement_.convert(m.displacement_m), force_.convert(m.force_n), m.at_end_stop,
               m.valve_saturated || command_saturated};
}

void ConvertedPlant::reset(double displacement_m) {
  plant_->reset(displacement_m);
  command_.reseed();
  displacement_.reseed();
  force_.reseed();
  last_command_m_ = displacement_m;
  read_sensors(false);
}

void ConvertedPlant::advance(double, double command_end_m, double duration_s) {
  const double command = command_.convert(command_end_m);
  plant_->advance(output_ == Output::kHold ? command : last_command_m_, command, duration_s);
  last_command_m_ = command;
  read_sensors(command_.saturated());
}

}  // namespace rpsd::servo
