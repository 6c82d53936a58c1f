// A channel's compensator as the exchange calls it on every step: the phase lead (the seed
// paper's kind and the examples') directly, a final class whose command is inlined; any other
// kind through CommandCompensator's virtual calls. Which one is found once, when the channel
// is built, so a step pays one predictable branch instead of two indirect calls.
#pragma once

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/discrete_phase_lead.h"

namespace rpsd::compensation {

class CompensatorCall {
 public:
  CompensatorCall() = default;
  // `compensator` must outlive this. Not real-time safe (a dynamic_cast).
  explicit CompensatorCall(CommandCompensator* compensator)
      : any_(compensator), phase_lead_(dynamic_cast<DiscretePhaseLeadCompensator*>(compensator)) {}

  // CommandCompensator::command and observe of the compensator. Real-time safe.
  double command(double target_m) noexcept {
    return phase_lead_ != nullptr ? phase_lead_->command(target_m) : any_->command(target_m);
  }
  void observe(double target_m, double measured_m) noexcept {
    if (phase_lead_ != nullptr) {
      phase_lead_->observe(target_m, measured_m);
    } else {
      any_->observe(target_m, measured_m);
    }
  }

 private:
  CommandCompensator* any_ = nullptr;
  DiscretePhaseLeadCompensator* phase_lead_ = nullptr;  // the same compensator when it is a phase lead
};

}  // namespace rpsd::compensation
