// What the studies show of a model beyond the dense eigen-solver: its lowest modes only.
#pragma once

#include <Eigen/Core>

namespace rpsd::studies {

// How many of a large model's lowest modes the overview and the dry run find (sparse solver).
inline constexpr Eigen::Index kLowestModesOfLargeModels = 10;

}  // namespace rpsd::studies
