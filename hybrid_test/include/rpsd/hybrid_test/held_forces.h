// The actuators that hold a force (TestConfig::held_forces, mixed control): their limits with
// the rig's defaults, whether a simulated plant can hold a force, and the coordinator's
// channel each becomes (coordinator/held_force.h). docs/held-forces.md.
#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include "rpsd/coordinator/held_force.h"
#include "rpsd/coordinator/step_record.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/servo/plant_factory.h"

namespace rpsd::hybrid_test {

// A held force's tracking error allowed by default: this share of the rig's force capacity
// (a proportional force loop holds its force to a few per cent, docs/servo-model.md).
inline constexpr double kDefaultHeldForceErrorShare = 0.10;

// The held force's limits with the rig's defaults: max_force_n the rig's force capacity,
// max_stroke_m its stroke, max_force_error_n kDefaultHeldForceErrorShare of its force capacity.
// A stated limit beyond the rig (max_force_error_n: beyond its force capacity), a limit that
// neither the file nor the rig makes finite, or |force_n| beyond max_force_n throws
// config::KeyError at "limits.<key>" or "force_n". Not real-time safe.
coordinator::HeldForceLimits held_force_limits(const HeldForce& held, const servo::Envelope& rig);

// Why a simulated plant cannot hold a force in this process (empty: it can): the node's own
// refusal of a force channel on a plant without a force loop. Not real-time safe.
std::string held_force_refusal(const servo::PlantConfig& plant);

// The simulated plant of a held force's channel in this process: the test's, pushing on the
// held force's specimen (specimen_stiffness_n_per_m) instead of the structure's. Not real-time safe.
servo::PlantConfig held_force_plant(const servo::PlantConfig& plant, double specimen_stiffness_n_per_m);

// "site 1 held force axial": how the summary, the dry run and a stop name it.
std::string held_force_label(const HeldForce& held);

// The time the ramp takes from the force at rest to the held force.
double held_force_ramp_s(const HeldForce& held, double force_at_rest_n);

// Held force k of the test as the coordinator takes it: its link channel
// (experimental.size() + k), its limits with the rig's defaults, its ramp from force_at_rest_n.
// Not real-time safe.
coordinator::HeldForceChannel held_force_channel(const TestConfig& test, std::size_t k, double force_at_rest_n);

// The link channel of held force k.
inline int held_force_link_channel(const TestConfig& test, std::size_t k) {
  return static_cast<int>(test.experimental.size() + k);
}

// What a run's records say of one held force: how well it was held once ramped, and how far
// its piston went (a soft or softening specimen takes stroke).
struct HeldForceStats {
  double ramp_s = 0.0;  // from its force at rest at its rate
  // The largest |force command - measured force| at or after the ramp's end; NaN when the run
  // stopped before it.
  double max_force_error_after_ramp_n = std::numeric_limits<double>::quiet_NaN();
  double min_measured_m = std::numeric_limits<double>::infinity();  // measured stroke's range
  double max_measured_m = -std::numeric_limits<double>::infinity();
  double last_measured_force_n = std::numeric_limits<double>::quiet_NaN();
  std::int64_t steps = 0;  // records seen
};

// Gathers HeldForceStats from each step's record as the run goes (StepRecord::held*), so that
// a run that keeps no records still reports them.
class HeldForceTracker {
 public:
  HeldForceTracker() = default;
  // Not real-time safe.
  explicit HeldForceTracker(const std::vector<coordinator::HeldForceChannel>& held);
  // Real-time safe: no allocation.
  void add(const coordinator::StepRecord& record);
  const std::vector<HeldForceStats>& stats() const { return stats_; }

 private:
  std::vector<HeldForceStats> stats_;
};

}  // namespace rpsd::hybrid_test
