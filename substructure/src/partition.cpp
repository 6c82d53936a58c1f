#include "rpsd/substructure/partition.h"

#include "matrix_checks.h"
#include "rpsd/substructure/ground_motion_load.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace rpsd::substructure {
namespace {

std::string num(Eigen::Index i) { return std::to_string(i); }

}  // namespace

void Partition::configure(const PartitionConfig& config) {
  const std::string ctx = "partition: ";
  const Eigen::Index n = config.dofs;
  if (n <= 0) throw std::invalid_argument(ctx + "dofs must be positive, got " + num(n));
  if (config.influence.size() != n) {
    throw std::invalid_argument(ctx + "influence vector has " + num(config.influence.size()) +
                                " entries but the model has " + num(n) + " DOFs");
  }
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!std::isfinite(config.influence[i])) {
      throw std::invalid_argument(ctx + "influence vector entry " + num(i) + " is not finite");
    }
  }
  const auto n_exp = static_cast<Eigen::Index>(config.experimental.size());
  if (n_exp > n) {
    throw std::invalid_argument(ctx + num(n_exp) + " experimental DOFs but the model has only " + num(n) + " DOFs");
  }
  std::vector<Eigen::Index> channel_of_dof(static_cast<std::size_t>(n), -1);
  std::vector<Eigen::Index> entry_of_dof(static_cast<std::size_t>(n), -1);
  std::vector<Eigen::Index> entry_of_channel(static_cast<std::size_t>(n_exp), -1);
  std::vector<ExperimentalDof> by_channel(static_cast<std::size_t>(n_exp));
  for (Eigen::Index e = 0; e < n_exp; ++e) {
    const ExperimentalDof& x = config.experimental[static_cast<std::size_t>(e)];
    const std::string at = ctx + "experimental entry " + num(e) + ": ";
    if (x.dof < 0 || x.dof >= n) {
      throw std::invalid_argument(at + "DOF index " + num(x.dof) + " is out of range 0.." + num(n - 1));
    }
    if (entry_of_dof[static_cast<std::size_t>(x.dof)] >= 0) {
      throw std::invalid_argument(at + "DOF " + num(x.dof) + " is already experimental (entry " +
                                  num(entry_of_dof[static_cast<std::size_t>(x.dof)]) +
                                  "); each DOF can be driven by one actuator only");
    }
    if (x.actuator_channel < 0 || x.actuator_channel >= n_exp) {
      throw std::invalid_argument(at + "actuator channel " + num(x.actuator_channel) + " is out of range 0.." +
                                  num(n_exp - 1) + " (one channel per experimental DOF)");
    }
    if (entry_of_channel[static_cast<std::size_t>(x.actuator_channel)] >= 0) {
      throw std::invalid_argument(at + "actuator channel " + num(x.actuator_channel) + " is already used by entry " +
                                  num(entry_of_channel[static_cast<std::size_t>(x.actuator_channel)]));
    }
    if (!(std::isfinite(x.displacement_scale) && x.displacement_scale > 0.0)) {
      throw std::invalid_argument(at + "displacement_scale must be positive, got " + detail::fmt(x.displacement_scale));
    }
    if (!(std::isfinite(x.force_scale) && x.force_scale > 0.0)) {
      throw std::invalid_argument(at + "force_scale must be positive, got " + detail::fmt(x.force_scale));
    }
    if (!(std::isfinite(x.specimen_stiffness_estimate_n_per_m) && x.specimen_stiffness_estimate_n_per_m >= 0.0)) {
      throw std::invalid_argument(at + "specimen_stiffness_estimate_n_per_m must be non-negative, got " +
                                  detail::fmt(x.specimen_stiffness_estimate_n_per_m));
    }
    entry_of_dof[static_cast<std::size_t>(x.dof)] = e;
    entry_of_channel[static_cast<std::size_t>(x.actuator_channel)] = e;
    channel_of_dof[static_cast<std::size_t>(x.dof)] = x.actuator_channel;
    by_channel[static_cast<std::size_t>(x.actuator_channel)] = x;
  }
  std::vector<Eigen::Index> numerical;
  for (Eigen::Index i = 0; i < n; ++i)
    if (channel_of_dof[static_cast<std::size_t>(i)] < 0) numerical.push_back(i);

  n_ = n;
  by_channel_ = std::move(by_channel);
  channel_of_dof_ = std::move(channel_of_dof);
  numerical_ = std::move(numerical);
  influence_ = config.influence;
  const auto channels = static_cast<Eigen::Index>(by_channel_.size());
  for (const auto& c : config.couplings) {
    if (c.channel_a < 0 || c.channel_a >= channels || c.channel_b < 0 || c.channel_b >= channels ||
        c.channel_a == c.channel_b || !std::isfinite(c.stiffness_n_per_m)) {
      throw std::invalid_argument("partition: a stiffness coupling needs two different channels of the " +
                                  num(channels) + " and a finite stiffness");
    }
  }
  couplings_ = config.couplings;
}

bool Partition::is_experimental(Eigen::Index dof) const noexcept { return channel_of(dof) >= 0; }

Eigen::Index Partition::channel_of(Eigen::Index dof) const noexcept {
  if (dof < 0 || dof >= n_) return -1;
  return channel_of_dof_[static_cast<std::size_t>(dof)];
}

void Partition::measured_to_model_displacements(const Eigen::Ref<const Eigen::VectorXd>& x_measured,
                                                Eigen::Ref<Eigen::VectorXd> d) const noexcept {
  for (std::size_t ch = 0; ch < by_channel_.size(); ++ch) {
    const ExperimentalDof& x = by_channel_[ch];
    d[x.dof] = x_measured[static_cast<Eigen::Index>(ch)] / x.displacement_scale;
  }
}

void Partition::scatter_forces(const Eigen::Ref<const Eigen::VectorXd>& f_measured,
                               Eigen::Ref<Eigen::VectorXd> r_exp) const noexcept {
  r_exp.setZero();
  add_forces(f_measured, r_exp);
}

linalg::StructuralMatrix Partition::with_specimen_stiffness(const linalg::StructuralMatrix& K_num) const {
  if (K_num.rows() != n_ || K_num.cols() != n_) {
    const std::string ctx = "partition: stiffness matrix is ";
    throw std::invalid_argument(ctx + num(K_num.rows()) + "x" + num(K_num.cols()) + " but the partition has " +
                                num(n_) + " DOFs");
  }
  std::vector<Eigen::Triplet<double>> diag;
  for (const ExperimentalDof& x : by_channel_) {
    diag.emplace_back(x.dof, x.dof, x.force_scale * x.displacement_scale * x.specimen_stiffness_estimate_n_per_m);
  }
  linalg::SparseMatrix D(n_, n_);
  for (const auto& c : couplings_) {
    const Eigen::Index a = by_channel_[static_cast<std::size_t>(c.channel_a)].dof;
    const Eigen::Index b = by_channel_[static_cast<std::size_t>(c.channel_b)].dof;
    diag.emplace_back(a, b, c.stiffness_n_per_m);
    diag.emplace_back(b, a, c.stiffness_n_per_m);
  }
  D.setFromTriplets(diag.begin(), diag.end());  // duplicates are summed
  return linalg::StructuralMatrix::linear_combination(1.0, K_num, 1.0, linalg::StructuralMatrix(D))
      .converted(K_num.storage());
}

void GroundMotionLoad::configure(const linalg::StructuralMatrix& mass, const Eigen::VectorXd& influence) {
  const std::string ctx = "ground motion load: ";
  detail::require_square(mass, ctx + "mass matrix M");
  if (influence.size() != mass.rows()) {
    throw std::invalid_argument(ctx + "influence vector has " + num(influence.size()) +
                                " entries but the mass matrix is " + num(mass.rows()) + "x" + num(mass.cols()));
  }
  if (!influence.allFinite()) throw std::invalid_argument(ctx + "influence vector is not finite");
  Eigen::VectorXd m_iota(mass.rows());
  mass.multiply(influence, m_iota);
  m_iota_ = std::move(m_iota);
}

}  // namespace rpsd::substructure
