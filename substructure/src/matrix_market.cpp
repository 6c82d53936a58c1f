#include "rpsd/substructure/matrix_market.h"

#include "matrix_checks.h"

#include <unsupported/Eigen/SparseExtra>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rpsd::substructure {
namespace {

// Eigen's loadMarket reads into a 2048-byte buffer and silently stops at a longer line.
constexpr std::size_t kEigenMaxLine = 2047;

// Built with += : GCC 12 warns falsely (-Wrestrict) on "literal" + std::string&&.
std::string quoted(const std::filesystem::path& p) {
  std::string s = "'";
  s += p.string();
  s += "'";
  return s;
}
std::string mm_file(const std::filesystem::path& p) {
  std::string s = "Matrix Market file ";
  s += quoted(p);
  return s;
}
std::string file_label(const std::filesystem::path& p) {
  std::string s = "file ";
  s += quoted(p);
  return s;
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

bool blank(const std::string& s) {
  return std::all_of(s.begin(), s.end(), [](unsigned char c) { return std::isspace(c); });
}

struct Header {
  bool symmetric = false;
  Eigen::Index rows = 0, cols = 0;
};

// Checks the whole file; throws with file and line on the first problem.
Header prescan(const std::filesystem::path& file) {
  const std::string f = mm_file(file);
  std::error_code ec;
  if (!std::filesystem::exists(file, ec)) throw std::invalid_argument(f + " does not exist");
  if (std::filesystem::is_directory(file, ec)) throw std::invalid_argument(f + " is a directory");
  std::ifstream in(file);
  if (!in) throw std::invalid_argument(f + " cannot be opened for reading");

  std::string line;
  std::size_t line_no = 0;
  auto at = [&](std::size_t n) { return f + ", line " + std::to_string(n) + ": "; };

  if (!std::getline(in, line)) throw std::invalid_argument(f + " is empty");
  ++line_no;
  std::istringstream banner(line);
  std::string tag, object, format, field, symmetry;
  banner >> tag >> object >> format >> field >> symmetry;
  if (tag != "%%MatrixMarket") {
    throw std::invalid_argument(at(1) + "missing the '%%MatrixMarket' banner; not a Matrix Market file");
  }
  if (lower(object) != "matrix") {
    throw std::invalid_argument(at(1) + "object '" + object + "' is not 'matrix'");
  }
  if (lower(format) == "array") {
    throw std::invalid_argument(at(1) +
                                "the dense 'array' format is not supported; write the "
                                "matrix in 'coordinate' format");
  }
  if (lower(format) != "coordinate") {
    throw std::invalid_argument(at(1) + "format '" + format + "' is not 'coordinate'");
  }
  if (lower(field) != "real" && lower(field) != "integer") {
    throw std::invalid_argument(at(1) + "field '" + field + "' is not supported (only 'real' or 'integer')");
  }
  if (lower(symmetry) != "general" && lower(symmetry) != "symmetric") {
    throw std::invalid_argument(at(1) + "symmetry '" + symmetry + "' is not supported (only 'general' or 'symmetric')");
  }
  Header h;
  h.symmetric = lower(symmetry) == "symmetric";

  // Size line: the first line that is neither a comment nor blank.
  bool have_size = false;
  long long nnz = 0, count = 0;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.size() > kEigenMaxLine) {
      throw std::invalid_argument(at(line_no) + "line is longer than " + std::to_string(kEigenMaxLine) + " characters");
    }
    if (!line.empty() && line[0] == '%') continue;
    if (blank(line)) continue;
    std::istringstream ls(line);
    if (!have_size) {
      long long r = 0, c = 0;
      std::string extra;
      if (!(ls >> r >> c >> nnz) || (ls >> extra)) {
        throw std::invalid_argument(at(line_no) + "expected the size line 'rows columns entries', got '" + line + "'");
      }
      if (r <= 0 || c <= 0 || nnz < 0) {
        throw std::invalid_argument(at(line_no) + "invalid size " + std::to_string(r) + "x" + std::to_string(c) +
                                    " with " + std::to_string(nnz) + " entries");
      }
      if (h.symmetric && r != c) {
        throw std::invalid_argument(at(line_no) + "a symmetric matrix must be square, got " + std::to_string(r) + "x" +
                                    std::to_string(c));
      }
      h.rows = r;
      h.cols = c;
      have_size = true;
      continue;
    }
    long long i = 0, j = 0;
    double v = 0.0;
    std::string extra;
    if (!(ls >> i >> j >> v) || (ls >> extra)) {
      throw std::invalid_argument(at(line_no) + "expected an entry 'row column value', got '" + line + "'");
    }
    if (i < 1 || i > h.rows || j < 1 || j > h.cols) {
      throw std::invalid_argument(at(line_no) + "entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is outside the " + std::to_string(h.rows) + "x" + std::to_string(h.cols) +
                                  " matrix (indices are 1-based)");
    }
    if (h.symmetric && i < j) {
      throw std::invalid_argument(at(line_no) + "entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                  ") is above the diagonal; a symmetric file "
                                  "stores the lower triangle only");
    }
    if (!std::isfinite(v)) {
      throw std::invalid_argument(at(line_no) + "entry value '" + line + "' is not finite");
    }
    ++count;
  }
  if (in.bad()) throw std::invalid_argument(f + ": read error after line " + std::to_string(line_no));
  if (!have_size) throw std::invalid_argument(f + " has no size line 'rows columns entries'");
  if (count != nnz) {
    throw std::invalid_argument(f + " declares " + std::to_string(nnz) + " entries but contains " +
                                std::to_string(count));
  }
  return h;
}

std::string shape(const linalg::SparseMatrix& A) { return std::to_string(A.rows()) + "x" + std::to_string(A.cols()); }

}  // namespace

linalg::SparseMatrix load_matrix_market(const std::filesystem::path& file) {
  const Header h = prescan(file);
  linalg::SparseMatrix A;
  if (!Eigen::loadMarket(A, file.string())) {
    throw std::invalid_argument(mm_file(file) + " cannot be opened for reading");
  }
  if (A.rows() != h.rows || A.cols() != h.cols) {
    throw std::invalid_argument(mm_file(file) + ": Eigen's loadMarket read a " + shape(A) +
                                " matrix where the size line says " + std::to_string(h.rows) + "x" +
                                std::to_string(h.cols));
  }
  if (h.symmetric) {
    // The file holds the lower triangle (checked above). Rebuild the full matrix from the
    // lower triangle, so the result is right whether or not loadMarket mirrored it (Eigen
    // 3.4.0 does not; later versions may).
    const linalg::SparseMatrix lower = A.triangularView<Eigen::Lower>();
    const linalg::SparseMatrix strict = A.triangularView<Eigen::StrictlyLower>();
    A = lower + linalg::SparseMatrix(strict.transpose());
  }
  A.makeCompressed();
  return A;
}

linalg::SparseMatrix load_square_matrix_market(const std::filesystem::path& file,
                                               std::optional<Eigen::Index> expected_dofs) {
  linalg::SparseMatrix A = load_matrix_market(file);
  if (A.rows() != A.cols()) {
    throw std::invalid_argument(mm_file(file) + " holds a " + shape(A) + " matrix; a structural matrix must be square");
  }
  if (expected_dofs && A.rows() != *expected_dofs) {
    throw std::invalid_argument(mm_file(file) + " holds a " + shape(A) + " matrix but the model has " +
                                std::to_string(*expected_dofs) + " DOFs");
  }
  return A;
}

LinearMdofConfig linear_config_from_matrix_market(const MatrixMarketModelFiles& files, DampingConfig damping) {
  LinearMdofConfig cfg;
  linalg::SparseMatrix M = load_square_matrix_market(files.mass_file, std::nullopt);
  const Eigen::Index n = M.rows();
  auto sized = [&](const std::filesystem::path& p) {
    linalg::SparseMatrix A = load_square_matrix_market(p, std::nullopt);
    if (A.rows() != n) {
      throw std::invalid_argument(mm_file(p) + " holds a " + shape(A) + " matrix but the mass file " +
                                  quoted(files.mass_file) + " holds a " + shape(M) + " one");
    }
    return A;
  };
  linalg::SparseMatrix K = sized(files.stiffness_file);
  cfg.mass_kg = linalg::StructuralMatrix(M);
  cfg.stiffness_n_per_m = linalg::StructuralMatrix(K);
  cfg.mass_source = file_label(files.mass_file);
  cfg.stiffness_source = file_label(files.stiffness_file);
  if (files.damping_file) {
    cfg.damping = DampingMatrix{linalg::StructuralMatrix(sized(*files.damping_file))};
    cfg.damping_source = file_label(*files.damping_file);
  } else {
    cfg.damping = std::move(damping);
  }
  return cfg;
}

}  // namespace rpsd::substructure
