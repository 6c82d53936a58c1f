// The seed paper's Figure 8 study: RPsD free vibration of an elastic SDOF with a phase-lead
// compensator swept over compensated delays, each case's effective damping identified from
// the response and set against delay theory. Not real-time safe (it runs whole tests).
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "rpsd/studies/study_config.h"

namespace rpsd::studies {

struct DelayCompensationCase {
  double compensated_delay_s = 0.0;  // design value: (a - 1) T of the phase lead
  double actuator_delay_s = 0.0;     // phase delay of the actuator at omega_n
  double compensator_lead_s = 0.0;   // phase lead of the discrete network at omega_n
  double residual_delay_s = 0.0;     // actuator delay - compensator lead (negative: over)
  double identified_damping_ratio = 0.0;
  double identified_frequency_hz = 0.0;
  double predicted_damping_ratio = 0.0;       // exact root of m s^2 + c s + k e^{-s tau}
  double approximate_damping_ratio = 0.0;     // zeta - omega_n tau / 2
  double predicted_damping_ratio_loop = 0.0;  // root of m s^2 + c s + k G_c(s) G_a(s)
  bool stable = false;
  bool aborted_on_amplitude = false;
  std::string stopped_by;                    // the limit or run-away rule that ended an unstable case ("" if none did)
  double tracking_rms_error_percent = 0.0;   // J2 between target and measured
  double tracking_peak_error_percent = 0.0;  // J3
  double tracking_delay_s = 0.0;             // signed, interpolated cross-correlation lag (run_criteria.h)
  bool tracking_delay_at_window_edge = false;  // the lag search's edge: the true delay may lie beyond
  double energy_balance_error_j = 0.0;         // input - (kinetic + damping + restoring) at the end
  double final_tracking_indicator_m2 = 0.0;
  std::int64_t steps = 0;  // steps taken (fewer when aborted on amplitude)
};

// Runs every case; `dir` (optional) receives one CSV per case.
std::vector<DelayCompensationCase> run_delay_compensation(const DelayCompensationStudy& study,
                                                          const std::filesystem::path& dir = {});

// The CSV name of case i.
std::string delay_case_csv_name(std::size_t index, double compensated_delay_s);

void write_delay_compensation(const std::filesystem::path& dir, const StudyDocument& file,
                              const DelayCompensationStudy& study, const std::vector<DelayCompensationCase>& cases);

}  // namespace rpsd::studies
