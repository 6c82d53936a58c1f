// What the record readers open: regular files only (a FIFO is refused without being opened,
// /dev/zero without being read), at most 64 MB, read line by line so that an error on line 5
// is reported without reading the rest of the file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <fstream>
#include <functional>
#include <future>
#include <sstream>
#include <string>

#include "rpsd/ground_motion/at2_reader.h"
#include "rpsd/ground_motion/record_error.h"
#include "rpsd/ground_motion/text_readers.h"
#include "test_files.h"

namespace rpsd::ground_motion {
namespace {

using testing::TempDirTest;

using Reader = std::function<void(const std::filesystem::path&)>;

const Reader kAt2 = [](const std::filesystem::path& f) { (void)read_peer_at2(f); };
const Reader kPlain = [](const std::filesystem::path& f) {
  (void)read_plain_text(f, {0.01, AccelerationUnit::kG, 0, std::nullopt, std::nullopt});
};
const Reader kTimeAcceleration = [](const std::filesystem::path& f) {
  TimeAccelerationOptions options;
  options.unit = AccelerationUnit::kG;
  (void)read_time_acceleration(f, options);
};

// The reader's error, from a thread: a reader that blocked would fail the bound instead of
// hanging the run (a bound on hanging, not on speed).
std::string refusal(const Reader& read, const std::filesystem::path& file) {
  auto result = std::async(std::launch::async, [&read, file]() -> std::string {
    try {
      read(file);
    } catch (const RecordError& e) {
      return e.what();
    }
    return "accepted";
  });
  if (result.wait_for(std::chrono::seconds(20)) != std::future_status::ready) {
    ADD_FAILURE() << file << ": the reader blocked";
    std::abort();  // the thread cannot be joined; end the run rather than hang
  }
  return result.get();
}

// Bytes this process has read so far (Linux: /proc/self/io, rchar).
std::uint64_t bytes_read() {
  std::ifstream io("/proc/self/io");
  std::string key;
  std::uint64_t value = 0;
  while (io >> key >> value) {
    if (key == "rchar:") return value;
  }
  return 0;
}

class RecordFiles : public TempDirTest {};

TEST_F(RecordFiles, DevZeroIsRefusedWithoutBeingRead) {
  for (const Reader* read : {&kAt2, &kPlain, &kTimeAcceleration}) {
    const std::string message = refusal(*read, "/dev/zero");
    EXPECT_NE(message.find("/dev/zero: is a character device; a ground-motion record must be a regular file"),
              std::string::npos)
        << message;
  }
}

TEST_F(RecordFiles, AFifoIsRefusedWithoutBlocking) {
  const auto fifo = dir_ / "record.AT2";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const Reader* read : {&kAt2, &kPlain, &kTimeAcceleration}) {
    const std::string message = refusal(*read, fifo);
    EXPECT_NE(message.find(fifo.string() + ": is a FIFO"), std::string::npos) << message;
  }
}

TEST_F(RecordFiles, ADirectoryIsRefused) {
  const std::string message = refusal(kAt2, dir_);
  EXPECT_NE(message.find(dir_.string() + ": is a directory"), std::string::npos) << message;
}

TEST_F(RecordFiles, ARecordOver64MbIsRefusedBeforeItIsRead) {
  const auto big = write("big.AT2", "");
  std::filesystem::resize_file(big, (64u << 20) + 1);  // sparse: nothing is written
  for (const Reader* read : {&kAt2, &kPlain, &kTimeAcceleration}) {
    const std::string message = refusal(*read, big);
    EXPECT_NE(message.find("big.AT2: has 67108865 bytes; a ground-motion record may have at most 64 MB"),
              std::string::npos)
        << message;
  }
}

// A 60 MB file whose fifth line is wrong: the error names line 5, and the reader has read
// no more than the first chunk of the file.
TEST_F(RecordFiles, AnErrorOnLine5IsReportedWithoutReadingTheRest) {
  struct Case {
    const Reader* read;
    std::string head;
    std::string expected;
  };
  const Case cases[] = {
      {&kAt2,
       "PEER STRONG MOTION DATABASE RECORD\nEVENT\nACCELERATION TIME HISTORY IN UNITS OF G\n"
       "NPTS=  1000, DT= .0100 SEC\n 0.1 0.2 oops 0.3\n",
       ":5:10: expected an acceleration value"},
      {&kPlain, "0.1\n0.2\n0.3\n0.4\noops\n", ":5:1: expected an acceleration value"},
      {&kTimeAcceleration, "0 0.1\n0.01 0.2\n0.02 0.3\n0.03 0.4\n0.04 oops\n", ":5:6: expected an acceleration value"},
  };
  for (const auto& c : cases) {
    const auto file = write("long.txt", c.head);
    std::filesystem::resize_file(file, 60u << 20);  // the rest: zero bytes, never written to disk
    const std::uint64_t before = bytes_read();
    const std::string message = refusal(*c.read, file);
    const std::uint64_t read = bytes_read() - before;
    EXPECT_NE(message.find(file.string() + c.expected), std::string::npos) << message;
    EXPECT_LT(read, 1u << 20) << "bytes read for an error on line 5";
  }
}

}  // namespace
}  // namespace rpsd::ground_motion
