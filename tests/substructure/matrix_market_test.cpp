// Matrix Market reading: round trips on files written here, and errors that name the file.

#include "rpsd/substructure/matrix_market.h"
#include "reference_models.h"
#include "rpsd/substructure/linear_mdof_model.h"
#include "rpsd/substructure/modal.h"

#include <unsupported/Eigen/SparseExtra>

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <numbers>
#include <random>
#include <string>

namespace rpsd::substructure {
namespace {

namespace fs = std::filesystem;

class MatrixMarket : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() /
           ("rpsd_mm_" + std::string(info->name()) + "_" + std::to_string(std::random_device{}()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p;
  }
  // The message of the std::invalid_argument thrown by f, or "" if none.
  template <typename F>
  static std::string error_of(F&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

#define EXPECT_CONTAINS(haystack, needle) \
  EXPECT_NE(std::string(haystack).find(needle), std::string::npos) << "message: " << (haystack)

// The benchmark's K as an FE program would export it: symmetric, lower triangle, 1-based.
const char* kBenchmarkK =
    "%%MatrixMarket matrix coordinate real symmetric\n"
    "% RTHS benchmark case 1 stiffness, N/m\n"
    "3 3 6\n"
    "1 1 26054883.88\n"
    "2 1 -23133938.88\n"
    "3 1 5937035.46\n"
    "2 2 32560774.19\n"
    "3 2 -14419970.78\n"
    "3 3 9267275.51\n";
const char* kBenchmarkM =
    "%%MatrixMarket matrix coordinate real general\n"
    "3 3 3\n"
    "1 1 1000\n"
    "2 2 1000\n"
    "3 3 1000\n";

TEST_F(MatrixMarket, SymmetricFileIsMirrored) {
  const linalg::SparseMatrix K = load_matrix_market(write("k.mtx", kBenchmarkK));
  EXPECT_EQ(K.rows(), 3);
  EXPECT_EQ(K.nonZeros(), 9);
  EXPECT_EQ(Eigen::MatrixXd(K), Eigen::MatrixXd(test::benchmark_case1_stiffness()));
}

TEST_F(MatrixMarket, GeneralFileAndIntegerField) {
  const linalg::SparseMatrix A = load_matrix_market(
      write("a.mtx", "%%MatrixMarket matrix coordinate integer general\n%comment\n\n2 3 3\n1 1 4\n2 3 -7\n1 2 5\n"));
  Eigen::MatrixXd expected(2, 3);
  expected << 4, 5, 0, 0, 0, -7;
  EXPECT_EQ(Eigen::MatrixXd(A), expected);
}

TEST_F(MatrixMarket, RoundTripThroughEigenSaveMarket) {
  // A random sparse 40x40 matrix written with full precision reads back bit-exact.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> val(-1e7, 1e7);
  std::uniform_int_distribution<int> idx(0, 39);
  std::vector<Eigen::Triplet<double>> t;
  for (int k = 0; k < 200; ++k) t.emplace_back(idx(rng), idx(rng), val(rng));
  linalg::SparseMatrix A(40, 40);
  A.setFromTriplets(t.begin(), t.end());
  const fs::path p = dir_ / "random.mtx";
  ASSERT_TRUE(Eigen::saveMarket(A, p.string()));
  const linalg::SparseMatrix B = load_matrix_market(p);
  EXPECT_EQ(Eigen::MatrixXd(B), Eigen::MatrixXd(A));
}

TEST_F(MatrixMarket, BenchmarkModelFromFiles) {
  const LinearMdofParameters cfg = linear_config_from_matrix_market(
      {write("m.mtx", kBenchmarkM), write("k.mtx", kBenchmarkK), std::nullopt}, RayleighFromModes{1, 2, 0.05, 0.05});
  LinearMdofModel model;
  model.configure(cfg);
  EXPECT_TRUE(model.initial_stiffness().is_sparse());
  EXPECT_TRUE(model.damping().is_sparse());
  const Eigen::VectorXd w = natural_frequencies_rad_s(model.mass(), model.initial_stiffness());
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(w[i] / (2.0 * std::numbers::pi), test::kBenchmarkCase1FrequenciesHz[i], 5e-4);
  // With a damping file instead.
  const LinearMdofParameters with_c = linear_config_from_matrix_market(
      {write("m2.mtx", kBenchmarkM), write("k2.mtx", kBenchmarkK), write("c.mtx", kBenchmarkM)});
  model.configure(with_c);
  EXPECT_EQ(model.damping().to_dense(), Eigen::MatrixXd(test::benchmark_case1_mass()));
}

TEST_F(MatrixMarket, MissingFileIsNamed) {
  const fs::path p = dir_ / "nope.mtx";
  const std::string msg = error_of([&] { (void)load_matrix_market(p); });
  EXPECT_CONTAINS(msg, p.string());
  EXPECT_CONTAINS(msg, "does not exist");
  EXPECT_CONTAINS(error_of([&] { (void)load_matrix_market(dir_); }), "is a directory");
}

TEST_F(MatrixMarket, UnreadableFileIsNamed) {
  const fs::path p = write("locked.mtx", kBenchmarkM);
  fs::permissions(p, fs::perms::none);
  if (std::ifstream(p).is_open()) GTEST_SKIP() << "running with privileges that ignore file permissions";
  const std::string msg = error_of([&] { (void)load_matrix_market(p); });
  EXPECT_CONTAINS(msg, p.string());
  EXPECT_CONTAINS(msg, "cannot be opened for reading");
}

TEST_F(MatrixMarket, MalformedFilesAreNamedWithTheLine) {
  struct Case {
    const char* text;
    const char* expected;
  };
  const Case cases[] = {
      {"", "is empty"},
      {"3 3 1\n1 1 2\n", "line 1: missing the '%%MatrixMarket' banner"},
      {"%%MatrixMarket matrix array real general\n2 2\n1\n2\n3\n4\n", "'array' format is not supported"},
      {"%%MatrixMarket matrix coordinate complex general\n1 1 1\n1 1 1 0\n", "field 'complex' is not supported"},
      {"%%MatrixMarket matrix coordinate pattern general\n1 1 1\n1 1\n", "field 'pattern' is not supported"},
      {"%%MatrixMarket matrix coordinate real skew-symmetric\n2 2 1\n2 1 1\n",
       "symmetry 'skew-symmetric' is not supported"},
      {"%%MatrixMarket matrix coordinate real general\n% only comments\n", "has no size line"},
      {"%%MatrixMarket matrix coordinate real general\nthree by three\n", "line 2: expected the size line"},
      {"%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 1\n2 2 1\n", "declares 3 entries but contains 2"},
      {"%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 1\n2 2 1\n", "declares 1 entries but contains 2"},
      {"%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n3 1 1\n",
       "line 4: entry (3, 1) is outside the 2x2 matrix"},
      {"%%MatrixMarket matrix coordinate real general\n2 2 1\n1 1 abc\n", "line 3: expected an entry"},
      {"%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 2 1\n", "line 3: entry (1, 2) is above the diagonal"},
      {"%%MatrixMarket matrix coordinate real symmetric\n2 3 0\n", "a symmetric matrix must be square"},
  };
  int k = 0;
  for (const Case& c : cases) {
    const fs::path p = write("bad" + std::to_string(k++) + ".mtx", c.text);
    const std::string msg = error_of([&] { (void)load_matrix_market(p); });
    EXPECT_CONTAINS(msg, p.string());
    EXPECT_CONTAINS(msg, c.expected);
  }
  // A line longer than Eigen's loadMarket buffer would silently truncate the matrix.
  const fs::path p = write(
      "long.mtx", "%%MatrixMarket matrix coordinate real general\n%" + std::string(3000, 'x') + "\n1 1 1\n1 1 1\n");
  EXPECT_CONTAINS(error_of([&] { (void)load_matrix_market(p); }), "line 2: line is longer than 2047");
}

TEST_F(MatrixMarket, NonSquareAndMisSizedMatricesAreNamed) {
  const fs::path rect = write("rect.mtx", "%%MatrixMarket matrix coordinate real general\n3 4 1\n1 1 1\n");
  std::string msg = error_of([&] { (void)load_square_matrix_market(rect, std::nullopt); });
  EXPECT_CONTAINS(msg, rect.string());
  EXPECT_CONTAINS(msg, "holds a 3x4 matrix; a structural matrix must be square");

  const fs::path k = write("k.mtx", kBenchmarkK);
  msg = error_of([&] { (void)load_square_matrix_market(k, 4); });
  EXPECT_CONTAINS(msg, k.string());
  EXPECT_CONTAINS(msg, "holds a 3x3 matrix but the model has 4 DOFs");

  const fs::path m2 = write("m2.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 2\n1 1 1\n2 2 1\n");
  msg = error_of([&] { (void)linear_config_from_matrix_market({m2, k, std::nullopt}); });
  EXPECT_CONTAINS(msg, k.string());
  EXPECT_CONTAINS(msg, m2.string());
  EXPECT_CONTAINS(msg, "holds a 3x3 matrix but the mass file");
}

TEST_F(MatrixMarket, ConfigureErrorsNameTheFile) {
  // A mass file that parses but is not symmetric: the model's message names the file.
  const fs::path m = write(
      "m_bad.mtx", "%%MatrixMarket matrix coordinate real general\n3 3 4\n1 1 1000\n2 2 1000\n3 3 1000\n1 2 10\n");
  const LinearMdofParameters cfg = linear_config_from_matrix_market({m, write("k.mtx", kBenchmarkK), std::nullopt});
  LinearMdofModel model;
  const std::string msg = error_of([&] { model.configure(cfg); });
  EXPECT_CONTAINS(msg, "mass matrix M (from file '" + m.string() + "') is not symmetric");
}

// A size line is checked before anything is sized from it: 1e9 x 1e9 would otherwise ask
// for gigabytes of index arrays, and a declared entry count the file cannot hold for as much.
TEST_F(MatrixMarket, AHugeSizeLineIsRefusedBeforeAnythingIsAllocated) {
  const fs::path huge =
      write("huge.mtx", "%%MatrixMarket matrix coordinate real general\n1000000000 1000000000 1\n1 1 1\n");
  std::string msg = error_of([&] { (void)load_matrix_market(huge); });
  EXPECT_CONTAINS(msg, huge.string());
  EXPECT_CONTAINS(msg, "line 2: size 1000000000x1000000000 exceeds the 100000 rows and columns rpsd accepts");

  const fs::path many = write("many.mtx", "%%MatrixMarket matrix coordinate real general\n1000 1000 100000\n1 1 1\n");
  msg = error_of([&] { (void)load_matrix_market(many); });
  EXPECT_CONTAINS(msg, "line 2: declares 100000 entries, more than the file's 69 bytes can hold");

  const fs::path dense = write("dense.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 5\n1 1 1\n");
  EXPECT_CONTAINS(error_of([&] { (void)load_matrix_market(dense); }),
                  "line 2: declares 5 entries, more than a 2x2 matrix has");
}

TEST_F(MatrixMarket, OnlyRegularFilesAreRead) {
  EXPECT_CONTAINS(error_of([&] { (void)load_matrix_market("/dev/zero"); }),
                  "/dev/zero: is a character device; a Matrix Market file must be a regular file");
  const fs::path fifo = dir_ / "k.mtx";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  // From a thread, so that a reader that blocked on the FIFO fails the bound, not the run.
  auto message = std::async(std::launch::async, [&] { return error_of([&] { (void)load_matrix_market(fifo); }); });
  if (message.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    ADD_FAILURE() << "the reader blocked on a FIFO";
    std::abort();
  }
  EXPECT_CONTAINS(message.get(), fifo.string() + ": is a FIFO");
}

}  // namespace
}  // namespace rpsd::substructure
