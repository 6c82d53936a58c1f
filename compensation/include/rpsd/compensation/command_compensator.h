// The command compensator of one actuator channel: a filter from the target displacement
// that the integrator predicts to the displacement command sent to the servo node, run
// once per control step dt. Adaptive schemes also learn from the measured displacement.
//
// Call order per control step n (the coordinator loop):
//   u[n] = command(x_t[n]);   send u[n]; the plant moves over the step;
//   observe(x_t[n], x_m[n]);  x_m[n] measured at the end of that step.
// "Delay" throughout this module means the lag of x_m behind the command sequence in this
// pairing: a plant with x_m[n] = u[n - m] has a delay of m dt.
#pragma once

#include <string_view>

namespace rpsd::compensation {

class CommandCompensator {
 public:
  virtual ~CommandCompensator() = default;

  // Sizes every buffer and derives the discrete coefficients for control step dt_s, then
  // resets to rest at zero. Throws std::invalid_argument with the offending value if the
  // parameters do not fit dt_s. Not real-time safe.
  virtual void configure(double dt_s) = 0;

  // Puts the filter at rest holding initial_displacement_m (a constant target then gives a
  // constant command) and restarts any adaptation from its initial values. Requires
  // configure(). Real-time safe.
  virtual void reset(double initial_displacement_m) noexcept = 0;

  // The displacement command for this control step's target; call exactly once per step.
  // Real-time safe.
  virtual double command(double target_m) noexcept = 0;

  // The target of this step and the displacement measured at its end; call exactly once per
  // step, after command(). Adaptive schemes learn from it; the others ignore it.
  // Real-time safe.
  virtual void observe(double target_m, double measured_m) noexcept = 0;

  // The delay the compensator currently makes up for, seconds: its low-frequency time
  // advance (the design value, or the current estimate of an adaptive scheme).
  // Real-time safe.
  virtual double compensated_delay_s() const noexcept = 0;

  // Short stable identifier ("none", "phase_lead", ...), for records. Real-time safe.
  virtual std::string_view name() const noexcept = 0;
};

}  // namespace rpsd::compensation
