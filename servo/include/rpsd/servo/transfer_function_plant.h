// A plant given as a continuous transfer function from displacement command to measured
// displacement, e.g. the RTHS benchmark's identified actuator-specimen model. Realised in
// controllable canonical form, balanced by a diagonal similarity, and integrated with RK4 at
// a fixed internal rate with the command ramping linearly between samples.
#pragma once

#include <string_view>

#include "rpsd/config/source.h"
#include "rpsd/servo/channel_converters.h"
#include "rpsd/servo/envelope.h"

#include <Eigen/Core>

#include "rpsd/servo/plant.h"
#include "rpsd/servo/polynomial.h"

namespace rpsd::servo {

class TransferFunctionPlant;

struct TransferFunctionPlantParameters {
  using Model = TransferFunctionPlant;  // the Plant these parameters build
  static constexpr std::string_view kName = "transfer_function";
  static constexpr std::string_view kSummary =
      "a linear plant from command to displacement, given by its numerator and denominator in descending powers of s";
  static TransferFunctionPlantParameters read(config::Source& section, double specimen_stiffness_n_per_m);

  TransferFunction transfer_function;       // strictly proper or proper
  double specimen_stiffness_n_per_m = 0.0;  // the load cell reads k x_m
  double plant_rate_hz = 8192.0;
  Envelope rig;  // the measured displacement stops at +/- rig.stroke_m
  // The load cell adds c dx_m/dt + m a when the specimen has damping or mass (the benchmark's
  // c_e, m_e): dx_m/dt exact from the state, a the acceleration averaged over the last advance
  // (the change of that velocity over its length), as a load cell behind an anti-aliasing
  // filter reads it: a command ramping from sample to sample accelerates the specimen at the
  // corners, which an instantaneous value at the sample would miss. The transfer function must
  // roll off by at least two powers of s (three with mass).
  double specimen_damping_n_s_per_m = 0.0;
  double specimen_mass_kg = 0.0;
  ChannelConverters converters{};  // servo.converters (none unless stated)

  // Throws std::invalid_argument when improper, unstable, or too fast for the rate.
  void validate() const;
};

class TransferFunctionPlant final : public Plant {
 public:
  // Builds the state-space realisation. Not real-time safe.
  explicit TransferFunctionPlant(const TransferFunctionPlantParameters& parameters);

  // At rest, holding displacement_m: the equilibrium for the constant command
  // displacement_m / G(0). Real-time safe.
  void reset(double displacement_m) override;
  void advance(double command_start_m, double command_end_m, double duration_s) override;
  PlantMeasurement measure() const override;
  // The load cell reads the outside load too; the motion does not depend on it.
  bool accepts_external_load() const noexcept override { return true; }
  void set_external_load_n(double force_n) noexcept override { external_load_n_ = force_n; }

 private:
  TransferFunctionPlantParameters parameters_;
  Eigen::MatrixXd a_;
  Eigen::VectorXd b_, c_;
  Eigen::VectorXd c_velocity_;  // dx_m/dt = c_velocity' x
  double d_ = 0.0;
  Eigen::VectorXd x_, k1_, k2_, k3_, k4_, scratch_;
  double last_command_m_ = 0.0;
  double mean_acceleration_m_per_s2_ = 0.0;  // over the last advance
  double max_step_s_;
  double external_load_n_ = 0.0;
};

}  // namespace rpsd::servo
