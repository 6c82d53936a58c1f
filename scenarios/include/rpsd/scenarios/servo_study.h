// Typed scenarios for the servo-system studies of the seed paper (Figures 5, 6 and 7).
// A study file names its kind with `study:` and the rig with `servo:` (a parameter file,
// relative to the study file). See scenarios/paper-fig*.yaml.
#pragma once

#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "rpsd/compensation/phase_lead.h"
#include "rpsd/servo/servo_parameters.h"

namespace rpsd::scenarios {

/// Figure 5: a predetermined linear sine sweep through the nonlinear plant.
struct SineSweepStudy {
  servo::ServoSystemParameters servo;
  double amplitude_m = 0.0127;
  double start_frequency_hz = 0.0;
  double end_frequency_hz = 10.0;
  double duration_s = 60.0;
  double command_rate_hz = 1024.0;               ///< command samples per second
  std::vector<double> report_frequencies_hz{1.0, 2.0, 5.0};
};

/// Figure 6: frequency responses of Eq. 8, Eq. 9 and the phase-lead compensated system.
struct FrequencyResponseStudy {
  servo::ServoSystemParameters servo;
  std::vector<double> frequencies_hz;            ///< log-spaced from the file's range
  compensation::PhaseLeadParameters phase_lead;
};

/// Figure 7: largest stable P gain against the attached mass.
struct MaxGainStudy {
  servo::ServoSystemParameters servo;
  std::vector<double> masses_kg;                 ///< log-spaced from the file's range
};

using ServoStudy = std::variant<SineSweepStudy, FrequencyResponseStudy, MaxGainStudy>;

struct ServoStudyFile {
  std::string name;         ///< the file's stem, for titles
  std::string description;  ///< optional `description:` text
  ServoStudy study;
};

/// Reads a study file; every error names file, line, column and key path. Not real-time safe.
ServoStudyFile load_servo_study(const std::filesystem::path& file);

/// `points` values from start to stop, equally spaced in log10. Both must be positive.
std::vector<double> log_spaced(double start, double stop, int points);

}  // namespace rpsd::scenarios
