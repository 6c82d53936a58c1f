#pragma once
// Configure-time validation of structural matrices. Every function throws
// std::invalid_argument whose message starts with `what` (e.g. "linear MDOF model: mass
// matrix M") and names the offending entry with 0-based indices. Not real-time safe.

#include "rpsd/linalg/structural_matrix.h"

#include <string>

namespace rpsd::substructure::detail {

void require_square(const linalg::StructuralMatrix& A, const std::string& what);
void require_size(const linalg::StructuralMatrix& A, Eigen::Index n, const std::string& what);
void require_finite(const linalg::StructuralMatrix& A, const std::string& what);
// |A(i,j) - A(j,i)| <= rel_tol * max|A| for every pair.
void require_symmetric(const linalg::StructuralMatrix& A, const std::string& what, double rel_tol = 1e-8);
void require_nonnegative_diagonal(const linalg::StructuralMatrix& A, const std::string& what);
// Cholesky succeeds. Call after require_symmetric.
void require_positive_definite(const linalg::StructuralMatrix& A, const std::string& what);

// Formats a double with enough digits to tell values apart in a message.
std::string fmt(double v);

}  // namespace rpsd::substructure::detail
