// The test's experimental setups (TestConfig::setups) turned into what the loop and the sites
// need: each setup's group for the exchange (its geometry, channels, where compensation acts,
// its actuators' limits within the rig's envelope), where each actuator rests (the strokes of
// the initial configuration), the stiffness each actuator's force guard predicts with, and
// the calibration of each actuator's reading against the stroke the geometry predicts.
// Not real-time safe.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/coordinator/setup_group.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"

namespace rpsd::hybrid_test {

// An actuator's reading at the start is further from the stroke the geometry predicts than
// experimental_setups[].max_calibration_offset_m: the rig is not where the file says, and
// the run does not start (summary result not_ready, exit 4).
class CalibrationOutOfRange : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One setup's calibration, for the summary.
struct SetupCalibration {
  std::uint32_t site_id = 1;
  std::vector<std::string> actuators;  // names ("actuator 2" when unnamed)
  std::vector<int> channels;
  std::vector<double> reference_length_m, predicted_stroke_m, reading_m, offset_m;
  bool measured = true;  // false: a site with no reading before the first feedback; offsets zero
  // Each actuator's load cell at rest, the start of the DOFs' restoring forces; measured false:
  // some are the stiffness estimate times the hold (a node that has read nothing yet).
  std::vector<double> force_at_rest_n;
  bool force_at_rest_measured = true;
};

struct SetupPlan {
  std::vector<coordinator::SetupGroup> groups;  // calibration offsets still zero
  // Per channel of the test: where its actuator rests (a setup's channels: the strokes of
  // the initial DOF targets), and the specimen stiffness its node's force guard predicts
  // with (a setup's channels: the diagonal of J⁻ᵀ K J⁻¹, K the DOFs' estimates).
  std::vector<double> hold_m, stiffness_estimate_n_per_m;
  std::vector<bool> in_setup;  // per channel
};

// `dof_hold_m`: each channel's target at the initial displacement (specimen scale). Without
// setups, hold and stiffness are the channels' own. std::invalid_argument naming
// experimental_setups[i] for a setup that does not fit the test. The reference
// (perfect_actuator) keeps the geometry without limits.
SetupPlan plan_setups(const TestConfig& test, const Eigen::VectorXd& dof_hold_m, double control_period_s,
                      bool perfect_actuator);

// Sets each group's offsets from the actuators' readings at the start (per channel; nullopt:
// not measured, offset zero) and returns them for the summary; throws CalibrationOutOfRange
// naming the site, the actuator, its offset and the limit.
std::vector<SetupCalibration> calibrate_setups(const TestConfig& test, SetupPlan& plan,
                                               const std::vector<std::optional<double>>& readings_m);

}  // namespace rpsd::hybrid_test
