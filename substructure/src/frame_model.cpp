#include "rpsd/substructure/frame_model.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

namespace rpsd::substructure {

FrameModel make_frame_model(int n, double omega_max_rad_s, bool consistent_mass) {
  std::vector<Eigen::Triplet<double>> k_trip, m_trip;
  auto spring = [&](int i, int j, double k) {
    k_trip.emplace_back(i, i, k);
    k_trip.emplace_back(j, j, k);
    k_trip.emplace_back(i, j, -k);
    k_trip.emplace_back(j, i, -k);
  };
  for (int i = 0; i < n; ++i) {
    k_trip.emplace_back(i, i, 0.5 + 0.1 * (i % 3));  // ground spring
    for (int o : {1, 2, 3, 4, 5, 28, 29, 30, 31, 32})
      if (i + o < n) spring(i, i + o, 1.0 + 0.25 * std::sin(0.7 * i + o));
    const double m = 1.0 + 0.2 * (i % 3);
    if (consistent_mass) {
      m_trip.emplace_back(i, i, m);
      if (i + 1 < n) {  // a weak coupling keeps M diagonally dominant, hence SPD
        m_trip.emplace_back(i, i + 1, 0.1);
        m_trip.emplace_back(i + 1, i, 0.1);
      }
    } else {
      m_trip.emplace_back(i, i, m);
    }
  }
  FrameModel f;
  f.stiffness.resize(n, n);
  f.stiffness.setFromTriplets(k_trip.begin(), k_trip.end());
  f.mass.resize(n, n);
  f.mass.setFromTriplets(m_trip.begin(), m_trip.end());
  // Gershgorin bound of the generalized eigenvalues (diagonal part of M, 0.8 safety for
  // the consistent mass whose smallest eigenvalue is >= m_min - 0.2).
  double bound = 0.0;
  for (int k = 0; k < n; ++k) {
    double row = 0.0;
    for (Eigen::SparseMatrix<double>::InnerIterator it(f.stiffness, k); it; ++it) row += std::abs(it.value());
    bound = std::max(bound, row / (consistent_mass ? 0.8 : 1.0));
  }
  f.stiffness *= omega_max_rad_s * omega_max_rad_s / bound;
  // 5 % damping near omega_max/100 and omega_max/10.
  const double w1 = omega_max_rad_s / 100.0, w2 = omega_max_rad_s / 10.0, xi = 0.05;
  const double a0 = 2.0 * xi * w1 * w2 / (w1 + w2), a1 = 2.0 * xi / (w1 + w2);
  f.damping = a0 * f.mass + a1 * f.stiffness;
  f.mass.makeCompressed();
  f.damping.makeCompressed();
  f.stiffness.makeCompressed();
  return f;
}

FrameModel permuted(const FrameModel& f) {
  const int n = static_cast<int>(f.mass.rows());
  Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> p(n);
  p.setIdentity();
  unsigned state = 12345u;
  for (int i = n - 1; i > 0; --i) {  // Fisher-Yates with a fixed LCG
    state = state * 1664525u + 1013904223u;
    std::swap(p.indices()(i), p.indices()(static_cast<int>(state % static_cast<unsigned>(i + 1))));
  }
  FrameModel g;
  g.mass = f.mass.twistedBy(p);
  g.damping = f.damping.twistedBy(p);
  g.stiffness = f.stiffness.twistedBy(p);
  return g;
}

}  // namespace rpsd::substructure
