// How the experimental restoring force of a channel is obtained.
#pragma once

#include <cstdint>

namespace rpsd::coordinator {

enum class RestoringForceSource : std::uint8_t {
  kMeasuredForce,                       // the load cell
  kStiffnessTimesMeasuredDisplacement,  // k x_measured: the seed paper's Figure 8 experiment,
                                        // where the load cell also sees the inertia of the mass
};

struct RestoringForcePath {
  RestoringForceSource source = RestoringForceSource::kMeasuredForce;
  double stiffness_n_per_m = 0.0;  // for kStiffnessTimesMeasuredDisplacement
};

}  // namespace rpsd::coordinator
