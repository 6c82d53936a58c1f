#pragma once
// Drives an integrator the way the coordinator does, with a linear restoring force
// R(d) = K d computed at every command.
#include "rpsd/integrators/factory.h"

#include <Eigen/Dense>

#include <functional>
#include <stdexcept>

namespace rpsd::integrators::test {

// One hybrid step: begin, all iterations with R = K * command, end.
template <class Stiffness>
void hybrid_step(Integrator& integrator, const Stiffness& k, const Eigen::VectorXd& f_next, Eigen::VectorXd& r) {
  if (integrator.begin_step(f_next) != StepStatus::kOk) throw std::runtime_error("begin_step");
  for (int i = 0; i < integrator.iterations_per_step(); ++i) {
    r.noalias() = k * integrator.target_displacement();
    if (integrator.set_measured_restoring_force(r) != StepStatus::kOk)
      throw std::runtime_error("set_measured_restoring_force");
  }
  if (integrator.end_step() != StepStatus::kOk) throw std::runtime_error("end_step");
}

}  // namespace rpsd::integrators::test
