#pragma once
// Reading structural matrices exported by finite-element programs in Matrix Market format.

#include "rpsd/substructure/linear_mdof_model.h"

#include <filesystem>
#include <optional>

namespace rpsd::substructure {

// Reads a real (or integer) coordinate Matrix Market file, general or symmetric (the
// lower triangle is stored; the upper is mirrored). The file is first checked line by line
// (banner, size line, entry count, index ranges, numbers) so that every problem is reported
// with the file name and line; the size line is checked against a cap (1e5 rows and
// columns) and against the entries the file can hold before anything is allocated.
// Regular files of at most 256 MB only.
// Unsupported: the dense "array" format, complex/pattern fields, skew-symmetric/Hermitian.
// Throws std::invalid_argument naming the file. Not real-time safe.
[[nodiscard]] linalg::SparseMatrix load_matrix_market(const std::filesystem::path& file);

// As load_matrix_market, and also requires a square matrix with expected_dofs rows when given.
[[nodiscard]] linalg::SparseMatrix load_square_matrix_market(const std::filesystem::path& file,
                                                             std::optional<Eigen::Index> expected_dofs);

struct MatrixMarketModelFiles {
  std::filesystem::path mass_file;
  std::filesystem::path stiffness_file;
  std::optional<std::filesystem::path> damping_file;  // if absent, `damping` below is used
};

// Loads M, K (and C) and checks that they are square and of the same size, naming the files.
// The model matrices are stored sparse. The returned config still goes through
// LinearMdofModel::configure, whose messages name the files through the *_source fields.
// Not real-time safe.
[[nodiscard]] LinearMdofParameters linear_config_from_matrix_market(const MatrixMarketModelFiles& files,
                                                                    DampingConfig damping = Undamped{});

}  // namespace rpsd::substructure
