// An experimental setup in a plane: the specimen's control point moves as a rigid body
// (translations x, y and rotation θ about z, a chosen subset of them being the site's DOFs,
// the others held at zero), and each actuator joins a fixed end on the reaction frame to an
// attachment point on the specimen. The setup turns the DOFs' displacements into the
// actuators' strokes (length less the length at the reference configuration), the measured
// strokes back into DOF displacements, and the actuators' forces into DOF forces through the
// transposed Jacobian (virtual work: F_dof · δu = Σ f_act · δs).
//
// Linear geometry uses the Jacobian at the reference configuration everywhere; large-
// displacement geometry uses the attachment points' displaced positions, and solves the
// measured strokes for the DOFs by Newton's method (bounded iterations, no allocation).
// Every kind of setup (setup_kinds.h) is one of these, built from the lab's own dimensions.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <string_view>

namespace rpsd::setups {

inline constexpr int kMaxSetupDofs = 3;  // x, y, θ: a plane's rigid body

// Vectors and matrices over a setup's DOFs or actuators: sized at run time, never on the heap.
using SetupVector = Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxSetupDofs, 1>;
using SetupMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSetupDofs, kMaxSetupDofs>;

// Which rigid-body motion of the control point a DOF is (m, m or rad; its force N, N or N·m).
enum class DofMotion : std::uint8_t { kTranslationX, kTranslationY, kRotation };
std::string_view dof_motion_name(DofMotion motion) noexcept;  // "translation_x", ...

enum class Geometry : std::uint8_t { kLinear, kLargeDisplacement };

// One actuator, in the lab's frame with the control point at the origin at the reference
// configuration (the specimen at rest, every DOF zero), metres. A positive stroke lengthens
// the actuator; its positive force pushes the attachment point away from the fixed end.
struct PlanarActuator {
  std::string name;                        // "horizontal", "west", ... for records and messages
  Eigen::Vector2d fixed_end_m{0.0, 0.0};   // on the reaction frame: does not move
  Eigen::Vector2d attachment_m{0.0, 0.0};  // on the specimen, at the reference configuration
};

struct PlanarGeometry {
  Geometry geometry = Geometry::kLinear;
  std::array<DofMotion, kMaxSetupDofs> dofs{};  // the site's DOFs, in the site's order
  int dof_count = 0;                            // 1..3, and as many actuators (square)
  std::array<PlanarActuator, kMaxSetupDofs> actuators{};
  // Large displacement: Newton stops when every stroke residual is below this, or fails
  // after max_newton_iterations.
  double newton_tolerance_m = 1e-12;
  int max_newton_iterations = 25;
};

enum class SetupStatus : std::uint8_t {
  kOk,
  kSingular,      // the Jacobian at this configuration has no inverse (the actuators cannot
                  // hold the DOFs there)
  kNotConverged,  // Newton did not reach the measured strokes within its iterations
  kMirrored,      // the strokes solve to a configuration mirrored from the reference one (the
                  // Jacobian's orientation flipped: an actuator swung through its fixed end)
};
std::string_view setup_status_text(SetupStatus status) noexcept;

class PlanarSetup {
 public:
  // Checks the geometry (1..3 distinct DOFs, one actuator each, no actuator of zero length,
  // a Jacobian at the reference configuration that is invertible): std::invalid_argument
  // naming the actuator or DOF. Not real-time safe.
  explicit PlanarSetup(PlanarGeometry geometry);

  int dofs() const noexcept { return geometry_.dof_count; }
  int actuators() const noexcept { return geometry_.dof_count; }
  const PlanarGeometry& geometry() const noexcept { return geometry_; }
  // Each actuator's length at the reference configuration, m.
  double reference_length_m(int actuator) const noexcept;

  // The strokes that put the specimen at `u` (DOF order). Real-time safe.
  void strokes(const SetupVector& u, SetupVector& strokes_m) const noexcept;
  // ∂stroke_i/∂u_j at `u` (the reference one for linear geometry). Real-time safe.
  void jacobian(const SetupVector& u, SetupMatrix& j) const noexcept;
  // The DOF displacements whose strokes are `strokes_m`: linear, J⁻¹ s; large displacement,
  // Newton from `guess` (the last solution). Real-time safe.
  SetupStatus displacements(const SetupVector& strokes_m, const SetupVector& guess, SetupVector& u) const noexcept;
  // DOF forces J(u)ᵀ f from the actuators' forces at configuration `u`. Real-time safe.
  void dof_forces(const SetupVector& u, const SetupVector& actuator_forces_n, SetupVector& dof_forces) const noexcept;
  // The actuator forces that carry `dof_forces` at `u` (solves J(u)ᵀ f = F): what a
  // simulated specimen loads each actuator with. Real-time safe.
  SetupStatus actuator_forces(const SetupVector& u, const SetupVector& dof_forces,
                              SetupVector& actuator_forces_n) const noexcept;

 private:
  PlanarGeometry geometry_;
  std::array<double, kMaxSetupDofs> reference_length_m_{};
  SetupMatrix reference_jacobian_, reference_jacobian_inverse_;
  bool reference_orientation_positive_ = true;  // the sign of det J at the reference configuration
};

}  // namespace rpsd::setups
