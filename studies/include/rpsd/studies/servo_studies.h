// Runs the servo-system studies of the seed paper (Figures 5, 6, 7) from their typed
// scenarios. Results are plain tables; study_output.h writes them. Not real-time safe.
#pragma once

#include <vector>

#include "rpsd/studies/study_config.h"

namespace rpsd::studies {

// Amplitude ratio and phase (degrees, negative = lag) of displacement over command.
struct Response {
  double amplitude_ratio = 0.0;
  double phase_deg = 0.0;
};

struct SweepComparison {
  double frequency_hz = 0.0;
  Response sweep;         // fitted over three cycles of the simulated sweep
  Response steady_state;  // simulated steady sine at the sweep amplitude (report rows only)
  Response eq8;           // paper's linear model
  Response full_linear;   // Eq. 8 with servovalve dynamics and D gain
  Response first_order;   // Eq. 9
};

struct SineSweepResult {
  std::vector<double> time_s, frequency_hz, command_m, displacement_m, force_n, spool_opening;
  std::vector<SweepComparison> report;  // at the study's report frequencies
  std::vector<SweepComparison> curve;   // every 0.25 Hz inside the sweep, for the plot
  double max_spool_opening = 0.0;
  double peak_force_n = 0.0;
};

SineSweepResult run_sine_sweep(const SineSweepStudy& study);

struct FrequencyResponseRow {
  double frequency_hz = 0.0;
  Response eq8, first_order, compensated, full_linear, full_linear_compensated;
};

std::vector<FrequencyResponseRow> run_frequency_response(const FrequencyResponseStudy& study);

struct MaxGainRow {
  double mass_kg = 0.0;
  double max_p_gain_routh = 0.0;       // Routh on Eq. 8
  double max_p_gain_full_model = 0.0;  // eigenvalues, servovalve dynamics included
  double oil_column_frequency_hz = 0.0;
};

std::vector<MaxGainRow> run_max_gain(const MaxGainStudy& study);

}  // namespace rpsd::studies
