#pragma once
// Shear building: N floors with lumped masses joined by story springs.
//
// DOF i (0-based) is the displacement of floor i+1 relative to the ground; story i joins
// floor i (the ground for i = 0) to floor i+1 and deforms by the drift d[i] − d[i−1]. The
// restoring force on floor i is V[i] − V[i+1] (V[N] = 0), so for linear springs
// K is tridiagonal with K(i,i) = k[i] + k[i+1] and K(i,i+1) = K(i+1,i) = −k[i+1].

#include "rpsd/substructure/damping.h"
#include "rpsd/substructure/numerical_model.h"
#include "rpsd/substructure/story_spring.h"

#include <optional>
#include <vector>

namespace rpsd::substructure {

struct ShearBuildingParameters {
  std::vector<double> floor_masses_kg;           // floor 1 (lowest) first; each > 0
  std::vector<StorySpringConfig> story_springs;  // story 1 (ground to floor 1) first
  DampingConfig damping = Undamped{};            // Rayleigh forms use the initial stiffness
  // Storage of M, C, K; by default dense up to kDenseFloorLimit floors, sparse beyond.
  std::optional<linalg::MatrixStorage> storage;
  static constexpr std::size_t kDenseFloorLimit = 64;
};
using ShearBuildingConfig [[deprecated("renamed ShearBuildingParameters (docs/migration.md)")]] =
    ShearBuildingParameters;

class ShearBuilding final : public NumericalModel {
 public:
  // Validates the masses, the spring parameters (messages name the story, 1-based) and the
  // damping, and sizes every buffer. Throws std::invalid_argument. Not real-time safe.
  void configure(const ShearBuildingParameters& config);

  [[nodiscard]] Eigen::Index dofs() const noexcept override { return static_cast<Eigen::Index>(springs_.size()); }
  [[nodiscard]] const linalg::StructuralMatrix& mass() const noexcept override { return M_; }
  [[nodiscard]] const linalg::StructuralMatrix& damping() const noexcept override { return C_; }
  [[nodiscard]] const linalg::StructuralMatrix& initial_stiffness() const noexcept override { return K0_; }
  // Assembled from the story tangents of the last trial. Real-time safe.
  [[nodiscard]] const linalg::StructuralMatrix& tangent_stiffness() noexcept override;

  // Real-time safe.
  void restoring_force(const Eigen::Ref<const Eigen::VectorXd>& d_trial,
                       Eigen::Ref<Eigen::VectorXd> r_out) noexcept override;
  // Real-time safe.
  void commit() noexcept override;

  [[nodiscard]] const StorySpring& story(std::size_t i) const { return springs_.at(i); }
  // Story shears of the last trial, story 1 first.
  [[nodiscard]] const std::vector<double>& trial_story_forces() const noexcept { return V_; }
  [[nodiscard]] const std::optional<RayleighCoefficients>& rayleigh() const noexcept { return rayleigh_; }

 private:
  // Writes the tridiagonal stiffness from the story initial or tangent stiffnesses into K,
  // whose pattern already holds the tridiagonal. Real-time safe.
  static void assemble_tridiagonal(const std::vector<StorySpring>& springs, linalg::StructuralMatrix& K,
                                   bool tangent) noexcept;

  std::vector<StorySpring> springs_;
  std::vector<double> V_;
  linalg::StructuralMatrix M_, C_, K0_, Kt_;
  std::optional<RayleighCoefficients> rayleigh_;
  bool tangent_stale_ = false;
};

}  // namespace rpsd::substructure
