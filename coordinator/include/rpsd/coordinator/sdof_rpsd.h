// An RPsD test of an elastic SDOF whose whole stiffness is the specimen's: the paper's
// Figure 8 experiment. The mass and viscous damping are numerical; the restoring force is
// the specimen stiffness times the measured displacement (or the measured force). One
// actuator, a plant behind the in-process link, any integrator and compensator.
// Not real-time safe as a whole (it builds the parts); the loop inside is.
#pragma once

#include <filesystem>
#include <functional>
#include <memory>
#include <vector>

#include "rpsd/compensation/compensator_factory.h"
#include "rpsd/coordinator/rpsd_loop.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/servo/plant.h"

namespace rpsd::coordinator {

struct SdofRpsdSetup {
  double mass_kg = 7080.0;
  double damping_ratio = 0.011;
  double stiffness_n_per_m = 700.8e3;
  double initial_displacement_m = 0.01;
  double dt_s = 1.0 / 1024.0;
  double duration_s = 10.0;
  /// The test stops early when the response exceeds this multiple of the initial
  /// displacement (an unstable case is then plainly unstable).
  double abort_amplitude_factor = 5.0;
  integrators::IntegratorConfig integrator = integrators::CentralDifferenceParams{};
  compensation::CompensatorConfig compensator = compensation::PassThroughParameters{};
  RestoringForcePath::Kind force_path = RestoringForcePath::Kind::kStiffnessTimesMeasuredDisplacement;
  /// Ground acceleration at t = n dt (F = -m a_g); empty for free vibration. The test then
  /// ends with the record.
  std::vector<double> ground_acceleration_m_per_s2;
  /// Keep every step record in memory for finish() (the Figure 8 study needs them).
  bool keep_records = true;
  /// Optional: a link placed between the loop and the in-process plant node (a network
  /// emulation that delays or loses feedback), built around the in-process link.
  std::function<std::unique_ptr<transport::Link>(transport::Link& in_process)> network;
  /// See LoopParts::max_feedback_age_periods (0: lock-step).
  int max_feedback_age_periods = 0;
};

struct SdofRpsdResult {
  std::vector<StepRecord> records;
  StepOutcome outcome = StepOutcome::kOk;
  bool aborted_on_amplitude = false;
  std::uint64_t dropped_records = 0;
};

/// The assembled test: build (not real-time safe), then step() as often as wanted.
class SdofRpsdTest {
 public:
  /// Builds every part and starts at rest at the initial displacement. Throws
  /// std::invalid_argument on inconsistent settings.
  SdofRpsdTest(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv = {});
  ~SdofRpsdTest();
  /// One integration step. Real-time safe.
  StepOutcome step();
  /// Displacement of the numerical DOF now.
  double displacement_m() const;
  /// The record of the last step. Real-time safe.
  const StepRecord& last_record() const;
  /// Stops the recorder and returns what was recorded. Not real-time safe.
  std::vector<StepRecord> finish();
  std::uint64_t dropped_records() const;

 private:
  struct Parts;
  std::unique_ptr<Parts> parts_;
};

/// Runs the test for its duration; `csv` (optional) receives every step.
SdofRpsdResult run_sdof_rpsd(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv = {});

}  // namespace rpsd::coordinator
