#pragma once
// Published reference data used by several tests.

#include <Eigen/Core>

namespace rpsd::substructure::test {

// RTHS benchmark (Silva et al. 2020), reference building case 1: M = 1000·I kg and K (N/m)
// as published (upper triangle given, symmetric). Frequencies 3.612 / 15.997 / 38.086 Hz.
inline Eigen::Matrix3d benchmark_case1_stiffness() {
  Eigen::Matrix3d K;
  K << 26054883.88, -23133938.88, 5937035.46, -23133938.88, 32560774.19, -14419970.78, 5937035.46, -14419970.78,
      9267275.51;
  return K;
}
inline Eigen::Matrix3d benchmark_case1_mass() { return 1000.0 * Eigen::Matrix3d::Identity(); }
inline constexpr double kBenchmarkCase1FrequenciesHz[3] = {3.612, 15.997, 38.086};

}  // namespace rpsd::substructure::test
