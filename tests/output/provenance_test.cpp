// The SHA-256 of input files against the standard's test vectors (FIPS 180-2, appendix B).
#include "rpsd/output/provenance.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>

namespace rpsd::output {
namespace {

std::string sha256_of_text(const std::string& text) {
  const auto file = std::filesystem::temp_directory_path() / ("rpsd-sha-" + std::to_string(getpid()));
  std::ofstream(file, std::ios::binary) << text;
  const std::string digest = sha256_of_file(file);
  std::filesystem::remove(file);
  return digest;
}

TEST(Provenance, Sha256OfTheStandardsTestVectors) {
  EXPECT_EQ(sha256_of_text("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_of_text(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_of_text("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  // Longer than one read buffer (64 KiB): a million 'a's.
  EXPECT_EQ(sha256_of_text(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(Provenance, AFileThatCannotBeReadIsNamed) {
  try {
    sha256_of_file("/nonexistent/scenario.yaml");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/scenario.yaml"), std::string::npos);
  }
}

}  // namespace
}  // namespace rpsd::output
