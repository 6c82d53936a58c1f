// The bounds the scenario readers put on physical quantities, stated once: each is far
// beyond any laboratory test (and any structure a real-time test integrates) yet keeps the
// numbers a simulation forms from them finite.
#pragma once

namespace rpsd::scenarios::ranges {

inline constexpr double kMaxMassKg = 1e9;               // a 1 million tonne structure
inline constexpr double kMaxStiffnessNPerM = 1e13;      // far stiffer than any specimen or FE entry in N/m
inline constexpr double kMaxForceN = 1e9;               // 1 GN, beyond any actuator or story shear
inline constexpr double kMaxDisplacementM = 10.0;       // beyond any actuator's stroke or story drift
inline constexpr double kMaxVelocityMPerS = 100.0;      // beyond any servo-hydraulic actuator
inline constexpr double kMaxAccelerationMPerS2 = 1e4;   // 1000 g
inline constexpr double kMaxDurationS = 86'400.0;       // a day
inline constexpr double kMaxRecordDurationS = 3'600.0;  // an hour of ground motion
inline constexpr double kMaxControlRateHz = 65'536.0;   // the coordinator's loop
inline constexpr double kMinControlRateHz = 1.0;        // slower is a quasi-static test, not rpsd's
inline constexpr double kMaxNodeRateHz = 100'000.0;     // a servo node's loop: beyond any controller
inline constexpr double kMaxPgaG = 10.0;                // the largest recorded PGA is about 4.4 g
inline constexpr double kMaxFrequencyHz = 1e4;          // beyond any servo-hydraulic bandwidth
inline constexpr double kMaxSteps = 1e9;                // integration steps of one test

}  // namespace rpsd::scenarios::ranges
