// The kernel's preemption model as rpsd host-check reads it: each source in its order, on
// files written here in the kernel's own formats.
#include "rpsd/realtime/kernel_preemption.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace rpsd::realtime {
namespace {

namespace fs = std::filesystem;

class KernelPreemptionFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("rpsd-kernel-preemption-" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    files_.realtime_flag = dir_ / "realtime";
    files_.debugfs_preempt = dir_ / "preempt";
    files_.cmdline = dir_ / "cmdline";
    files_.config_gz = dir_ / "config.gz";
    files_.version = "#1 SMP PREEMPT_DYNAMIC Thu Jan  1 00:00:00 UTC 2026";
  }
  void TearDown() override { fs::remove_all(dir_); }

  void write(const fs::path& file, const std::string& text) { std::ofstream(file) << text; }
  void write_config(const std::string& text) {
    gzFile out = gzopen(files_.config_gz.c_str(), "wb");
    ASSERT_NE(out, nullptr);
    gzputs(out, text.c_str());
    gzclose(out);
  }

  fs::path dir_;
  KernelFiles files_;
};

TEST_F(KernelPreemptionFiles, TheSchedulersDebugfsFileNamesTheActiveModelInParentheses) {
  write(files_.debugfs_preempt, "none voluntary (full) lazy\n");
  write(files_.cmdline, "quiet preempt=none\n");  // debugfs tells what is in force now
  const KernelPreemption k = read_kernel_preemption(files_);
  EXPECT_EQ(k.model, PreemptionModel::kFull);
  EXPECT_EQ(k.source, files_.debugfs_preempt.string());
  write(files_.debugfs_preempt, "(none) voluntary full lazy\n");
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kNone);
}

TEST_F(KernelPreemptionFiles, ADynamicKernelBootedWithPreemptTakesTheBootParameter) {
  write(files_.cmdline, "console=ttyS0 preempt=voluntary quiet -- --init-option preempt=full\n");
  write_config("CONFIG_PREEMPT_NONE=y\n");
  const KernelPreemption k = read_kernel_preemption(files_);
  EXPECT_EQ(k.model, PreemptionModel::kVoluntary);
  EXPECT_NE(k.source.find("preempt=voluntary"), std::string::npos) << k.source;
}

TEST_F(KernelPreemptionFiles, ADynamicKernelBootedWithoutPreemptRunsItsBuildsDefault) {
  // This VM's case: PREEMPT_DYNAMIC, no preempt= (what follows "--" is init's), debugfs
  // unreadable, and the build's default none.
  write(files_.cmdline, "console=ttyS0 quiet -- --firecracker-init preempt=full\n");
  write_config(
      "# CONFIG_PREEMPT_VOLUNTARY is not set\nCONFIG_PREEMPT_BUILD=y\nCONFIG_PREEMPT_NONE=y\n"
      "# CONFIG_PREEMPT is not set\nCONFIG_PREEMPT_COUNT=y\nCONFIG_PREEMPT_DYNAMIC=y\n");
  const KernelPreemption k = read_kernel_preemption(files_);
  EXPECT_EQ(k.model, PreemptionModel::kNone);
  EXPECT_NE(k.source.find("config.gz"), std::string::npos) << k.source;
  EXPECT_FALSE(preempts_for_real_time(k.model));
}

TEST_F(KernelPreemptionFiles, TheConfigurationsChoiceIsReadWhateverOtherPreemptKeysItHas) {
  write_config("CONFIG_PREEMPT_BUILD=y\nCONFIG_PREEMPT=y\nCONFIG_PREEMPT_COUNT=y\nCONFIG_PREEMPT_RCU=y\n");
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kFull);
  write_config("CONFIG_PREEMPT_BUILD=y\nCONFIG_PREEMPT_LAZY=y\n");
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kLazy);
  write_config("CONFIG_PREEMPT=y\nCONFIG_PREEMPT_RT=y\n");
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kRealTime);
}

TEST_F(KernelPreemptionFiles, APreemptRtKernelIsKnownByItsFlagOrItsVersion) {
  write(files_.realtime_flag, "1\n");
  write(files_.debugfs_preempt, "(none) voluntary full lazy\n");
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kRealTime);
  fs::remove(files_.realtime_flag);
  files_.version = "#1 SMP PREEMPT_RT Thu Jan  1 00:00:00 UTC 2026";
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kRealTime);
}

TEST_F(KernelPreemptionFiles, WithNothingReadableTheVersionDecidesOrItIsUnknown) {
  files_.version = "#1 SMP PREEMPT Thu Jan  1 00:00:00 UTC 2026";
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kFull);
  files_.version = "#1 SMP Thu Jan  1 00:00:00 UTC 2026";  // none or voluntary
  EXPECT_EQ(read_kernel_preemption(files_).model, PreemptionModel::kUnknown);
  files_.version = "#1 SMP PREEMPT_DYNAMIC Thu Jan  1 00:00:00 UTC 2026";
  const KernelPreemption k = read_kernel_preemption(files_);
  EXPECT_EQ(k.model, PreemptionModel::kUnknown);
  EXPECT_FALSE(preempts_for_real_time(k.model));
}

TEST(KernelPreemption, OnlyFullLazyAndRtPreemptForARealTimeThread) {
  EXPECT_FALSE(preempts_for_real_time(PreemptionModel::kNone));
  EXPECT_FALSE(preempts_for_real_time(PreemptionModel::kVoluntary));
  EXPECT_FALSE(preempts_for_real_time(PreemptionModel::kUnknown));
  EXPECT_TRUE(preempts_for_real_time(PreemptionModel::kFull));
  EXPECT_TRUE(preempts_for_real_time(PreemptionModel::kLazy));
  EXPECT_TRUE(preempts_for_real_time(PreemptionModel::kRealTime));
  EXPECT_EQ(preemption_name(PreemptionModel::kRealTime), "rt");
  EXPECT_EQ(preemption_name(PreemptionModel::kNone), "none");
}

TEST(KernelPreemption, ThisHostsModelIsReadWithoutThrowing) {
  const KernelPreemption k = read_kernel_preemption();
  EXPECT_FALSE(k.source.empty());
}

}  // namespace
}  // namespace rpsd::realtime
