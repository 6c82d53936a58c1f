// A dense matrix from the rows a file gives (each row the same length, at least one row),
// as the readers of inline matrices need it.
#pragma once

#include <Eigen/Dense>

#include <vector>

namespace rpsd::linalg {

Eigen::MatrixXd dense_from_rows(const std::vector<std::vector<double>>& rows);

}  // namespace rpsd::linalg
