#include "rpsd/substructure/bilinear_spring.h"
#include "rpsd/substructure/bouc_wen_spring.h"
#include "rpsd/substructure/linear_spring.h"
#include "rpsd/substructure/reading_ranges.h"

#include "matrix_checks.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::substructure {

using config::Number;

namespace {

Number initial_stiffness_range() { return {"N/m", "the initial stiffness", 0.0, ranges::kMaxStiffnessNPerM, true}; }
Number post_yield_range() { return Number::between(0.0, 1.0, "", "post-yield over initial stiffness"); }

}  // namespace

LinearSpringParameters LinearSpringParameters::read(config::Source& s) {
  return LinearSpringParameters{s.number("stiffness_n_per_m", initial_stiffness_range())};
}

BilinearSpringParameters BilinearSpringParameters::read(config::Source& s) {
  BilinearSpringParameters b;
  b.stiffness_n_per_m = s.number("stiffness_n_per_m", initial_stiffness_range());
  b.yield_force_n = s.number("yield_force_n", Number{"N", "the yield force", 0.0, ranges::kMaxForceN, true});
  b.post_yield_ratio = s.number("post_yield_ratio", post_yield_range());
  return b;
}

BoucWenSpringParameters BoucWenSpringParameters::example() {
  BoucWenSpringParameters b;
  b.stiffness_n_per_m = 5.0e7;
  b.post_yield_ratio = 0.05;
  b.n = 2.0;
  b.beta = b.gamma = 1.0 / (2.0 * 0.01 * 0.01);
  return b;
}

BoucWenSpringParameters BoucWenSpringParameters::read(config::Source& s) {
  // beta and gamma in 1/m^n: 1e6 is a yield displacement of a micrometre.
  BoucWenSpringParameters b;
  b.stiffness_n_per_m = s.number("stiffness_n_per_m", initial_stiffness_range());
  b.post_yield_ratio = s.number("post_yield_ratio", post_yield_range());
  b.A = s.number_or("A", b.A, Number{"", "Bouc-Wen A", 0.0, 100.0, true});
  b.beta = s.number("beta", Number::between(0.0, 1e6, "1/m^n", "Bouc-Wen beta"));
  b.gamma = s.number("gamma", Number::between(-1e6, 1e6, "1/m^n", "Bouc-Wen gamma (beta + gamma > 0)"));
  b.n = s.number_or("n", b.n, Number::between(1.0, 20.0, "", "Bouc-Wen n, the sharpness of yielding"));
  return b;
}

namespace {

void require(bool ok, const std::string& spring, const std::string& what, double got) {
  if (!ok) throw std::invalid_argument(spring + ": " + what + ", got " + detail::fmt(got));
}

double sign(double x) noexcept { return (x > 0.0) - (x < 0.0); }

}  // namespace

// ---------------------------------------------------------------- linear

LinearSpring::LinearSpring(const LinearSpringParameters& c) : k_(c.stiffness_n_per_m) {
  require(std::isfinite(k_) && k_ > 0.0, "linear spring", "stiffness_n_per_m must be positive", k_);
}

// ---------------------------------------------------------------- bilinear

BilinearSpring::BilinearSpring(const BilinearSpringParameters& c)
    : k0_(c.stiffness_n_per_m), fy_(c.yield_force_n), alpha_(c.post_yield_ratio), H_(0.0) {
  const std::string s = "bilinear spring";
  require(std::isfinite(k0_) && k0_ > 0.0, s, "stiffness_n_per_m must be positive", k0_);
  require(std::isfinite(fy_) && fy_ > 0.0, s, "yield_force_n must be positive", fy_);
  require(std::isfinite(alpha_) && alpha_ >= 0.0 && alpha_ < 1.0, s, "post_yield_ratio must be in [0, 1)", alpha_);
  // Series combination of k0 and H gives the post-yield slope α k0.
  H_ = alpha_ * k0_ / (1.0 - alpha_);
  committed_.tangent = k0_;
  trial_ = committed_;
}

double BilinearSpring::trial(double u) noexcept {
  State t = committed_;
  t.u = u;
  const double f_elastic = k0_ * (u - committed_.u_plastic);
  const double xi = f_elastic - committed_.back_force;  // relative force
  const double excess = std::abs(xi) - fy_;
  if (excess <= 0.0) {
    t.force = f_elastic;
    t.tangent = k0_;
  } else {
    const double dgamma = excess / (k0_ + H_);
    const double s = sign(xi);
    t.u_plastic = committed_.u_plastic + s * dgamma;
    t.back_force = committed_.back_force + s * H_ * dgamma;
    t.force = f_elastic - s * k0_ * dgamma;
    t.tangent = alpha_ * k0_;
  }
  trial_ = t;
  return t.force;
}

void BilinearSpring::commit() noexcept { committed_ = trial_; }

// ---------------------------------------------------------------- Bouc–Wen

BoucWenSpring::BoucWenSpring(const BoucWenSpringParameters& c)
    : k0_(c.stiffness_n_per_m),
      alpha_(c.post_yield_ratio),
      A_(c.A),
      beta_(c.beta),
      gamma_(c.gamma),
      n_(c.n),
      z_max_(0.0),
      h_max_(0.0),
      max_substeps_(c.max_substeps) {
  const std::string s = "Bouc-Wen spring";
  require(std::isfinite(k0_) && k0_ > 0.0, s, "stiffness_n_per_m must be positive", k0_);
  require(std::isfinite(alpha_) && alpha_ >= 0.0 && alpha_ < 1.0, s, "post_yield_ratio must be in [0, 1)", alpha_);
  require(std::isfinite(A_) && A_ > 0.0, s, "A must be positive", A_);
  require(std::isfinite(beta_) && beta_ >= 0.0, s, "beta must be non-negative", beta_);
  require(std::isfinite(gamma_) && beta_ + gamma_ > 0.0, s,
          "beta + gamma must be positive (otherwise z is unbounded); gamma", gamma_);
  require(std::isfinite(n_) && n_ >= 1.0, s, "n must be at least 1", n_);
  require(std::isfinite(c.substep_ratio) && c.substep_ratio > 0.0 && c.substep_ratio <= 1.0, s,
          "substep_ratio must be in (0, 1]", c.substep_ratio);
  require(c.max_substeps >= 1, s, "max_substeps must be at least 1", c.max_substeps);
  z_max_ = std::pow(A_ / (beta_ + gamma_), 1.0 / n_);
  const double L = n_ * std::pow(z_max_, n_ - 1.0) * (beta_ + std::abs(gamma_));
  h_max_ = c.substep_ratio / L;
  committed_.tangent = initial_stiffness();
  trial_ = committed_;
}

double BoucWenSpring::initial_stiffness() const noexcept { return k0_ * (alpha_ + (1.0 - alpha_) * A_); }

double BoucWenSpring::dz_du(double z, double s) const noexcept {
  const double az = std::abs(z);
  const double zn = n_ == 1.0 ? az : (n_ == 2.0 ? az * az : std::pow(az, n_));
  return A_ - zn * (beta_ * sign(s * z) + gamma_);
}

double BoucWenSpring::trial(double u) noexcept {
  const double du = u - committed_.u;
  double z = committed_.z;
  double s = sign(du);
  int steps = 0;
  if (du != 0.0) {
    const double ratio = std::abs(du) / h_max_;
    steps =
        ratio >= static_cast<double>(max_substeps_) ? max_substeps_ : std::max(1, static_cast<int>(std::ceil(ratio)));
    const double h = du / steps;  // signed: dz = g(z; s) du
    for (int i = 0; i < steps; ++i) {
      const double k1 = dz_du(z, s);
      const double k2 = dz_du(z + 0.5 * h * k1, s);
      const double k3 = dz_du(z + 0.5 * h * k2, s);
      const double k4 = dz_du(z + h * k3, s);
      z += h * (k1 + 2.0 * k2 + 2.0 * k3 + k4) / 6.0;
    }
  } else {
    s = committed_.direction;
  }
  last_substeps_ = steps;
  trial_.u = u;
  trial_.z = z;
  trial_.direction = s;
  trial_.force = alpha_ * k0_ * u + (1.0 - alpha_) * k0_ * z;
  trial_.tangent = alpha_ * k0_ + (1.0 - alpha_) * k0_ * dz_du(z, s);
  return trial_.force;
}

void BoucWenSpring::commit() noexcept { committed_ = trial_; }

}  // namespace rpsd::substructure
