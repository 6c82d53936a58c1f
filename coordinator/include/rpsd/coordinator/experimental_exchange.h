// One exchange with the experimental sites: the targets of every channel go through its
// compensator and the coordinator's limits, out over the link, and the measurement comes back
// checked (node faults, non-finite values, run-aways, the force limit) and turned into the
// specimens' restoring forces. The RPsD loop runs one per integrator iteration; `rpsd
// site-server` runs one per trial displacement OpenSees sends. Configured once, then
// exchange() is real-time safe: no allocation, no locks, no exceptions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "rpsd/compensation/command_compensator.h"
#include "rpsd/compensation/tracking_indicator.h"
#include "rpsd/coordinator/coordinator_limits.h"
#include "rpsd/coordinator/restoring_force.h"
#include "rpsd/coordinator/step_outcome.h"
#include "rpsd/coordinator/step_record.h"
#include "rpsd/transport/link.h"

namespace rpsd::coordinator {

struct ExchangeParts {
  transport::Link* link = nullptr;
  std::vector<compensation::CommandCompensator*> compensators;  // one per channel, configured
  std::vector<RestoringForcePath> force_paths;                  // one per channel
  std::uint32_t test_id = 1;
  std::uint64_t run_id = 0;  // 0: drawn here
  // Lock-step (0): every exchange needs the feedback of its own command. Real time (> 0): a
  // feedback at most this many control periods old stands in for a late one (counted).
  int max_feedback_age_periods = 0;
  std::vector<CoordinatorLimits> limits;  // per channel, or empty: none
  bool stop_on_node_limits = false;
  int max_valve_saturation_exchanges = 0;  // 0: not checked
};

class ExperimentalExchange {
 public:
  // Checks the parts fit together (std::invalid_argument naming the mismatch). Not real-time safe.
  explicit ExperimentalExchange(ExchangeParts parts);

  int channels() const { return channels_; }
  std::uint64_t run_id() const { return command_.run_id; }

  // At rest: the actuators hold `targets` (specimen scale), the specimens carry `forces`.
  // Resets compensators and indicators. Not real-time safe.
  void start(const Eigen::VectorXd& targets, std::span<const double> specimen_force_n);

  // Commands the channels toward `targets` (specimen scale) at test time `time_s` and takes
  // the measurement. kOk: specimen_forces() holds this exchange's restoring forces. Otherwise
  // nothing more may be sent; limit_stop() says which limit when one acted. Real-time safe.
  StepOutcome exchange(const Eigen::VectorXd& targets, double time_s);

  const Eigen::VectorXd& specimen_forces() const { return specimen_forces_; }
  const transport::CommandSample& command() const { return command_; }
  const transport::FeedbackSample& feedback() const { return feedback_; }
  const LimitStop& limit_stop() const { return limit_stop_; }
  std::int64_t exchanges() const { return exchange_; }
  // Real time: exchanges answered by an older measurement, and the age of the last one's.
  std::int64_t late_feedback_total() const { return late_total_; }
  std::int64_t feedback_age_periods() const { return feedback_age_; }

  // The channels' part of a step record (targets, commands, measurements, forces, tracking,
  // round trips). Real-time safe.
  void fill_channels(StepRecord& r) const;

 private:
  bool commands_within_limits();  // fills limit_stop_ when not
  StepOutcome run_away();         // kOk, or kRunAway with limit_stop_ filled

  ExchangeParts parts_;
  int channels_ = 0;
  Eigen::VectorXd targets_, specimen_forces_;
  std::vector<compensation::TrackingIndicator> tracking_;
  transport::CommandSample command_;
  transport::FeedbackSample feedback_;
  std::int64_t exchange_ = 0;
  std::int64_t late_total_ = 0;
  std::int64_t feedback_age_ = 0;
  LimitStop limit_stop_;
  std::array<double, transport::kMaxChannels> last_sent_m_{};
  int saturated_exchanges_ = 0;
};

}  // namespace rpsd::coordinator
