#include "rpsd/substructure/matrix_market.h"

#include "matrix_checks.h"
#include "rpsd/config/input_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace rpsd::substructure {
namespace {

// No entry of a real coordinate file needs a longer line.
constexpr std::size_t kMaxLine = 2047;
// The size line is checked against this before anything is allocated: a structure tested
// in real time has far fewer DOFs, and 1e5 keeps a sparse matrix's index arrays small.
constexpr long long kMaxDofs = 100'000;
// The shortest entry line, "1 1 1\n": the file's size bounds how many entries it can hold.
constexpr long long kMinEntryBytes = 6;

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

struct Contents {
  bool symmetric = false;
  Eigen::Index rows = 0, cols = 0;
  std::vector<Eigen::Triplet<double>> entries;
};

// Reads the file line by line, checking each; throws with file and line on the first
// problem. Nothing is sized from the file before its size line has been checked.
Contents read_entries(const std::filesystem::path& file) {
  const std::string f = mm_file(file);
  std::optional<config::InputFile> opened;
  try {
    opened.emplace(file, config::kMaxMatrixMarketFileBytes, "Matrix Market file");
  } catch (const config::InputFileError& e) {
    throw std::invalid_argument(e.what());
  }
  config::InputFile& in = *opened;
  const auto getline = [&in](std::string& text) {
    try {
      return in.next_line(text);
    } catch (const config::InputFileError& e) {
      throw std::invalid_argument(e.what());
    }
  };

  std::string line;
  std::size_t line_no = 0;
  auto at = [&](std::size_t n) { return f + ", line " + std::to_string(n) + ": "; };

  if (!getline(line)) throw std::invalid_argument(f + " is empty");
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
  Contents h;
  h.symmetric = lower(symmetry) == "symmetric";

  // Size line: the first line that is neither a comment nor blank.
  bool have_size = false;
  long long nnz = 0, count = 0;
  while (getline(line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.size() > kMaxLine) {
      throw std::invalid_argument(at(line_no) + "line is longer than " + std::to_string(kMaxLine) + " characters");
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
      if (r > kMaxDofs || c > kMaxDofs) {
        throw std::invalid_argument(at(line_no) + "size " + std::to_string(r) + "x" + std::to_string(c) +
                                    " exceeds the " + std::to_string(kMaxDofs) + " rows and columns rpsd accepts");
      }
      const long long room = static_cast<long long>(in.size_bytes()) / kMinEntryBytes;
      if (nnz > r * c || nnz > room) {
        throw std::invalid_argument(at(line_no) + "declares " + std::to_string(nnz) + " entries, more than " +
                                    (nnz > r * c
                                         ? "a " + std::to_string(r) + "x" + std::to_string(c) + " matrix has"
                                         : "the file's " + std::to_string(in.size_bytes()) + " bytes can hold"));
      }
      h.rows = r;
      h.cols = c;
      h.entries.reserve(static_cast<std::size_t>(nnz));
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
    if (count == nnz) {
      // Stops here: a file that holds more entries than it declares is not read to its end.
      throw std::invalid_argument(at(line_no) + "declares " + std::to_string(nnz) + " entries but contains " +
                                  std::to_string(nnz + 1) + " or more");
    }
    h.entries.emplace_back(static_cast<Eigen::Index>(i - 1), static_cast<Eigen::Index>(j - 1), v);
    ++count;
  }
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
  const Contents h = read_entries(file);
  // Repeated entries add up, as in Eigen's loadMarket.
  linalg::SparseMatrix A(h.rows, h.cols);
  A.setFromTriplets(h.entries.begin(), h.entries.end());
  if (h.symmetric) {
    // The file holds the lower triangle (checked above): mirror it.
    const linalg::SparseMatrix strict = A.triangularView<Eigen::StrictlyLower>();
    A = A + linalg::SparseMatrix(strict.transpose());
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

LinearMdofParameters linear_config_from_matrix_market(const MatrixMarketModelFiles& files, DampingConfig damping) {
  LinearMdofParameters cfg;
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
