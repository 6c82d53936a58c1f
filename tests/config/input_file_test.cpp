// A file a user names: a FIFO, a device or a directory is refused at once (a FIFO must not
// even be opened, since open() blocks until a writer comes), and so is a file over its cap.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>

#include "rpsd/config/input_file.h"

namespace rpsd::config {
namespace {

namespace fs = std::filesystem;

class InputFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::temp_directory_path() / ("rpsd-input-" + std::to_string(::getpid()) + "-" + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  fs::path write(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }

  fs::path dir_;
};

// The refusal's message, from a thread: a reader that blocked would fail the bound instead
// of hanging the test run (the bound is on hanging, not on speed).
std::string refusal(const fs::path& file, std::uintmax_t max_bytes = 1024) {
  auto result = std::async(std::launch::async, [file, max_bytes]() -> std::string {
    try {
      InputFile in(file, max_bytes, "test file");
      std::string line;
      while (in.next_line(line)) {
      }
    } catch (const InputFileError& e) {
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

TEST_F(InputFileTest, ReadsLinesOfARegularFile) {
  InputFile in(write("a.txt", "one\ntwo\r\n\nlast"), 1024, "test file");
  EXPECT_EQ(in.size_bytes(), 14u);
  std::string line;
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, "one");
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, "two\r");
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, "");
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, "last");
  EXPECT_FALSE(in.next_line(line));
}

TEST_F(InputFileTest, ALineLongerThanTheReadChunkIsWhole) {
  const std::string long_line(200'000, 'x');
  InputFile in(write("long.txt", long_line + "\nend\n"), 1 << 20, "test file");
  std::string line;
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, long_line);
  ASSERT_TRUE(in.next_line(line));
  EXPECT_EQ(line, "end");
  EXPECT_FALSE(in.next_line(line));
}

TEST_F(InputFileTest, AFifoIsRefusedWithoutBlocking) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string message = refusal(fifo);
  EXPECT_NE(message.find(fifo.string() + ": is a FIFO (named pipe); a test file must be a regular file"),
            std::string::npos)
      << message;
}

TEST_F(InputFileTest, ADeviceIsRefused) {
  const std::string message = refusal("/dev/zero");
  EXPECT_NE(message.find("/dev/zero: is a character device; a test file must be a regular file"), std::string::npos)
      << message;
}

TEST_F(InputFileTest, ADirectoryIsRefused) {
  const std::string message = refusal(dir_);
  EXPECT_NE(message.find(dir_.string() + ": is a directory"), std::string::npos) << message;
}

TEST_F(InputFileTest, AFileOverItsCapIsRefusedBeforeItIsRead) {
  const fs::path big = write("big.txt", "");
  fs::resize_file(big, (4u << 20) + 1);  // sparse: nothing is written
  const std::string message = refusal(big, 4u << 20);
  EXPECT_NE(message.find(big.string() + ": has 4194305 bytes; a test file may have at most 4 MB"), std::string::npos)
      << message;
  EXPECT_EQ(refusal(write("small.txt", std::string(1024, 'x')), 1024), "accepted");
}

TEST_F(InputFileTest, AMissingFileIsNamed) {
  const std::string message = refusal(dir_ / "none.txt");
  EXPECT_NE(message.find("none.txt: does not exist"), std::string::npos) << message;
}

TEST_F(InputFileTest, CheckingOpensNothing) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_THROW(check_input_file(fifo, 1024, "test file"), InputFileError);
  EXPECT_NO_THROW(check_input_file(write("ok.txt", "1"), 1024, "test file"));
}

}  // namespace
}  // namespace rpsd::config
