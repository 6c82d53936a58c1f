#include "rpsd/servo/transfer_function_plant.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include <stdexcept>
#include "substeps.h"

namespace rpsd::servo {

void TransferFunctionPlantParameters::validate() const {
  const auto& tf = transfer_function;
  if (tf.denominator.degree() < 1) throw std::invalid_argument("transfer function: denominator must have degree >= 1");
  if (tf.numerator.degree() > tf.denominator.degree())
    throw std::invalid_argument("transfer function: improper (numerator degree > denominator degree)");
  const Eigen::VectorXcd poles = tf.denominator.roots();
  if (poles.real().maxCoeff() >= 0.0) throw std::invalid_argument("transfer function: unstable or marginal pole");
  if (!(plant_rate_hz >= 1e3 && plant_rate_hz <= 1e6))
    throw std::invalid_argument("plant_rate_hz: must be from 1e3 to 1e6 Hz");
  rig.validate();
  // RK4's stability region reaches |lambda h| ~ 2.8 on the real axis; keep a margin.
  if (poles.cwiseAbs().maxCoeff() / plant_rate_hz > 1.0) {
    throw std::invalid_argument("plant_rate_hz: too low for the fastest pole of the transfer function");
  }
  if (!(specimen_stiffness_n_per_m >= 0.0))
    throw std::invalid_argument("specimen_stiffness_n_per_m: must be zero or positive");
  if (!(specimen_damping_n_s_per_m >= 0.0) || !(specimen_mass_kg >= 0.0))
    throw std::invalid_argument("specimen damping and mass: must be zero or positive");
  const int roll_off = tf.denominator.degree() - tf.numerator.degree();
  if (specimen_damping_n_s_per_m > 0.0 && roll_off < 2)
    throw std::invalid_argument("specimen_damping_n_s_per_m: the transfer function must roll off by s^2 or more");
  if (specimen_mass_kg > 0.0 && roll_off < 3)
    throw std::invalid_argument("specimen_mass_kg: the transfer function must roll off by s^3 or more");
}

TransferFunctionPlant::TransferFunctionPlant(const TransferFunctionPlantParameters& parameters)
    : parameters_(parameters), max_step_s_(1.0 / parameters.plant_rate_hz) {
  parameters_.validate();
  const Polynomial& den = parameters_.transfer_function.denominator;
  const Polynomial& num = parameters_.transfer_function.numerator;
  const int n = den.degree();
  const double lead = den.coefficient(n);
  // Controllable canonical form of N(s)/D(s) with D monic.
  a_ = Eigen::MatrixXd::Zero(n, n);
  a_.topRightCorner(n - 1, n - 1).setIdentity();
  for (int i = 0; i < n; ++i) a_(n - 1, i) = -den.coefficient(i) / lead;
  b_ = Eigen::VectorXd::Zero(n);
  b_[n - 1] = 1.0;
  d_ = num.coefficient(n) / lead;
  c_.resize(n);
  for (int i = 0; i < n; ++i) c_[i] = num.coefficient(i) / lead - d_ * den.coefficient(i) / lead;
  // Diagonal similarity so that the states have comparable magnitudes: state i scales with
  // omega^i, omega the geometric mean of the pole magnitudes.
  const double omega = std::pow(std::abs(den.coefficient(0) / lead), 1.0 / n);
  for (int i = 0; i < n; ++i) {
    const double s = std::pow(omega, i);  // x = S z with S = diag(omega^i)
    a_.row(i) /= s;
    a_.col(i) *= s;
    b_[i] /= s;
    c_[i] *= s;
  }
  // With CB = 0, y' = CAx.
  c_velocity_ = a_.transpose() * c_;
  for (auto* v : {&x_, &k1_, &k2_, &k3_, &k4_, &scratch_}) *v = Eigen::VectorXd::Zero(n);
  reset(0.0);
}

void TransferFunctionPlant::reset(double displacement_m) {
  const double static_gain = parameters_.transfer_function.static_gain();
  const double command = displacement_m / static_gain;
  x_ = -a_.partialPivLu().solve(b_ * command);
  last_command_m_ = command;
  mean_acceleration_m_per_s2_ = 0.0;
}

void TransferFunctionPlant::advance(double command_start_m, double command_end_m, double duration_s) {
  if (!(duration_s > 0.0)) return;
  const int substeps = detail::substeps(duration_s / max_step_s_);
  const double h = duration_s / substeps;
  const double slope = (command_end_m - command_start_m) / duration_s;
  const double velocity_before = c_velocity_.dot(x_);
  for (int i = 0; i < substeps; ++i) {
    const double u0 = command_start_m + slope * i * h;
    k1_.noalias() = a_ * x_;
    k1_ += b_ * u0;
    scratch_ = x_ + 0.5 * h * k1_;
    k2_.noalias() = a_ * scratch_;
    k2_ += b_ * (u0 + 0.5 * h * slope);
    scratch_ = x_ + 0.5 * h * k2_;
    k3_.noalias() = a_ * scratch_;
    k3_ += b_ * (u0 + 0.5 * h * slope);
    scratch_ = x_ + h * k3_;
    k4_.noalias() = a_ * scratch_;
    k4_ += b_ * (u0 + h * slope);
    x_ += (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  }
  last_command_m_ = command_end_m;
  mean_acceleration_m_per_s2_ = (c_velocity_.dot(x_) - velocity_before) / duration_s;
}

PlantMeasurement TransferFunctionPlant::measure() const {
  // A linear model has no end stops of its own: the rig's are applied to its output.
  const double y = c_.dot(x_) + d_ * last_command_m_;
  const double stroke = parameters_.rig.stroke_m;
  const double x = std::clamp(y, -stroke, stroke);
  const double force = parameters_.specimen_stiffness_n_per_m * x +
                       parameters_.specimen_damping_n_s_per_m * c_velocity_.dot(x_) +
                       parameters_.specimen_mass_kg * mean_acceleration_m_per_s2_ + external_load_n_;
  return {x, force, std::abs(y) >= stroke, false};
}

TransferFunctionPlantParameters TransferFunctionPlantParameters::read(config::Source& section,
                                                                      double specimen_stiffness_n_per_m) {
  // Coefficients in descending powers of s, as transfer functions are usually published; a
  // servo model needs no more than degree 8, and 1e30 bounds the coefficients of one whose
  // poles lie below the plant rate.
  constexpr std::size_t kMaxCoefficients = 9;
  auto numerator =
      section.numbers("numerator_descending", config::Number::between(-1e30, 1e30, "", "b_m ... b_0 of the numerator"),
                      kMaxCoefficients);
  auto denominator =
      section.numbers("denominator_descending",
                      config::Number::between(-1e30, 1e30, "", "a_n ... a_0 of the denominator"), kMaxCoefficients);
  std::reverse(numerator.begin(), numerator.end());
  std::reverse(denominator.begin(), denominator.end());
  TransferFunctionPlantParameters t;
  t.transfer_function = {
      Polynomial(Eigen::Map<Eigen::VectorXd>(numerator.data(), static_cast<Eigen::Index>(numerator.size()))),
      Polynomial(Eigen::Map<Eigen::VectorXd>(denominator.data(), static_cast<Eigen::Index>(denominator.size())))};
  t.specimen_stiffness_n_per_m = specimen_stiffness_n_per_m;
  t.specimen_damping_n_s_per_m = section.number_or(
      "specimen_damping_n_s_per_m", 0.0,
      config::Number::non_negative("N s/m", "the specimen's damping in the measured force: + c dx_m/dt"));
  t.specimen_mass_kg =
      section.number_or("specimen_mass_kg", 0.0,
                        config::Number::non_negative("kg", "the specimen's mass in the measured force: + m d2x_m/dt2"));
  t.plant_rate_hz = section.number_or("plant_rate_hz", t.plant_rate_hz,
                                      config::Number::between(1e3, 1e6, "Hz", "fixed-step integration rate"));
  t.rig = Envelope::read(*section.section("rig", "what the simulated rig can do"));
  try {
    t.validate();
  } catch (const std::invalid_argument& e) {
    section.fail("denominator_descending", e.what());
  }
  return t;
}

}  // namespace rpsd::servo
