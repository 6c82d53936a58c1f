// The bounds the substructure's readers put on physical quantities: the scenario readers'
// (scenarios/src/physical_ranges.h, which checks that the two agree), far beyond any
// laboratory test yet keeping the numbers a model forms from them finite.
#pragma once

namespace rpsd::substructure::ranges {

inline constexpr double kMaxMassKg = 1e9;
inline constexpr double kMaxStiffnessNPerM = 1e13;
inline constexpr double kMaxForceN = 1e9;

}  // namespace rpsd::substructure::ranges
