// A synthetic sparse model banded like a 2-D frame, for scaling studies and tests of large
// models: 10 nodes per floor, 3 DOF per node, so each DOF couples to the next 5 DOFs (same
// floor) and to the DOFs 28-32 away (floor above); half-bandwidth 32. The stiffness comes
// from springs between coupled DOFs plus one to ground at every DOF (symmetric positive
// definite by construction); lumped or weakly coupled mass; Rayleigh damping. Not real-time safe.
#pragma once

#include <Eigen/SparseCore>

namespace rpsd::substructure {

struct FrameModel {
  Eigen::SparseMatrix<double> mass, damping, stiffness;
};

// n DOF; the stiffness is scaled so that the largest natural frequency is at most
// omega_max_rad_s (bounded by Gershgorin's theorem on M^-1/2 K M^-1/2); 5 % damping near
// omega_max / 100 and omega_max / 10.
FrameModel make_frame_model(int n, double omega_max_rad_s, bool consistent_mass = false);

// The same model with its DOFs renumbered by a fixed pseudo-random permutation, so that the
// natural order is no longer banded and solvers must reorder.
FrameModel permuted(const FrameModel& f);

}  // namespace rpsd::substructure
