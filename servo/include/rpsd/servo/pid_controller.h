// A discrete PID controller for a servo loop, acting on the tracking error
// e = target - measured once per control period T:
//   C(s) = Kp + Ki / s + Kd s / (Tf s + 1)
// discretised by Tustin, s = (2 / T)(z - 1)/(z + 1), so that its frequency response is C at
// the warped s = j (2 / T) tan(w T / 2). The output is limited to the converter's range, and
// the integral is clamped (conditional integration) while the limit holds it back.
#pragma once

namespace rpsd::servo {

struct PidGains {
  double proportional = 0.0;              // Kp, output units per error unit
  double integral_per_s = 0.0;            // Ki, output units per error unit per second
  double derivative_s = 0.0;              // Kd, output units per error unit per (1/s)
  double derivative_filter_time_s = 0.0;  // Tf; 0 only without derivative action

  // Throws std::invalid_argument naming the key: a negative or non-finite value, a derivative
  // without its filter, or no gain at all.
  void validate() const;
};

class PidController {
 public:
  // Validates the gains and the period (positive, finite). With derivative action the filter
  // time must be at least period_s / 2: below it the Tustin pole (2 Tf - T)/(2 Tf + T) turns
  // negative and the derivative alternates sign from sample to sample, a ringing at the
  // Nyquist frequency. Starts at rest with zero output. Not real-time safe (it may throw).
  PidController(const PidGains& gains, double period_s);

  // One control period: the new error and the output's limits (the converter's range;
  // -inf / +inf when none). Returns the limited output. A non-finite error, or limits that
  // are NaN or out of order, give NaN and lose the state: every later output is NaN until
  // reset(), so that a fault is never limited into a finite command. Real-time safe.
  double update(double error, double output_min, double output_max);

  // At rest holding held_output: the integral carries it, the error history and the
  // derivative are zero. Real-time safe.
  void reset(double held_output);

  bool saturated() const { return saturated_; }  // the last output was limited
  double integral() const { return integral_; }  // the integral term I_k, output units
  double period_s() const { return period_s_; }

 private:
  PidGains gains_;
  double period_s_;
  double integral_step_;    // Ki T / 2
  double derivative_pole_;  // (2 Tf - T) / (2 Tf + T)
  double derivative_gain_;  // 2 Kd / (2 Tf + T)
  double integral_ = 0.0;
  double derivative_ = 0.0;
  double previous_error_ = 0.0;
  bool saturated_ = false;
};

}  // namespace rpsd::servo
