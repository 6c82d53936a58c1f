#include "rpsd/substructure/linear_mdof_model.h"

#include "matrix_checks.h"

namespace rpsd::substructure {
namespace {

std::string label(const std::string& name, const std::string& source) {
  return source.empty() ? name : name + " (from " + source + ")";
}

}  // namespace

void LinearMdofModel::configure(const LinearMdofParameters& config) {
  const std::string ctx = "linear MDOF model: ";
  const std::string m = ctx + label("mass matrix M", config.mass_source);
  const std::string k = ctx + label("stiffness matrix K", config.stiffness_source);
  detail::require_square(config.mass_kg, m);
  detail::require_square(config.stiffness_n_per_m, k);
  if (config.stiffness_n_per_m.rows() != config.mass_kg.rows()) {
    throw std::invalid_argument(k + " is " + std::to_string(config.stiffness_n_per_m.rows()) + "x" +
                                std::to_string(config.stiffness_n_per_m.cols()) + " but " +
                                label("mass matrix M", config.mass_source) + " is " +
                                std::to_string(config.mass_kg.rows()) + "x" + std::to_string(config.mass_kg.cols()));
  }
  detail::require_finite(config.mass_kg, m);
  detail::require_finite(config.stiffness_n_per_m, k);
  detail::require_symmetric(config.mass_kg, m);
  detail::require_symmetric(config.stiffness_n_per_m, k);
  detail::require_positive_definite(config.mass_kg, m);
  detail::require_nonnegative_diagonal(config.stiffness_n_per_m, k);

  const std::string c_ctx = config.damping_source.empty() ? ctx : ctx + "(damping from " + config.damping_source + ") ";
  BuiltDamping built = build_damping(config.damping, config.mass_kg, config.stiffness_n_per_m, c_ctx);

  // Commit only after every check has passed, so a failed configure leaves no half state.
  M_ = config.mass_kg;
  K_ = config.stiffness_n_per_m;
  C_ = std::move(built.c);
  rayleigh_ = built.rayleigh;
}

void LinearMdofModel::restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                                      Eigen::Ref<Eigen::VectorXd> r_out) noexcept {
  K_.multiply(d_trial, r_out);
}

}  // namespace rpsd::substructure
