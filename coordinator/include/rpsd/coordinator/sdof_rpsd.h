// An RPsD test of an elastic SDOF whose whole stiffness is the specimen's: the paper's
// Figure 8 experiment. The mass and viscous damping are numerical; the restoring force is
// the specimen stiffness times the measured displacement (or the measured force). One
// actuator, a plant behind the in-process link, any integrator and compensator.
// Not real-time safe as a whole (it builds the parts); the loop inside is.
#pragma once

#include <filesystem>
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
};

struct SdofRpsdResult {
  std::vector<StepRecord> records;
  StepOutcome outcome = StepOutcome::kOk;
  bool aborted_on_amplitude = false;
  std::uint64_t dropped_records = 0;
};

/// Runs the test with `plant` as the actuator; `csv` (optional) receives every step.
SdofRpsdResult run_sdof_rpsd(const SdofRpsdSetup& setup, servo::Plant& plant, const std::filesystem::path& csv = {});

}  // namespace rpsd::coordinator
