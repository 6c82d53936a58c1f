// OpenSSL's low-level SHA-256 is deprecated in 3.0 in favour of EVP, whose contexts allocate
// on every re-initialisation; the low-level context is a plain struct that copies without
// allocating, which the real-time path needs (udp_authenticator.h).
#define OPENSSL_SUPPRESS_DEPRECATED
#include "rpsd/node/udp_authenticator.h"

#include <fcntl.h>
#include <openssl/crypto.h>
#include <openssl/rand.h>
#include <openssl/sha.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <string>

namespace rpsd::node {

struct UdpAuthenticator::States {
  SHA256_CTX inner;  // after absorbing key ^ ipad
  SHA256_CTX outer;  // after absorbing key ^ opad
};

UdpAuthenticator::UdpAuthenticator(std::span<const std::byte> key) : states_(std::make_unique<States>()) {
  if (key.size() < kUdpMinKeyBytes || key.size() > kUdpMaxKeyBytes) {
    throw std::invalid_argument("UDP key: " + std::to_string(key.size()) + " bytes, expected " +
                                std::to_string(kUdpMinKeyBytes) + " to " + std::to_string(kUdpMaxKeyBytes));
  }
  std::array<unsigned char, SHA256_CBLOCK> pad{};
  const auto keyed = [&](unsigned char fill, SHA256_CTX& state) {
    pad.fill(fill);
    for (std::size_t i = 0; i < key.size(); ++i) pad[i] ^= static_cast<unsigned char>(key[i]);
    SHA256_Init(&state);
    SHA256_Update(&state, pad.data(), pad.size());
  };
  keyed(0x36, states_->inner);
  keyed(0x5c, states_->outer);
  OPENSSL_cleanse(pad.data(), pad.size());
}

UdpAuthenticator::~UdpAuthenticator() { OPENSSL_cleanse(states_.get(), sizeof(States)); }

void UdpAuthenticator::tag(std::span<const std::byte> message, std::span<std::byte, kUdpTagBytes> out) const noexcept {
  std::array<unsigned char, SHA256_DIGEST_LENGTH> inner_hash{};
  SHA256_CTX work = states_->inner;
  SHA256_Update(&work, message.data(), message.size());
  SHA256_Final(inner_hash.data(), &work);
  work = states_->outer;
  SHA256_Update(&work, inner_hash.data(), inner_hash.size());
  SHA256_Final(reinterpret_cast<unsigned char*>(out.data()), &work);
}

bool UdpAuthenticator::verify(std::span<const std::byte> message,
                              std::span<const std::byte, kUdpTagBytes> tag) const noexcept {
  std::array<std::byte, kUdpTagBytes> expected{};
  this->tag(message, expected);
  return CRYPTO_memcmp(expected.data(), tag.data(), kUdpTagBytes) == 0;
}

std::vector<std::byte> read_udp_key_file(const std::filesystem::path& file) {
  const std::string name = file.string();
  const auto refuse = [&](const std::string& problem) -> std::invalid_argument {
    return std::invalid_argument(name + ": " + problem);
  };
  // Opened first and checked on the open file, so that what is checked is what is read.
  const int fd = ::open(name.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK | O_NOCTTY);
  if (fd < 0) throw refuse(std::string("cannot open the key file: ") + std::strerror(errno));
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) throw refuse(std::string("cannot stat the key file: ") + std::strerror(errno));
  if (!S_ISREG(st.st_mode)) throw refuse("a key file must be a regular file");
  if (st.st_uid != ::geteuid()) {
    throw refuse("the key file is owned by uid " + std::to_string(st.st_uid) + ", not by this process's user (uid " +
                 std::to_string(::geteuid()) + "): whoever owns it can change the key");
  }
  if ((st.st_mode & 077) != 0) {
    std::ostringstream problem;
    problem << "the key file's mode is 0" << std::oct << (st.st_mode & 0777)
            << ": group or others may read it; a key must be readable by its owner only (chmod 600 " << name << ")";
    throw refuse(problem.str());
  }
  std::array<std::byte, kUdpMaxKeyBytes + 1> buffer{};  // +1: a longer file shows
  std::size_t size = 0;
  for (;;) {
    const ssize_t got = ::read(fd, buffer.data() + size, buffer.size() - size);
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw refuse(std::string("cannot read the key file: ") + std::strerror(errno));
    if (got == 0) break;
    size += static_cast<std::size_t>(got);
    if (size == buffer.size()) break;
  }
  std::vector<std::byte> key(buffer.begin(), buffer.begin() + static_cast<std::ptrdiff_t>(size));
  OPENSSL_cleanse(buffer.data(), buffer.size());
  if (size < kUdpMinKeyBytes || size > kUdpMaxKeyBytes) {
    const std::string got =
        size > kUdpMaxKeyBytes ? "more than " + std::to_string(kUdpMaxKeyBytes) : std::to_string(size);
    throw refuse("the key file holds " + got + " bytes; a key is " + std::to_string(kUdpMinKeyBytes) + " to " +
                 std::to_string(kUdpMaxKeyBytes) + " raw bytes (make one with: openssl rand -out " + name + " 32)");
  }
  return key;
}

void random_nonce(std::span<std::byte> out) {
  if (RAND_bytes(reinterpret_cast<unsigned char*>(out.data()), static_cast<int>(out.size())) != 1) {
    throw std::runtime_error("UDP link: the random generator (OpenSSL RAND_bytes) failed to draw a session nonce");
  }
}

}  // namespace rpsd::node
