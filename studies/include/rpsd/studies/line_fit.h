// Least-squares straight line through points (x, y): its slope. Not real-time safe.
#pragma once

#include <span>

namespace rpsd::studies {

// Slope of the least-squares line through (x[i], y[i]) (units of y per unit of x); 0 with
// fewer than 2 points or all x equal.
double least_squares_slope(std::span<const double> x, std::span<const double> y);

}  // namespace rpsd::studies
