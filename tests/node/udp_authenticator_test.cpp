// The UDP link's HMAC-SHA-256: equal to OpenSSL's one-shot HMAC for every key length it
// takes and messages of 0 to 300 bytes, refusing another key's tag and any altered byte;
// and its key file: refused unless a regular file of 32-64 bytes that only its owner may
// read, each refusal naming the file and saying how to fix it.
#include <gtest/gtest.h>

#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "rpsd/node/udp_authenticator.h"

namespace rpsd::node {
namespace {

namespace fs = std::filesystem;

std::vector<std::byte> random_bytes(std::size_t n, std::mt19937& random) {
  std::vector<std::byte> bytes(n);
  for (auto& b : bytes) b = static_cast<std::byte>(random());
  return bytes;
}

std::array<std::byte, kUdpTagBytes> openssl_hmac(std::span<const std::byte> key, std::span<const std::byte> message) {
  std::array<std::byte, kUdpTagBytes> tag{};
  unsigned int length = 0;
  HMAC(EVP_sha256(), key.data(), static_cast<int>(key.size()), reinterpret_cast<const unsigned char*>(message.data()),
       message.size(), reinterpret_cast<unsigned char*>(tag.data()), &length);
  EXPECT_EQ(length, kUdpTagBytes);
  return tag;
}

TEST(UdpAuthenticator, EqualsOpenSslsHmacSha256) {
  std::mt19937 random(25);
  for (std::size_t key_bytes = kUdpMinKeyBytes; key_bytes <= kUdpMaxKeyBytes; ++key_bytes) {
    const auto key = random_bytes(key_bytes, random);
    const UdpAuthenticator authenticator(key);
    for (std::size_t n : {0u, 1u, 55u, 56u, 63u, 64u, 65u, 120u, 176u, 300u}) {
      const auto message = random_bytes(n, random);
      std::array<std::byte, kUdpTagBytes> tag{};
      authenticator.tag(message, tag);
      EXPECT_EQ(tag, openssl_hmac(key, message)) << key_bytes << " " << n;
      EXPECT_TRUE(authenticator.verify(message, tag));
    }
  }
}

// docs/udp-controller-protocol.md's vector for controller implementers.
TEST(UdpAuthenticator, MatchesTheDocumentedTestVector) {
  std::vector<std::byte> key(32), message(120);
  for (std::size_t i = 0; i < key.size(); ++i) key[i] = static_cast<std::byte>(i);
  for (std::size_t i = 0; i < 4; ++i) message[i] = static_cast<std::byte>("RPSC"[i]);
  std::array<std::byte, kUdpTagBytes> tag{};
  UdpAuthenticator(key).tag(message, tag);
  std::string hex;
  for (const std::byte b : tag) {
    hex += "0123456789abcdef"[static_cast<int>(b) >> 4];
    hex += "0123456789abcdef"[static_cast<int>(b) & 15];
  }
  EXPECT_EQ(hex, "e4a47a1fca3dafa9d44d773a723bbacecd8afa9825d216aead780ba9f0dac847");
}

TEST(UdpAuthenticator, RefusesAnotherKeysTagAndAnyAlteredByte) {
  std::mt19937 random(4231);
  const auto key = random_bytes(32, random);
  auto other_key = key;
  other_key[31] ^= std::byte{1};
  const UdpAuthenticator ours(key), theirs(other_key);
  auto message = random_bytes(120, random);
  std::array<std::byte, kUdpTagBytes> tag{};
  theirs.tag(message, tag);
  EXPECT_FALSE(ours.verify(message, tag));
  ours.tag(message, tag);
  ASSERT_TRUE(ours.verify(message, tag));
  for (std::size_t at = 0; at < message.size(); ++at) {
    message[at] ^= std::byte{0x80};
    EXPECT_FALSE(ours.verify(message, tag)) << at;
    message[at] ^= std::byte{0x80};
  }
  for (std::size_t at = 0; at < tag.size(); ++at) {
    tag[at] ^= std::byte{1};
    EXPECT_FALSE(ours.verify(message, tag)) << at;
    tag[at] ^= std::byte{1};
  }
  EXPECT_THROW(UdpAuthenticator(random_bytes(31, random)), std::invalid_argument);
  EXPECT_THROW(UdpAuthenticator(random_bytes(65, random)), std::invalid_argument);
}

class KeyFile : public ::testing::Test {
 protected:
  fs::path write(std::size_t bytes, mode_t mode) {
    std::ofstream(file_, std::ios::binary | std::ios::trunc) << std::string(bytes, 'k');
    ::chmod(file_.c_str(), mode);
    return file_;
  }
  std::string error(const fs::path& file) {
    try {
      (void)read_udp_key_file(file);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "";
  }
  void TearDown() override { fs::remove(file_); }
  fs::path file_ = fs::temp_directory_path() / ("rpsd-udp-key-" + std::to_string(::getpid()) + ".key");
};

TEST_F(KeyFile, OnlyItsOwnerMayReadIt) {
  EXPECT_EQ(read_udp_key_file(write(32, 0600)).size(), 32u);
  EXPECT_EQ(read_udp_key_file(write(64, 0400)).size(), 64u);
  for (const mode_t mode : {0640, 0604, 0644, 0660, 0606, 0610, 0601}) {
    const std::string e = error(write(32, mode));
    EXPECT_EQ(e.rfind(file_.string() + ": ", 0), 0u) << e;
    EXPECT_NE(e.find("group or others may read it"), std::string::npos) << mode << ": " << e;
    EXPECT_NE(e.find("chmod 600 " + file_.string()), std::string::npos) << e;
  }
}

TEST_F(KeyFile, HoldsThirtyTwoToSixtyFourRawBytes) {
  EXPECT_NE(
      error(write(31, 0600)).find("holds 31 bytes; a key is 32 to 64 raw bytes (make one with: openssl rand -out "),
      std::string::npos);
  EXPECT_NE(error(write(65, 0600)).find("holds more than 64 bytes"), std::string::npos);
  EXPECT_NE(error(write(0, 0600)).find("holds 0 bytes"), std::string::npos);
  const std::string missing = error(file_.string() + ".missing");
  EXPECT_NE(missing.find(".missing: cannot open the key file"), std::string::npos) << missing;
  const std::string directory = error(fs::temp_directory_path());
  EXPECT_NE(directory.find("a key file must be a regular file"), std::string::npos) << directory;
}

}  // namespace
}  // namespace rpsd::node
