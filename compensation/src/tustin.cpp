#include "rpsd/compensation/tustin.h"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace rpsd::compensation {
namespace {

// p(q) * r(q), coefficients in ascending powers of q.
std::vector<double> multiply(const std::vector<double>& p, const std::vector<double>& r) {
  std::vector<double> out(p.size() + r.size() - 1, 0.0);
  for (std::size_t i = 0; i < p.size(); ++i)
    for (std::size_t j = 0; j < r.size(); ++j) out[i + j] += p[i] * r[j];
  return out;
}

std::vector<double> power(const std::vector<double>& p, std::size_t n) {
  std::vector<double> out{1.0};
  for (std::size_t i = 0; i < n; ++i) out = multiply(out, p);
  return out;
}

// sum_k c_k s^(n-k) with s = K (1 - q) / (1 + q), times (1 + q)^n: ascending powers of q.
std::vector<double> mapped(const std::vector<double>& descending, std::size_t n, double K) {
  std::vector<double> out(n + 1, 0.0);
  const std::size_t offset = n + 1 - descending.size();  // a numerator of lower degree
  for (std::size_t i = 0; i < descending.size(); ++i) {
    const std::size_t k = n - (offset + i);  // the power of s
    const std::vector<double> term = multiply(power({1.0, -1.0}, k), power({1.0, 1.0}, n - k));
    const double scale = descending[i] * std::pow(K, static_cast<double>(k));
    for (std::size_t j = 0; j < term.size(); ++j) out[j] += scale * term[j];
  }
  return out;
}

void check(const std::vector<double>& c, const char* what) {
  if (c.empty()) throw std::invalid_argument(std::string("transfer function: the ") + what + " is empty");
  for (double v : c) {
    if (!std::isfinite(v))
      throw std::invalid_argument(std::string("transfer function: a ") + what + " coefficient is not finite");
  }
}

}  // namespace

double tustin_constant(double dt_s, double prewarp_frequency_hz) {
  if (prewarp_frequency_hz == 0.0) return 2.0 / dt_s;
  const double w = 2.0 * std::numbers::pi * prewarp_frequency_hz;
  return w / std::tan(0.5 * w * dt_s);
}

DiscreteFilterCoefficients tustin(const ContinuousTransferFunction& tf, double dt_s, double prewarp_frequency_hz) {
  check(tf.numerator, "numerator");
  check(tf.denominator, "denominator");
  if (tf.denominator.front() == 0.0) {
    throw std::invalid_argument("transfer function: the denominator's leading coefficient is zero");
  }
  if (tf.numerator.size() > tf.denominator.size()) {
    throw std::invalid_argument("transfer function: the numerator's degree exceeds the denominator's (not proper)");
  }
  if (!(dt_s > 0.0) || !(prewarp_frequency_hz >= 0.0) || !(prewarp_frequency_hz < 0.5 / dt_s)) {
    throw std::invalid_argument("transfer function: needs dt > 0 and a pre-warping frequency below Nyquist");
  }
  const std::size_t n = tf.denominator.size() - 1;
  const double K = tustin_constant(dt_s, prewarp_frequency_hz);
  DiscreteFilterCoefficients f{mapped(tf.numerator, n, K), mapped(tf.denominator, n, K)};
  const double a0 = f.a.front();
  if (a0 == 0.0) throw std::invalid_argument("transfer function: a pole at s = K maps to infinity; change dt");
  for (double& v : f.b) v /= a0;
  for (double& v : f.a) v /= a0;
  return f;
}

std::complex<double> evaluate(const ContinuousTransferFunction& tf, std::complex<double> s) {
  std::complex<double> n = 0.0, d = 0.0;
  for (double c : tf.numerator) n = n * s + c;
  for (double c : tf.denominator) d = d * s + c;
  return n / d;
}

std::complex<double> discrete_response(const DiscreteFilterCoefficients& f, double omega_rad_s, double dt_s) {
  const std::complex<double> q = std::polar(1.0, -omega_rad_s * dt_s);  // z^-1
  std::complex<double> n = 0.0, d = 0.0, qk = 1.0;
  for (std::size_t k = 0; k < f.b.size(); ++k, qk *= q) {
    n += f.b[k] * qk;
    d += f.a[k] * qk;
  }
  return n / d;
}

std::vector<std::complex<double>> polynomial_roots(const std::vector<double>& descending) {
  std::size_t first = 0;
  while (first < descending.size() && descending[first] == 0.0) ++first;
  const auto n = static_cast<Eigen::Index>(descending.size() - first) - 1;
  if (n < 1) return {};
  Eigen::MatrixXd companion = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index j = 0; j < n; ++j)
    companion(0, j) = -descending[first + 1 + static_cast<std::size_t>(j)] / descending[first];
  for (Eigen::Index i = 1; i < n; ++i) companion(i, i - 1) = 1.0;
  const Eigen::VectorXcd roots = companion.eigenvalues();
  return {roots.data(), roots.data() + roots.size()};
}

}  // namespace rpsd::compensation
