// A servo controller closing its loop at the control rate around a plant given from the
// controller's output: the target's error against the measured displacement goes through a
// PID (pid_controller.h) whose output a D/A converter holds over the period; the plant's
// displacement and force come back through their sensors' A/D converters
// (signal_converter.h), and that measurement is both the controller's feedback and what
// the node reports. The RTHS benchmark's G_xu with its sample PI controller is one of these
// (docs/benchmark.md). Without a controller the command goes straight to the D/A.
#pragma once

#include <optional>
#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/converted_plant.h"
#include "rpsd/servo/envelope.h"
#include "rpsd/servo/pid_controller.h"
#include "rpsd/servo/plant.h"
#include "rpsd/servo/transfer_function_plant.h"

namespace rpsd::servo {

class FeedbackControlledPlant;

struct FeedbackControlledPlantParameters {
  using Model = FeedbackControlledPlant;
  static constexpr std::string_view kName = "feedback_controlled";
  static constexpr std::string_view kSummary =
      "a PID servo controller at the control rate around a plant from its output (a transfer function or the RTHS "
      "benchmark's G_xu), with D/A and A/D converters";
  static FeedbackControlledPlantParameters read(config::Source& section, double specimen_stiffness_n_per_m);

  TransferFunctionPlantParameters plant;  // from the controller's output u to x_m; its rig
  std::optional<PidGains> controller;     // none: the command goes to the D/A as it is
  ChannelConverters converters;

  // Throws std::invalid_argument naming the problem. Not real-time safe.
  void validate() const;
  // The controller at this control period (a derivative filter shorter than half a period
  // rings at the Nyquist frequency): std::invalid_argument naming it. Not real-time safe.
  void validate_for_period(double control_period_s) const;
  const Envelope& rig() const { return plant.rig; }
};

class FeedbackControlledPlant final : public Plant {
 public:
  // Not real-time safe.
  explicit FeedbackControlledPlant(const FeedbackControlledPlantParameters& parameters);

  // At rest holding displacement_m: the plant at the equilibrium of u = x / G_xu(0), the
  // integral carrying that u, the noise restarted from its seeds. Real-time safe.
  void reset(double displacement_m) override;
  // One control period: the controller acts on the target at its end (command_end_m, through
  // the reference converter) less the displacement measured at its start (through the error
  // converter), and its output is held for duration_s. Real-time safe.
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  // The converted readings; valve_saturated: the controller's output or its D/A at a limit.
  PlantMeasurement measure() const override;
  // Refuses a load from outside (plant.h's default): its load cell reads its transfer
  // function's own specimen behind the servo loop, which a coupled specimen cannot reach.

 private:
  FeedbackControlledPlantParameters parameters_;
  ConvertedPlant converted_;  // the plant behind the converters; the D/A holds with a controller
  std::optional<PidController> controller_;
  SignalConverter reference_, error_;  // the loop's own signals (pass-through unless stated)
  double holding_output_ = 0.0;        // the controller's output that holds the last reset
};

}  // namespace rpsd::servo
