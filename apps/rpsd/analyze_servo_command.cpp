#include <iomanip>
#include <iostream>
#include <memory>

#include "rpsd/commands.h"
#include "rpsd/commands/analysis_reports.h"
#include "rpsd/scenarios/servo_parameters_file.h"
#include "rpsd/servo/linear_analysis.h"

namespace rpsd::cli {
namespace {

struct AnalyzeServoOptions {
  std::string file;
  bool json = false;
};

void print_table(const std::string& name, const servo::ServoAnalysis& a) {
  std::cout << "servo system: " << name << '\n' << std::fixed;
  const auto row = [](const char* label, double value, const char* unit, int digits) {
    std::cout << "  " << std::left << std::setw(44) << label << std::right << std::setw(12) << std::setprecision(digits)
              << value << ' ' << unit << '\n';
  };
  row("cut-off frequency f_c (Eq. 9)", a.cutoff_frequency_hz, "Hz", 3);
  row("response delay T_d = 1/omega_c (Eq. 12)", a.response_delay_ms, "ms", 2);
  row("amplitude reduction at 2 Hz (Eq. 10)", 100.0 * a.amplitude_reduction_at_2hz, "%", 2);
  row("oil-column frequency (Eq. 11)", a.oil_column_frequency_hz, "Hz", 2);
  row("static gain of Eq. 8", a.static_gain, "", 5);
  row("P gain", a.p_gain, "V/V", 4);
  row("max stable P gain, Routh on Eq. 8", a.max_stable_p_gain, "V/V", 4);
  row("max stable P gain, eigenvalues, full model", a.max_stable_p_gain_full_model, "V/V", 4);
  row("specimen natural frequency", a.specimen_natural_frequency_hz, "Hz", 3);
  row("servovalve spool-loop frequency", a.servovalve_natural_frequency_hz, "Hz", 2);
  row("servovalve spool-loop damping ratio", a.servovalve_damping_ratio, "", 3);
}

}  // namespace

void add_analyze_servo(CLI::App& analyze) {
  auto options = std::make_shared<AnalyzeServoOptions>();
  analyze.add_option("servo_parameters", options->file, "Servo-system parameter file (YAML)")->check(CLI::ExistingFile);
  analyze.add_flag("--json", options->json, "Print JSON instead of a table");
  analyze.callback([&analyze, options] {
    if (!analyze.get_subcommands().empty()) return;  // an analyze subcommand ran instead
    if (options->file.empty()) throw CLI::RequiredError("servo_parameters (or an analyze subcommand)");
    if (options->json) {
      std::cout << commands::servo_analysis_json(options->file).dump(2) << '\n';
      return;
    }
    const auto parameters = scenarios::load_servo_parameters(options->file);
    print_table(parameters.name, servo::analyze(parameters));
  });
}

}  // namespace rpsd::cli
