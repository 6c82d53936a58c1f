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

  // Whether the plant can carry a load from outside: a share of a coupled specimen
  // (coupled_specimen_actuator.h) that its own specimen does not know of. Refused by default.
  virtual bool accepts_external_load() const noexcept { return false; }
  // The force the outside specimen opposes the piston with, N (positive: against a positive
  // stroke, as the plant's own spring k x), held until the next call; reset() puts the plant at
  // rest carrying it. The load cell reads it; a plant whose motion responds to its load (the
  // servo-hydraulic model) carries it in its specimen equation. Ignored by a plant that does
  // not accept one. Real-time safe.
  virtual void set_external_load_n(double /*force_n*/) noexcept {}
};

}  // namespace rpsd::servo
