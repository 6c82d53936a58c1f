#include "claimed_dds_domain.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace rpsd::testing {

namespace {

namespace fs = std::filesystem;

// A claim whose pid file names no live process, or that has had no pid file for over a
// second (its claimant died between making the folder and writing the file).
bool is_stale(const fs::path& claim) {
  std::ifstream in(claim / "pid");
  long pid = 0;
  if (in >> pid && pid > 0) return ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
  std::error_code ec;
  const auto made = fs::last_write_time(claim, ec);
  return !ec && fs::file_time_type::clock::now() - made > std::chrono::seconds(1);
}

// Takes the domain's folder for this process: made anew, or a stale one moved aside first
// (rename is atomic: of two processes taking over the same stale claim, one wins).
bool try_claim(const fs::path& claim) {
  std::error_code ec;
  if (!fs::create_directory(claim, ec)) {
    if (ec || !is_stale(claim)) return false;
    const fs::path aside = claim.string() + ".stale." + std::to_string(::getpid());
    fs::rename(claim, aside, ec);
    if (ec) return false;
    fs::remove_all(aside, ec);
    if (!fs::create_directory(claim, ec)) return false;
  }
  std::ofstream(claim / "pid") << ::getpid() << '\n';
  return true;
}

}  // namespace

DdsDomainClaim::DdsDomainClaim(const fs::path& dir, std::uint32_t first, std::uint32_t count) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("DdsDomainClaim: cannot make " + dir.string() + ": " + ec.message());
  // From a number drawn from the pid, so that claimants rarely try the same folders.
  const std::uint32_t start = count > 0 ? static_cast<std::uint32_t>(::getpid()) % count : 0;
  for (std::uint32_t i = 0; i < count; ++i) {
    const std::uint32_t domain = first + (start + i) % count;
    const fs::path claim = dir / std::to_string(domain);
    if (try_claim(claim)) {
      domain_ = domain;
      path_ = claim;
      owner_pid_ = ::getpid();
      return;
    }
  }
  throw std::runtime_error("DdsDomainClaim: each of the " + std::to_string(count) + " domains from " +
                           std::to_string(first) + " under " + dir.string() + " is held by a live process");
}

DdsDomainClaim::~DdsDomainClaim() {
  if (owner_pid_ != ::getpid()) return;
  std::error_code ec;
  fs::remove_all(path_, ec);
}

std::uint32_t claimed_dds_domain() {
  // Released by its destructor when the process exits.
  static const DdsDomainClaim claim(fs::temp_directory_path() / "rpsd-test-claims" / "dds-domain", kFirstClaimedDomain,
                                    kClaimedDomains);
  return claim.domain();
}

}  // namespace rpsd::testing
