#include "rpsd/substructure/shear_building.h"

#include "matrix_checks.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::substructure {

StorySpring::StorySpring(const StorySpringConfig& config)
    : law_(std::visit([](const auto& c) -> StorySpringLaw { return typename std::decay_t<decltype(c)>::Spring(c); },
                      config)) {}

void ShearBuilding::configure(const ShearBuildingParameters& config) {
  const std::string ctx = "shear building: ";
  const std::size_t n = config.floor_masses_kg.size();
  if (n == 0) throw std::invalid_argument(ctx + "floor_masses_kg is empty; a building needs at least one floor");
  if (config.story_springs.size() != n) {
    throw std::invalid_argument(ctx + std::to_string(n) + " floor masses but " +
                                std::to_string(config.story_springs.size()) +
                                " story springs; give one spring per story");
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double m = config.floor_masses_kg[i];
    if (!(std::isfinite(m) && m > 0.0)) {
      throw std::invalid_argument(ctx + "floor " + std::to_string(i + 1) + ": mass must be positive, got " +
                                  detail::fmt(m) + " kg");
    }
  }
  std::vector<StorySpring> springs;
  springs.reserve(n);
  for (std::size_t i = 0; i < n; ++i) {
    try {
      springs.emplace_back(config.story_springs[i]);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(ctx + "story " + std::to_string(i + 1) + ": " + e.what());
    }
  }

  const auto N = static_cast<Eigen::Index>(n);
  const linalg::MatrixStorage storage = config.storage.value_or(
      n <= ShearBuildingParameters::kDenseFloorLimit ? linalg::MatrixStorage::kDense : linalg::MatrixStorage::kSparse);
  linalg::StructuralMatrix M, K;
  if (storage == linalg::MatrixStorage::kDense) {
    Eigen::MatrixXd m = Eigen::MatrixXd::Zero(N, N);
    for (Eigen::Index i = 0; i < N; ++i) m(i, i) = config.floor_masses_kg[static_cast<std::size_t>(i)];
    M = linalg::StructuralMatrix(std::move(m));
    K = linalg::StructuralMatrix(Eigen::MatrixXd::Zero(N, N));
  } else {
    std::vector<Eigen::Triplet<double>> mt, kt;
    for (Eigen::Index i = 0; i < N; ++i) {
      mt.emplace_back(i, i, config.floor_masses_kg[static_cast<std::size_t>(i)]);
      kt.emplace_back(i, i, 0.0);
      if (i + 1 < N) {
        kt.emplace_back(i, i + 1, 0.0);
        kt.emplace_back(i + 1, i, 0.0);
      }
    }
    linalg::SparseMatrix m(N, N), k(N, N);
    m.setFromTriplets(mt.begin(), mt.end());
    k.setFromTriplets(kt.begin(), kt.end());  // explicit zeros fix the tridiagonal pattern
    M = linalg::StructuralMatrix(m);
    K = linalg::StructuralMatrix(k);
  }

  assemble_tridiagonal(springs, K, false);
  BuiltDamping built = build_damping(config.damping, M, K, ctx);

  // Commit only after every check has passed, so a failed configure leaves no half state.
  springs_ = std::move(springs);
  M_ = std::move(M);
  K0_ = K;
  Kt_ = std::move(K);
  C_ = std::move(built.c);
  rayleigh_ = built.rayleigh;
  V_.assign(n, 0.0);
  tangent_stale_ = false;
}

void ShearBuilding::assemble_tridiagonal(const std::vector<StorySpring>& springs, linalg::StructuralMatrix& K,
                                         bool tangent) noexcept {
  const auto N = static_cast<Eigen::Index>(springs.size());
  auto k = [&](Eigen::Index i) {
    const StorySpring& s = springs[static_cast<std::size_t>(i)];
    return tangent ? s.tangent_stiffness() : s.initial_stiffness();
  };
  if (K.is_sparse()) {
    linalg::SparseMatrix& S = K.sparse_mut();
    // The pattern is fixed at configure(): coeffRef finds existing entries and never inserts.
    for (Eigen::Index i = 0; i < N; ++i) {
      const double above = i + 1 < N ? k(i + 1) : 0.0;
      S.coeffRef(i, i) = k(i) + above;
      if (i + 1 < N) {
        S.coeffRef(i, i + 1) = -above;
        S.coeffRef(i + 1, i) = -above;
      }
    }
    K.values_changed();
  } else {
    Eigen::MatrixXd& D = K.dense_mut();
    for (Eigen::Index i = 0; i < N; ++i) {
      const double above = i + 1 < N ? k(i + 1) : 0.0;
      D(i, i) = k(i) + above;
      if (i + 1 < N) {
        D(i, i + 1) = -above;
        D(i + 1, i) = -above;
      }
    }
  }
}

const linalg::StructuralMatrix& ShearBuilding::tangent_stiffness() noexcept {
  if (tangent_stale_) {
    assemble_tridiagonal(springs_, Kt_, true);
    tangent_stale_ = false;
  }
  return Kt_;
}

void ShearBuilding::restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d,
                                    Eigen::Ref<Eigen::VectorXd> r) noexcept {
  const std::size_t n = springs_.size();
  double below = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double di = d[static_cast<Eigen::Index>(i)];
    V_[i] = springs_[i].trial(di - below);
    below = di;
  }
  for (std::size_t i = 0; i < n; ++i) {
    r[static_cast<Eigen::Index>(i)] = V_[i] - (i + 1 < n ? V_[i + 1] : 0.0);
  }
  tangent_stale_ = true;
}

void ShearBuilding::commit() noexcept {
  for (StorySpring& s : springs_) s.commit();
}

}  // namespace rpsd::substructure
