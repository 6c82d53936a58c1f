// HMAC-SHA-256 for the UDP controller protocol's version 2 (docs/udp-controller-protocol.md),
// keyed once and then allocation-free per datagram, and the key file it is keyed from.
// OpenSSL 3.0's EVP_MAC and HMAC_CTX allocate on every re-initialisation (measured: two
// allocations a datagram), so the inner and outer SHA-256 states of RFC 2104 are computed
// once from the key and copied for each datagram; tests check the result against OpenSSL's
// one-shot HMAC and RFC 4231's vectors.
#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

namespace rpsd::node {

inline constexpr std::size_t kUdpTagBytes = 32;     // a full HMAC-SHA-256, not truncated
inline constexpr std::size_t kUdpMinKeyBytes = 32;  // the hash's length (RFC 2104's minimum advice)
inline constexpr std::size_t kUdpMaxKeyBytes = 64;  // SHA-256's block: a longer key would be hashed down

class UdpAuthenticator {
 public:
  // Throws std::invalid_argument unless the key has kUdpMinKeyBytes..kUdpMaxKeyBytes bytes.
  // Not real-time safe.
  explicit UdpAuthenticator(std::span<const std::byte> key);
  ~UdpAuthenticator();  // wipes the keyed states
  UdpAuthenticator(const UdpAuthenticator&) = delete;
  UdpAuthenticator& operator=(const UdpAuthenticator&) = delete;

  // HMAC-SHA-256(key, message). Real-time safe: no allocation.
  void tag(std::span<const std::byte> message, std::span<std::byte, kUdpTagBytes> out) const noexcept;
  // Whether `tag` is the message's, compared in constant time (CRYPTO_memcmp). Real-time safe.
  bool verify(std::span<const std::byte> message, std::span<const std::byte, kUdpTagBytes> tag) const noexcept;

 private:
  struct States;
  std::unique_ptr<States> states_;
};

// Reads a key file: a regular file of kUdpMinKeyBytes..kUdpMaxKeyBytes raw bytes (`openssl
// rand -out KEY 32`), owned by this process's user and readable by its owner only (mode 0600
// or 0400). Throws std::invalid_argument "FILE: ..." saying what is wrong and how to fix it.
// Not real-time safe.
std::vector<std::byte> read_udp_key_file(const std::filesystem::path& file);

// Fills `out` from OpenSSL's RAND_bytes (a session nonce); throws std::runtime_error when the
// generator fails. Not real-time safe.
void random_nonce(std::span<std::byte> out);

}  // namespace rpsd::node
