// A DDS domain for one test process that no other live test on this machine holds, so that
// tests run at once (ctest -j, two checkouts) never hear each other. The claim is a folder
// made atomically (mkdir) under the system's temporary folder,
// rpsd-test-claims/dds-domain/N, holding the claimant's pid; a claim whose process has gone is
// taken over. The system tests claim from the same folders and range (tests/system/lib.sh).
// Domains 200..232 are left to the tests that name a fixed domain of their own, each its own.
#pragma once

#include <cstdint>
#include <filesystem>

namespace rpsd::testing {

inline constexpr std::uint32_t kFirstClaimedDomain = 1, kClaimedDomains = 199;

// The same number for every call in a process; released when the process exits. Throws
// std::runtime_error when every domain of the range is held by a live process.
std::uint32_t claimed_dds_domain();

// One claim among `count` domains from `first`, in the folder `dir`, held until destroyed:
// what claimed_dds_domain() holds, in a folder of the caller's choosing. Throws
// std::runtime_error naming the folder when each of them is held by a live process.
class DdsDomainClaim {
 public:
  DdsDomainClaim(const std::filesystem::path& dir, std::uint32_t first, std::uint32_t count);
  ~DdsDomainClaim();
  DdsDomainClaim(const DdsDomainClaim&) = delete;
  DdsDomainClaim& operator=(const DdsDomainClaim&) = delete;

  std::uint32_t domain() const { return domain_; }

 private:
  std::uint32_t domain_ = 0;
  std::filesystem::path path_;
  long owner_pid_ = 0;  // a forked child that exits does not release its parent's claim
};

}  // namespace rpsd::testing
