// A plant that can also be driven in force control (mixed control, issue 30): its controller's
// error is then the force command less the load cell's force. A plant is one when it derives
// from this interface besides servo::Plant; SimulatedActuator finds out when it is built, and a
// channel of any other plant cannot be put in force control.
#pragma once

namespace rpsd::servo {

class ForceControlledPlant {
 public:
  virtual ~ForceControlledPlant() = default;

  // Advances the plant by duration_s in force control while the force command moves linearly
  // from force_start_n to force_end_n (a first-order hold, as Plant::advance). Real-time safe.
  virtual void advance_in_force(double force_start_n, double force_end_n, double duration_s) = 0;

  // False when the plant's parameters give it no force loop (no gain). Not real-time safe.
  virtual bool controls_force() const { return true; }
};

}  // namespace rpsd::servo
