#include "rpsd/substructure/damping.h"

#include "matrix_checks.h"
#include "rpsd/substructure/modal.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace rpsd::substructure {
namespace {

linalg::StructuralMatrix zero_like(const linalg::StructuralMatrix& K) {
  if (K.is_sparse()) return linalg::StructuralMatrix(linalg::SparseMatrix(K.rows(), K.cols()));
  return linalg::StructuralMatrix(Eigen::MatrixXd::Zero(K.rows(), K.cols()));
}

BuiltDamping rayleigh(const RayleighCoefficients& c, const linalg::StructuralMatrix& M,
                      const linalg::StructuralMatrix& K) {
  linalg::StructuralMatrix C = linalg::StructuralMatrix::linear_combination(c.a0_per_s, M, c.a1_s, K);
  return {C.converted(K.storage()), c};
}

}  // namespace

BuiltDamping build_damping(const DampingConfig& config, const linalg::StructuralMatrix& M,
                           const linalg::StructuralMatrix& K, const std::string& context) {
  const Eigen::Index n = K.rows();
  return std::visit(
      [&](const auto& cfg) -> BuiltDamping {
        using T = std::decay_t<decltype(cfg)>;
        if constexpr (std::is_same_v<T, Undamped>) {
          return {zero_like(K), std::nullopt};
        } else if constexpr (std::is_same_v<T, DampingMatrix>) {
          detail::require_square(cfg.c, context + "damping matrix C");
          detail::require_size(cfg.c, n, context + "damping matrix C");
          detail::require_finite(cfg.c, context + "damping matrix C");
          return {cfg.c, std::nullopt};
        } else if constexpr (std::is_same_v<T, RayleighFromModes>) {
          for (int mode : {cfg.mode_a, cfg.mode_b}) {
            if (mode < 1 || mode > n) {
              throw std::invalid_argument(context + "Rayleigh damping: mode number " + std::to_string(mode) +
                                          " is out of range 1.." + std::to_string(n) + " (1 = fundamental mode)");
            }
          }
          if (cfg.mode_a == cfg.mode_b) {
            throw std::invalid_argument(context + "Rayleigh damping: the two mode numbers are both " +
                                        std::to_string(cfg.mode_a) + "; they must differ");
          }
          // A model beyond the dense solver's reach needs only its lowest modes, from the sparse one.
          const Eigen::VectorXd w = n > kMaxDenseEigenDofs
                                        ? lowest_modes_sparse(M, K, std::max(cfg.mode_a, cfg.mode_b)).omega_rad_s
                                        : natural_frequencies_rad_s(M, K);
          try {
            return rayleigh(rayleigh_from_frequencies(w[cfg.mode_a - 1], w[cfg.mode_b - 1], cfg.damping_ratio_a,
                                                      cfg.damping_ratio_b),
                            M, K);
          } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(context + "modes " + std::to_string(cfg.mode_a) + " and " +
                                        std::to_string(cfg.mode_b) + ": " + e.what());
          }
        } else if constexpr (std::is_same_v<T, RayleighFromFrequencies>) {
          try {
            return rayleigh(rayleigh_from_frequencies(cfg.omega_a_rad_s, cfg.omega_b_rad_s, cfg.damping_ratio_a,
                                                      cfg.damping_ratio_b),
                            M, K);
          } catch (const std::invalid_argument& e) {
            throw std::invalid_argument(context + e.what());
          }
        } else if constexpr (std::is_same_v<T, ModalDamping>) {
          const std::size_t given = cfg.damping_ratios.size();
          if (given != 1 && given != static_cast<std::size_t>(n)) {
            throw std::invalid_argument(context + "modal damping: " + std::to_string(given) + " ratios for " +
                                        std::to_string(n) + " modes (give one, or one per mode)");
          }
          for (double z : cfg.damping_ratios) {
            if (!(std::isfinite(z) && z >= 0.0)) {
              throw std::invalid_argument(context + "modal damping: a ratio " + detail::fmt(z) + " is not >= 0");
            }
          }
          const ModalSolution modes = modal_analysis(M, K);
          const Eigen::MatrixXd m = M.to_dense();
          Eigen::VectorXd c_modal(n);
          for (Eigen::Index k = 0; k < n; ++k) {
            c_modal[k] = 2.0 * cfg.damping_ratios[given == 1 ? 0 : static_cast<std::size_t>(k)] * modes.omega_rad_s[k];
          }
          const Eigen::MatrixXd m_phi = m * modes.modes;
          Eigen::MatrixXd c = m_phi * c_modal.asDiagonal() * m_phi.transpose();
          c = 0.5 * (c + c.transpose());  // symmetric to the last bit
          return {linalg::StructuralMatrix(c), std::nullopt};
        } else {
          static_assert(std::is_same_v<T, RayleighCoefficients>);
          if (!(std::isfinite(cfg.a0_per_s) && cfg.a0_per_s >= 0.0) || !(std::isfinite(cfg.a1_s) && cfg.a1_s >= 0.0)) {
            throw std::invalid_argument(context +
                                        "Rayleigh coefficients must be non-negative and "
                                        "finite, got a0 = " +
                                        detail::fmt(cfg.a0_per_s) + " 1/s, a1 = " + detail::fmt(cfg.a1_s) + " s");
          }
          return rayleigh(cfg, M, K);
        }
      },
      config);
}

}  // namespace rpsd::substructure
