// The control period of the nodes several node tests drive (1024 Hz), defined once: a unity build
// compiles all of node_tests' files as one translation unit.
#pragma once

namespace rpsd::node {

inline constexpr double kNodePeriodS = 1.0 / 1024.0;

}  // namespace rpsd::node
