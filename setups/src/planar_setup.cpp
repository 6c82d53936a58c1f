#include "rpsd/setups/planar_setup.h"

#include <Eigen/LU>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace rpsd::setups {

namespace {

// The attachment point of `a` with the control point at u, and its derivative along each DOF.
struct Displaced {
  Eigen::Vector2d point;
  std::array<Eigen::Vector2d, kMaxSetupDofs> along_dof;
};

Displaced displaced(const PlanarGeometry& g, const PlanarActuator& a, const SetupVector& u) noexcept {
  double x = 0.0, y = 0.0, theta = 0.0;
  for (int j = 0; j < g.dof_count; ++j) {
    switch (g.dofs[static_cast<std::size_t>(j)]) {
      case DofMotion::kTranslationX:
        x = u[j];
        break;
      case DofMotion::kTranslationY:
        y = u[j];
        break;
      case DofMotion::kRotation:
        theta = u[j];
        break;
    }
  }
  const double c = std::cos(theta), s = std::sin(theta);
  const Eigen::Vector2d& r = a.attachment_m;
  Displaced d;
  d.point = {x + c * r.x() - s * r.y(), y + s * r.x() + c * r.y()};
  for (int j = 0; j < g.dof_count; ++j) {
    switch (g.dofs[static_cast<std::size_t>(j)]) {
      case DofMotion::kTranslationX:
        d.along_dof[static_cast<std::size_t>(j)] = {1.0, 0.0};
        break;
      case DofMotion::kTranslationY:
        d.along_dof[static_cast<std::size_t>(j)] = {0.0, 1.0};
        break;
      case DofMotion::kRotation:
        d.along_dof[static_cast<std::size_t>(j)] = {-s * r.x() - c * r.y(), c * r.x() - s * r.y()};
        break;
    }
  }
  return d;
}

// Whether a square matrix is too near singular to invert: its smallest pivot against its size.
bool near_singular(const SetupMatrix& j) noexcept {
  if (j.rows() == 0) return true;
  const double scale = j.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return true;
  const Eigen::PartialPivLU<SetupMatrix> lu(j);
  const double smallest = lu.matrixLU().diagonal().cwiseAbs().minCoeff();
  return !(smallest > 1e-9 * scale);
}

}  // namespace

std::string_view dof_motion_name(DofMotion motion) noexcept {
  switch (motion) {
    case DofMotion::kTranslationX:
      return "translation_x";
    case DofMotion::kTranslationY:
      return "translation_y";
    case DofMotion::kRotation:
      return "rotation";
  }
  return "?";
}

std::string_view setup_status_text(SetupStatus status) noexcept {
  switch (status) {
    case SetupStatus::kOk:
      return "ok";
    case SetupStatus::kSingular:
      return "the setup's Jacobian is singular at this configuration";
    case SetupStatus::kNotConverged:
      return "the setup's geometry did not converge on the measured strokes";
    case SetupStatus::kMirrored:
      return "the measured strokes solve to a configuration mirrored from the reference one (the Jacobian's "
             "orientation flipped)";
  }
  return "?";
}

PlanarSetup::PlanarSetup(PlanarGeometry geometry) : geometry_(std::move(geometry)) {
  const int n = geometry_.dof_count;
  if (n < 1 || n > kMaxSetupDofs) {
    throw std::invalid_argument("an experimental setup drives 1 to " + std::to_string(kMaxSetupDofs) +
                                " DOFs, one actuator each (" + std::to_string(n) + " given)");
  }
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < i; ++k) {
      if (geometry_.dofs[static_cast<std::size_t>(i)] == geometry_.dofs[static_cast<std::size_t>(k)]) {
        throw std::invalid_argument("the setup's DOFs " + std::to_string(k + 1) + " and " + std::to_string(i + 1) +
                                    " are both " +
                                    std::string(dof_motion_name(geometry_.dofs[static_cast<std::size_t>(i)])));
      }
    }
  }
  if (!(geometry_.newton_tolerance_m > 0.0) || geometry_.max_newton_iterations < 1) {
    throw std::invalid_argument("the setup's Newton solve needs a positive tolerance and at least one iteration");
  }
  for (int i = 0; i < n; ++i) {
    const PlanarActuator& a = geometry_.actuators[static_cast<std::size_t>(i)];
    const double length = (a.attachment_m - a.fixed_end_m).norm();
    if (!std::isfinite(length) || !(length > 0.0)) {
      throw std::invalid_argument("actuator " + std::to_string(i + 1) + (a.name.empty() ? "" : " (" + a.name + ")") +
                                  ": its fixed end and its attachment point coincide (zero length)");
    }
    reference_length_m_[static_cast<std::size_t>(i)] = length;
  }
  reference_jacobian_.resize(n, n);
  const Geometry wanted = geometry_.geometry;
  geometry_.geometry = Geometry::kLargeDisplacement;  // the true Jacobian at the reference
  jacobian(SetupVector::Zero(n), reference_jacobian_);
  geometry_.geometry = wanted;
  if (near_singular(reference_jacobian_)) {
    throw std::invalid_argument(
        "the setup's actuators cannot hold its DOFs: the Jacobian at the reference configuration is singular "
        "(two actuators along one line, or a rotation without a lever arm)");
  }
  reference_jacobian_inverse_ = reference_jacobian_.inverse();
  reference_orientation_positive_ = reference_jacobian_.determinant() > 0.0;
}

double PlanarSetup::reference_length_m(int actuator) const noexcept {
  return reference_length_m_[static_cast<std::size_t>(actuator)];
}

void PlanarSetup::strokes(const SetupVector& u, SetupVector& strokes_m) const noexcept {
  const int n = dofs();
  strokes_m.resize(n);
  if (geometry_.geometry == Geometry::kLinear) {
    strokes_m.noalias() = reference_jacobian_ * u;
    return;
  }
  for (int i = 0; i < n; ++i) {
    const PlanarActuator& a = geometry_.actuators[static_cast<std::size_t>(i)];
    const Displaced d = displaced(geometry_, a, u);
    strokes_m[i] = (d.point - a.fixed_end_m).norm() - reference_length_m_[static_cast<std::size_t>(i)];
  }
}

void PlanarSetup::jacobian(const SetupVector& u, SetupMatrix& j) const noexcept {
  const int n = dofs();
  j.resize(n, n);
  if (geometry_.geometry == Geometry::kLinear) {
    j = reference_jacobian_;
    return;
  }
  for (int i = 0; i < n; ++i) {
    const PlanarActuator& a = geometry_.actuators[static_cast<std::size_t>(i)];
    const Displaced d = displaced(geometry_, a, u);
    const Eigen::Vector2d along = d.point - a.fixed_end_m;
    const double length = along.norm();
    const Eigen::Vector2d unit = length > 0.0 ? Eigen::Vector2d(along / length) : Eigen::Vector2d::Zero();
    for (int k = 0; k < n; ++k) j(i, k) = unit.dot(d.along_dof[static_cast<std::size_t>(k)]);
  }
}

SetupStatus PlanarSetup::displacements(const SetupVector& strokes_m, const SetupVector& guess,
                                       SetupVector& u) const noexcept {
  const int n = dofs();
  if (geometry_.geometry == Geometry::kLinear) {
    u.noalias() = reference_jacobian_inverse_ * strokes_m;
    return SetupStatus::kOk;
  }
  // From the last solution; from the linear solution when there is none yet (a guess of
  // another size, or not finite), so that a first call is safe too.
  if (guess.size() == n && guess.allFinite()) {
    u = guess;
  } else {
    u.noalias() = reference_jacobian_inverse_ * strokes_m;
  }
  SetupVector s(n), residual(n), change(n);
  SetupMatrix j(n, n);
  // A solution on the mirrored branch has the same strokes but a Jacobian of the other
  // orientation (the branches meet where it is singular): it is not the specimen's configuration.
  const auto on_the_reference_branch = [&] {
    jacobian(u, j);
    return (j.determinant() > 0.0) == reference_orientation_positive_ ? SetupStatus::kOk : SetupStatus::kMirrored;
  };
  for (int iteration = 0; iteration < geometry_.max_newton_iterations; ++iteration) {
    this->strokes(u, s);
    residual = strokes_m - s;
    if (!residual.allFinite()) return SetupStatus::kNotConverged;
    if (residual.cwiseAbs().maxCoeff() <= geometry_.newton_tolerance_m) return on_the_reference_branch();
    jacobian(u, j);
    if (near_singular(j)) return SetupStatus::kSingular;
    change.noalias() = Eigen::PartialPivLU<SetupMatrix>(j).solve(residual);
    u += change;
  }
  this->strokes(u, s);
  residual = strokes_m - s;
  return residual.allFinite() && residual.cwiseAbs().maxCoeff() <= geometry_.newton_tolerance_m
             ? on_the_reference_branch()
             : SetupStatus::kNotConverged;
}

void PlanarSetup::dof_forces(const SetupVector& u, const SetupVector& actuator_forces_n,
                             SetupVector& dof_forces) const noexcept {
  SetupMatrix j(dofs(), dofs());
  jacobian(u, j);
  dof_forces.noalias() = j.transpose() * actuator_forces_n;
}

SetupStatus PlanarSetup::actuator_forces(const SetupVector& u, const SetupVector& dof_forces,
                                         SetupVector& actuator_forces_n) const noexcept {
  SetupMatrix j(dofs(), dofs());
  jacobian(u, j);
  if (near_singular(j)) return SetupStatus::kSingular;
  actuator_forces_n.noalias() = Eigen::PartialPivLU<SetupMatrix>(j.transpose()).solve(dof_forces);
  return SetupStatus::kOk;
}

}  // namespace rpsd::setups
