// The effective damping ratio of a test's lowest mode, identified from its record as it runs
// (issue 31): per structure channel, the specimen force the test used is fitted by least
// squares as f = a x + b v + c against the channel's target displacement x and its
// central-difference velocity v. A lagging actuator shows as b < 0, the negative damping the
// delay theory predicts (b = -k sin(w tau) / w for a pure delay). Projected on the lowest mode
// (mass-normalised shape phi, phi_j^2 times the channel's scales), the mode's damping and
// stiffness become phi'C phi + sum w_j b_j and phi'K_N phi + sum w_j a_j, and the ratio
// their quotient over twice the square root (docs/telemetry.md). Off the loop: the
// telemetry publisher feeds it from the recorder's writer thread. Allocates only in configure().
#pragma once

#include <array>
#include <cstdint>
#include <limits>
#include <vector>

#include "rpsd/coordinator/step_record.h"
#include "rpsd/transport/messages.h"

namespace rpsd::telemetry {

// The lowest mode of the test's numerical model as the identification needs it, mass-normalised;
// filled before the run by the studies (they own the modal analysis). Unknown (NaN) where the
// record's channels are not the structure's DOFs one to one (experimental setups) or where no
// modal analysis exists (OpenSees sites).
struct LowestMode {
  double frequency_hz = std::numeric_limits<double>::quiet_NaN();
  double numerical_stiffness_n_per_m = std::numeric_limits<double>::quiet_NaN();  // phi'K_N phi
  double numerical_damping_n_s_per_m = std::numeric_limits<double>::quiet_NaN();  // phi'C phi
  // Per record channel: phi_j^2 x force scale x displacement scale at the channel's DOF.
  std::vector<double> channel_weight;

  bool known() const { return frequency_hz > 0.0 && !channel_weight.empty(); }
};

class EffectiveDampingIdentifier {
 public:
  // How many periods of the lowest mode must pass before a figure is given.
  static constexpr double kPeriodsBeforeIdentifying = 2.0;

  // Starts over for a run at control_rate_hz. Not real-time safe (copies the weights).
  void configure(const LowestMode& mode, double control_rate_hz);
  // Each step's record, in order.
  void observe(const coordinator::StepRecord& record) noexcept;
  // The identified damping ratio, or NaN: the mode unknown, too little record yet, or a
  // channel that has not moved enough to fit (its target constant, or its displacement and
  // velocity not independent).
  double damping_ratio() const noexcept;

 private:
  // Centred sums of one channel's fit, accumulated about the first sample (numerically stable
  // over long records).
  struct Sums {
    double n = 0, x = 0, v = 0, f = 0, xx = 0, xv = 0, vv = 0, fx = 0, fv = 0;
  };
  LowestMode mode_;
  double rate_hz_ = 0.0;
  std::int64_t steps_needed_ = 0;
  std::int64_t seen_ = 0;
  std::array<Sums, transport::kMaxChannels> sums_{};
  // The two previous targets and the previous force of each channel (the velocity is centred
  // on the previous step).
  std::array<double, transport::kMaxChannels> x_before_{}, x_previous_{}, f_previous_{}, origin_x_{}, origin_f_{};
};

}  // namespace rpsd::telemetry
