// What a study file says, typed (scenarios/ reads it): the servo-system studies of the seed
// paper (Figures 5, 6 and 7), the RPsD delay-compensation study (Figure 8), or a whole test
// (hybrid_test::TestConfig) with an optional sweep or Monte Carlo batch (hybrid_test/hybrid_test_document.h).
#pragma once

#include <variant>
#include <vector>

#include "rpsd/compensation/phase_lead.h"
#include "rpsd/hybrid_test/hybrid_test_config.h"
#include "rpsd/hybrid_test/hybrid_test_document.h"
#include "rpsd/integrators/factory.h"
#include "rpsd/servo/pure_delay_plant.h"
#include "rpsd/servo/servo_parameters.h"

namespace rpsd::studies {

// Figure 5: a predetermined linear sine sweep through the nonlinear plant.
struct SineSweepStudy {
  servo::ServoSystemParameters servo;
  double amplitude_m = 0.0127;
  double start_frequency_hz = 0.0;
  double end_frequency_hz = 10.0;
  double duration_s = 60.0;
  double command_rate_hz = 1024.0;  // command samples per second
  std::vector<double> report_frequencies_hz{1.0, 2.0, 5.0};
};

// Figure 6: frequency responses of Eq. 8, Eq. 9 and the phase-lead compensated system.
struct FrequencyResponseStudy {
  servo::ServoSystemParameters servo;
  std::vector<double> frequencies_hz;  // log-spaced from the file's range
  compensation::PhaseLeadParameters phase_lead;
};

// Figure 7: largest stable P gain against the attached mass.
struct MaxGainStudy {
  servo::ServoSystemParameters servo;
  std::vector<double> masses_kg;  // log-spaced from the file's range
};

// Figure 8: an elastic SDOF released from an initial displacement in RPsD, its whole
// stiffness the specimen's (restoring force = k x measured), with a phase-lead compensator
// swept over compensated delays below, at and above the actuator's response delay.
struct DelayCompensationStudy {
  double mass_kg = 7080.0;
  double stiffness_n_per_m = 700.8e3;
  double damping_ratio = 0.011;
  double initial_displacement_m = 0.01;
  double control_rate_hz = 1024.0;  // integration step = control period
  double duration_s = 8.0;
  double abort_amplitude_factor = 10.0;
  integrators::IntegratorConfig integrator = integrators::CentralDifferenceParameters{};
  // The actuator: the seed paper's servo-hydraulic model, or an ideal pure delay.
  std::variant<servo::ServoSystemParameters, servo::PureDelayParameters> plant;
  double phase_lead_ratio_a = 5.0;
  std::vector<double> compensated_delays_s;
};

using Study =
    std::variant<SineSweepStudy, FrequencyResponseStudy, MaxGainStudy, DelayCompensationStudy, hybrid_test::TestConfig>;

// A study file: the test document's parts (name, provenance, sweep or Monte Carlo batch;
// hybrid_test/hybrid_test_document.h) and which study it holds (for a sweep: the first case).
struct StudyDocument : hybrid_test::TestDocument {
  Study study;
};

}  // namespace rpsd::studies
