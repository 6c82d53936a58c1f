// Modal damping, C = M Phi diag(2 zeta_k w_k) Phi^T M: each mode gets its ratio, as the
// eigenvalues of the state matrix show (state_space_damping.h), for any ratios per mode.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rpsd/substructure/damping.h"
#include "state_space_damping.h"

namespace rpsd::substructure {
namespace {

TEST(ModalDamping, EachModeGetsItsOwnRatio) {
  Eigen::MatrixXd m = Eigen::Vector3d(1000.0, 1500.0, 800.0).asDiagonal();
  Eigen::MatrixXd k(3, 3);
  k << 3.0e6, -1.2e6, 0.0, -1.2e6, 2.0e6, -0.8e6, 0.0, -0.8e6, 0.8e6;
  const BuiltDamping built =
      build_damping(ModalDamping{{0.02, 0.05, 0.10}}, linalg::StructuralMatrix(m), linalg::StructuralMatrix(k), "");
  const std::vector<double> zeta = test::state_space_damping_ratios(m, built.c.to_dense(), k);
  ASSERT_EQ(zeta.size(), 3u);
  EXPECT_NEAR(zeta[0], 0.02, 1e-9);
  EXPECT_NEAR(zeta[1], 0.05, 1e-9);
  EXPECT_NEAR(zeta[2], 0.10, 1e-9);
}

TEST(ModalDamping, OneRatioIsEveryModesAndAWrongCountIsNamed) {
  Eigen::MatrixXd m = Eigen::Vector2d(2.0, 1.0).asDiagonal();
  Eigen::MatrixXd k(2, 2);
  k << 300.0, -100.0, -100.0, 100.0;
  const BuiltDamping built =
      build_damping(ModalDamping{{0.05}}, linalg::StructuralMatrix(m), linalg::StructuralMatrix(k), "");
  for (double z : test::state_space_damping_ratios(m, built.c.to_dense(), k)) EXPECT_NEAR(z, 0.05, 1e-9);
  EXPECT_THAT(
      [&] {
        (void)build_damping(ModalDamping{{0.05, 0.02, 0.01}}, linalg::StructuralMatrix(m), linalg::StructuralMatrix(k),
                            "C: ");
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("C: modal damping: 3 ratios for 2 modes")));
}

}  // namespace
}  // namespace rpsd::substructure
