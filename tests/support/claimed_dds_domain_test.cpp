#include "claimed_dds_domain.h"

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

namespace rpsd::testing {
namespace {

namespace fs = std::filesystem;

class DdsDomainClaimTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rpsd-claims-test-" + std::to_string(::getpid()) + "-" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  // A claim folder of domain `domain` naming process `pid`.
  void held_by(std::uint32_t domain, long pid) const {
    fs::create_directories(dir_ / std::to_string(domain));
    std::ofstream(dir_ / std::to_string(domain) / "pid") << pid << '\n';
  }
  static long pid_of_a_finished_process() {
    const pid_t child = ::fork();
    if (child == 0) ::_exit(0);
    int status = 0;
    ::waitpid(child, &status, 0);
    return child;
  }

  fs::path dir_;
};

TEST_F(DdsDomainClaimTest, TwoClaimsHoldTwoDomainsOfTheRangeAndTheirFoldersNameThisProcess) {
  const DdsDomainClaim a(dir_, 40, 2);
  const DdsDomainClaim b(dir_, 40, 2);
  EXPECT_NE(a.domain(), b.domain());
  for (const auto* claim : {&a, &b}) {
    EXPECT_GE(claim->domain(), 40u);
    EXPECT_LE(claim->domain(), 41u);
    std::ifstream pid(dir_ / std::to_string(claim->domain()) / "pid");
    long written = 0;
    ASSERT_TRUE(pid >> written);
    EXPECT_EQ(written, ::getpid());
  }
}

TEST_F(DdsDomainClaimTest, ADomainHeldByALiveProcessIsNotTaken) {
  held_by(7, ::getppid());
  EXPECT_THROW(DdsDomainClaim(dir_, 7, 1), std::runtime_error);
  held_by(8, ::getppid());
  const DdsDomainClaim claim(dir_, 7, 3);
  EXPECT_EQ(claim.domain(), 9u);
}

TEST_F(DdsDomainClaimTest, ADomainHeldByAProcessThatHasGoneIsTakenOver) {
  held_by(7, pid_of_a_finished_process());
  const DdsDomainClaim claim(dir_, 7, 1);
  EXPECT_EQ(claim.domain(), 7u);
}

TEST_F(DdsDomainClaimTest, AClaimBeingWrittenIsNotTakenButOneLeftWithoutItsPidIs) {
  fs::create_directories(dir_ / "7");  // made this instant, its pid file not yet written
  EXPECT_THROW(DdsDomainClaim(dir_, 7, 1), std::runtime_error);
  fs::last_write_time(dir_ / "7", fs::file_time_type::clock::now() - std::chrono::seconds(5));
  const DdsDomainClaim claim(dir_, 7, 1);
  EXPECT_EQ(claim.domain(), 7u);
}

TEST_F(DdsDomainClaimTest, ReleasedWhenDestroyed) {
  { const DdsDomainClaim claim(dir_, 7, 1); }
  EXPECT_FALSE(fs::exists(dir_ / "7"));
  const DdsDomainClaim again(dir_, 7, 1);
  EXPECT_EQ(again.domain(), 7u);
}

TEST_F(DdsDomainClaimTest, AForkedChildThatExitsKeepsItsParentsClaim) {
  const DdsDomainClaim claim(dir_, 7, 1);
  const pid_t child = ::fork();
  if (child == 0) {
    claim.~DdsDomainClaim();  // what the child's exit() would run for a static claim
    ::_exit(0);
  }
  int status = 0;
  ::waitpid(child, &status, 0);
  EXPECT_TRUE(fs::exists(dir_ / "7" / "pid"));
}

TEST_F(DdsDomainClaimTest, WhenEveryDomainIsHeldTheErrorNamesTheFolder) {
  held_by(7, ::getppid());
  try {
    const DdsDomainClaim claim(dir_, 7, 1);
    FAIL() << "claimed a held domain";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(dir_.string()), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace rpsd::testing
