#include "rpsd/servo/feedback_controlled_plant.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "rpsd/servo/benchmark_transfer_system.h"

namespace rpsd::servo {
namespace {

// Control periods the controller is built for: the node's is fixed for a test, and a PID's
// Tustin coefficients depend on it.
constexpr double kPeriodTolerance = 1e-9;

PidGains read_pid_gains(config::Source& section) {
  using config::Number;
  PidGains g;
  g.proportional = section.number_or("proportional_gain", 0.0, Number::non_negative("", "Kp, m/m"));
  g.integral_per_s = section.number_or("integral_gain_per_s", 0.0, Number::non_negative("1/s", "Ki"));
  g.derivative_s = section.number_or("derivative_gain_s", 0.0, Number::non_negative("s", "Kd"));
  g.derivative_filter_time_s =
      section.number_or("derivative_filter_time_s", 0.0, Number::non_negative("s", "Tf of Kd s / (Tf s + 1)"));
  section.finish();
  return g;  // checked with the whole plant (validate)
}

}  // namespace

FeedbackControlledPlantParameters FeedbackControlledPlantParameters::read(config::Source& section,
                                                                          double specimen_stiffness_n_per_m) {
  FeedbackControlledPlantParameters p;
  const bool by_coefficients = section.has("numerator_descending") || section.has("denominator_descending");
  const auto benchmark = section.optional_section("rths_benchmark_model", "the benchmark's G_xu by its parameters");
  if (by_coefficients == static_cast<bool>(benchmark)) {
    section.fail_section(
        "give the plant either as numerator_descending/denominator_descending or as "
        "rths_benchmark_model, not both or neither");
  }
  if (benchmark) {
    const BenchmarkTransferSystem b = BenchmarkTransferSystem::read(*benchmark);
    p.plant.transfer_function = b.transfer_function();
    p.plant.specimen_stiffness_n_per_m = b.specimen_stiffness_n_per_m;
    p.plant.specimen_damping_n_s_per_m = b.specimen_damping_n_s_per_m;
    p.plant.specimen_mass_kg = b.specimen_mass_kg;
    p.plant.plant_rate_hz = section.number_or("plant_rate_hz", 32768.0,
                                              config::Number::between(1e3, 1e6, "Hz", "fixed-step integration rate"));
    p.plant.rig = Envelope::read(*section.section("rig", "what the simulated rig can do"));
  } else {
    p.plant = TransferFunctionPlantParameters::read(section, specimen_stiffness_n_per_m);
  }
  if (const auto c = section.optional_section("controller", "the servo controller's PID on the tracking error")) {
    p.controller = read_pid_gains(*c);
  }
  // Its `converters` are read with every plant's (read_plant_config).
  try {
    p.validate();
  } catch (const std::invalid_argument& e) {
    section.fail_section(e.what());
  }
  return p;
}

void FeedbackControlledPlantParameters::validate() const {
  plant.validate();
  if (controller) {
    try {
      controller->validate();
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("controller: ") + e.what());
    }
  }
  converters.validate();
  if (!controller && converters.any_in_loop()) {
    throw std::invalid_argument("converters: reference and error are a controller's signals: give a controller");
  }
}

void FeedbackControlledPlantParameters::validate_for_period(double control_period_s) const {
  if (!controller) return;
  try {
    (void)PidController(*controller, control_period_s);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(std::string("controller: ") + e.what());
  }
}

FeedbackControlledPlant::FeedbackControlledPlant(const FeedbackControlledPlantParameters& parameters)
    : parameters_(parameters),
      converted_(std::make_unique<TransferFunctionPlant>(parameters.plant), parameters.converters,
                 parameters.controller ? ConvertedPlant::Output::kHold : ConvertedPlant::Output::kRamp),
      reference_(parameters.converters.reference),
      error_(parameters.converters.error) {
  parameters_.validate();
  reset(0.0);
}

void FeedbackControlledPlant::reset(double displacement_m) {
  converted_.reset(displacement_m);
  reference_.reseed();
  error_.reseed();
  holding_output_ = displacement_m / parameters_.plant.transfer_function.static_gain();
  if (controller_) controller_->reset(holding_output_);
}

void FeedbackControlledPlant::advance(double command_start_m, double command_end_m, double duration_s) {
  if (!(duration_s > 0.0)) return;
  if (!parameters_.controller) {
    converted_.advance(command_start_m, command_end_m, duration_s);
    return;
  }
  if (!controller_ || std::abs(controller_->period_s() - duration_s) > kPeriodTolerance * duration_s) {
    // First period (or a new one): the controller is built for it. Only at the start of a
    // test, where the node's period is fixed; the files' readers checked the controller at
    // that period (validate_for_period).
    controller_.emplace(*parameters_.controller, duration_s);
    controller_->reset(holding_output_);
  }
  const double error = error_.convert(reference_.convert(command_end_m) - converted_.measure().displacement_m);
  const double u = controller_->update(error, -converted_.command_limit(), converted_.command_limit());
  converted_.advance(u, u, duration_s);
}

PlantMeasurement FeedbackControlledPlant::measure() const {
  PlantMeasurement m = converted_.measure();
  m.valve_saturated = m.valve_saturated || (controller_ && controller_->saturated());
  return m;
}

}  // namespace rpsd::servo
