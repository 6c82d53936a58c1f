// Builds against the installed rpsd::servo and rpsd::output and prints the paper rig's cut-off
// frequency for a parameter set written in code, also as a results CSV would write it.
#include <cstdio>
#include <string>

#include "rpsd/output/csv_number.h"
#include "rpsd/servo/linear_analysis.h"

int main() {
  rpsd::servo::ServoSystemParameters p;
  p.controller.proportional_gain = 0.798;
  p.servovalve = {1.421e-3, 6.8235e-6, 1.267e-4, 6666.67, 1.5e-3};
  p.flow.no_load_flow_gain_m3_per_s = 1.4766e-2;
  p.flow.supply_pressure_pa = 20.7e6;
  p.actuator = {7.536e-3, 1.95e-3, 1.3e9, 9.15e-12, 0.127};
  p.sensors.lvdt_gain_v_per_m = 78.74;
  p.specimen.mass_kg = 7080.0;
  p.specimen.stiffness.initial_n_per_m = 700.8e3;
  const double cutoff_hz = rpsd::servo::analyze(p).cutoff_frequency_hz;
  char csv[rpsd::output::kG10MaxChars];
  const std::string as_csv(csv, rpsd::output::format_g10(csv, cutoff_hz));
  std::printf("cutoff_frequency_hz %.3f (in a results CSV: %s)\n", cutoff_hz, as_csv.c_str());
  return 0;
}
