// The plant seen by whoever commands the actuator: a continuous-time system advanced over
// one command interval at a time. Simulated plants (the seed paper's servo-hydraulic model,
// ideal delays, transfer functions) implement it; hardware adapters sit beside them.
#pragma once

namespace rpsd::servo {

// What the rig's sensors report: LVDT displacement and load-cell force; and whether the piston
// sits on an end stop or the servovalve is fully open.
struct PlantMeasurement {
  double displacement_m = 0.0;
  double force_n = 0.0;
  bool at_end_stop = false;
  bool valve_saturated = false;
};

class Plant {
 public:
  virtual ~Plant() = default;

  // Puts the plant at rest, holding the specimen at displacement_m. Real-time safe.
  virtual void reset(double displacement_m) = 0;

  // Advances the plant by duration_s while the displacement command moves linearly from
  // command_start_m to command_end_m (a first-order hold: the actuator controller sees a
  // continuous ramp, as a D/A converter followed by the controller's input filter would
  // give, rather than steps that the derivative gain would turn into spikes).
  // Real-time safe.
  virtual void advance(double command_start_m, double command_end_m, double duration_s) = 0;

  // The current sensor readings. Real-time safe.
  virtual PlantMeasurement measure() const = 0;
};

}  // namespace rpsd::servo
