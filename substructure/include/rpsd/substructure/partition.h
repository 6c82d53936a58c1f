#pragma once
// The partition of a hybrid model between numerical and experimental DOFs.
//
// Each experimental DOF is driven by one actuator channel. Model and specimen may differ in
// scale: the actuator is commanded displacement_scale × (model displacement), and the
// measured specimen force enters the model as force_scale × (specimen force). For a
// specimen at length scale λ (specimen/model), displacement_scale = λ and, by similitude
// with equal stress, force_scale = 1/λ².

#include "rpsd/linalg/structural_matrix.h"

#include <Eigen/Core>

#include <concepts>
#include <vector>

namespace rpsd::substructure {

struct ExperimentalDof {
  Eigen::Index dof = 0;               // 0-based global DOF of the model
  Eigen::Index actuator_channel = 0;  // 0-based channel of the servo node
  double displacement_scale = 1.0;    // specimen displacement / model displacement, > 0
  double force_scale = 1.0;           // model force / specimen force, > 0
  // Initial stiffness of the specimen in specimen units (N/m), ≥ 0; an estimate used only to
  // build the initial stiffness of the coupled system (with_specimen_stiffness).
  double specimen_stiffness_estimate_n_per_m = 0.0;
};

struct PartitionConfig {
  Eigen::Index dofs = 0;                      // DOFs of the whole model
  std::vector<ExperimentalDof> experimental;  // channels must be exactly 0..size()-1
  Eigen::VectorXd influence;                  // ground-motion influence vector ι, size dofs
  // Estimated stiffness between two channels' DOFs (model units, N/m), added symmetrically
  // to K0 beside the diagonal estimates: a substructure that couples its DOFs (an OpenSees
  // site's storeys). Each entry {channel a, channel b, k} adds k at (a, b) and (b, a).
  struct Coupling {
    Eigen::Index channel_a = 0, channel_b = 0;
    double stiffness_n_per_m = 0.0;
  };
  std::vector<Coupling> couplings;
};

class Partition {
 public:
  // Validates DOF and channel indices (in range, no duplicates, channels 0..n_exp−1 each
  // used once), scales and ι. Throws std::invalid_argument. Not real-time safe.
  void configure(const PartitionConfig& config);

  [[nodiscard]] Eigen::Index dofs() const noexcept { return n_; }
  [[nodiscard]] Eigen::Index channels() const noexcept { return static_cast<Eigen::Index>(by_channel_.size()); }
  [[nodiscard]] const Eigen::VectorXd& influence() const noexcept { return influence_; }
  [[nodiscard]] bool is_experimental(Eigen::Index dof) const noexcept;
  // Channel driving `dof`, or −1 for a numerical DOF. Real-time safe.
  [[nodiscard]] Eigen::Index channel_of(Eigen::Index dof) const noexcept;
  [[nodiscard]] const std::vector<Eigen::Index>& numerical_dofs() const noexcept { return numerical_; }
  [[nodiscard]] const ExperimentalDof& channel(Eigen::Index ch) const {
    return by_channel_.at(static_cast<std::size_t>(ch));
  }

  // commands[ch] = displacement_scale · d_global[dof]. Sizes dofs() and channels().
  // Real-time safe.
  void extract_commands(const Eigen::Ref<const Eigen::VectorXd>& d_global,
                        Eigen::Ref<Eigen::VectorXd> commands) const noexcept {
    extract_into(d_global, commands);
  }
  // The same on whole vectors, inline and without a Ref's set-up (the loop's every step);
  // only for Eigen::VectorXd itself, so that nothing converts to one.
  template <std::same_as<Eigen::VectorXd> D, std::same_as<Eigen::VectorXd> C>
  void extract_commands(const D& d_global, C& commands) const noexcept {
    extract_into(d_global, commands);
  }

  // d_global[dof] = x_measured[ch] / displacement_scale for the experimental DOFs; the other
  // entries are left unchanged. Real-time safe.
  void measured_to_model_displacements(const Eigen::Ref<const Eigen::VectorXd>& x_measured,
                                       Eigen::Ref<Eigen::VectorXd> d_global) const noexcept;

  // r_exp = 0 except r_exp[dof] = force_scale · f_measured[ch]. Real-time safe.
  void scatter_forces(const Eigen::Ref<const Eigen::VectorXd>& f_measured,
                      Eigen::Ref<Eigen::VectorXd> r_exp) const noexcept;
  // r[dof] += force_scale · f_measured[ch] (adds R_exp to R_num in place). Real-time safe.
  void add_forces(const Eigen::Ref<const Eigen::VectorXd>& f_measured, Eigen::Ref<Eigen::VectorXd> r) const noexcept {
    add_into(f_measured, r);
  }
  template <std::same_as<Eigen::VectorXd> F, std::same_as<Eigen::VectorXd> R>
  void add_forces(const F& f_measured, R& r) const noexcept {
    add_into(f_measured, r);
  }

  // K_num plus the specimens' estimated stiffness in model units
  // (force_scale · displacement_scale · k_specimen on the diagonal of each experimental DOF,
  // and the couplings between them), with the storage of K_num. Not real-time safe.
  [[nodiscard]] linalg::StructuralMatrix with_specimen_stiffness(const linalg::StructuralMatrix& K_num) const;

 private:
  Eigen::Index n_ = 0;
  std::vector<ExperimentalDof> by_channel_;
  std::vector<Eigen::Index> channel_of_dof_;
  std::vector<Eigen::Index> numerical_;
  Eigen::VectorXd influence_;
  std::vector<PartitionConfig::Coupling> couplings_;

  template <typename D, typename C>
  void extract_into(const D& d, C& commands) const noexcept {
    for (std::size_t ch = 0; ch < by_channel_.size(); ++ch) {
      const ExperimentalDof& x = by_channel_[ch];
      commands[static_cast<Eigen::Index>(ch)] = x.displacement_scale * d[x.dof];
    }
  }
  template <typename F, typename R>
  void add_into(const F& f_measured, R& r) const noexcept {
    for (std::size_t ch = 0; ch < by_channel_.size(); ++ch) {
      const ExperimentalDof& x = by_channel_[ch];
      r[x.dof] += x.force_scale * f_measured[static_cast<Eigen::Index>(ch)];
    }
  }
};

}  // namespace rpsd::substructure
