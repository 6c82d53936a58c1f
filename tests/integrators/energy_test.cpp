// Average acceleration (trapezoidal rule) conserves the energy of an undamped linear
// system exactly, whatever the time step.
#include "rpsd/integrators/factory.h"
#include "run_helpers.h"

#include <gtest/gtest.h>

namespace rpsd::integrators::test {
namespace {

TEST(AverageAcceleration, ConservesEnergyInUndampedFreeVibration) {
  Eigen::Matrix3d K;
  K << 26054883.88, -23133938.88, 5937035.46,   //
      -23133938.88, 32560774.19, -14419970.78,  //
      5937035.46, -14419970.78, 9267275.51;
  const Eigen::Matrix3d M = 1000.0 * Eigen::Matrix3d::Identity();
  for (int iterations : {1, 3}) {
    for (double dt : {1.0 / 4096.0, 0.01, 0.2}) {  // omega_max dt = 0.06, 2.4, 48
      auto p = NewmarkParameters::average_acceleration();
      p.fixed_iteration = {iterations, 1};
      auto integrator = make_integrator(p);
      integrator->configure(StructuralMatrices::dense(M, Eigen::Matrix3d::Zero(), K), dt);
      const Eigen::VectorXd d0 = Eigen::Vector3d(0.01, 0.02, 0.03);
      const Eigen::VectorXd v0 = Eigen::Vector3d(-0.1, 0.0, 0.2);
      const Eigen::VectorXd zero = Eigen::VectorXd::Zero(3);
      const Eigen::MatrixXd KK = K;
      integrator->initialize(d0, v0, KK * d0, zero);
      auto energy = [&] {
        const auto& d = integrator->displacement();
        const auto& v = integrator->velocity();
        return 0.5 * v.dot(M * v) + 0.5 * d.dot(K * d);
      };
      const double e0 = energy();
      Eigen::VectorXd r(3);
      double worst = 0.0;
      for (int n = 0; n < 10000; ++n) {
        hybrid_step(*integrator, KK, zero, r);
        worst = std::max(worst, std::abs(energy() - e0) / e0);
      }
      EXPECT_LT(worst, 1e-9) << "dt " << dt << " iterations " << iterations;
    }
  }
}

}  // namespace
}  // namespace rpsd::integrators::test
