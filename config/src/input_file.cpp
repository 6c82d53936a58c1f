#include "rpsd/config/input_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "rpsd/config/input_log.h"

namespace rpsd::config {
namespace {

std::string kind_of(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

[[noreturn]] void refuse(const std::string& name, const std::string& message) {
  throw InputFileError(name + ": " + message);
}

void check_stat(const struct stat& info, const std::string& name, std::uintmax_t max_bytes, std::string_view what) {
  if (!S_ISREG(info.st_mode)) {
    refuse(name, "is " + kind_of(info.st_mode) + "; a " + std::string(what) + " must be a regular file");
  }
  const auto size = static_cast<std::uintmax_t>(info.st_size);
  if (size > max_bytes) {
    refuse(name, "has " + std::to_string(size) + " bytes; a " + std::string(what) + " may have at most " +
                     byte_size_text(max_bytes));
  }
}

}  // namespace

std::string byte_size_text(std::uintmax_t bytes) {
  constexpr std::uintmax_t mebibyte = 1u << 20;
  if (bytes % mebibyte == 0) return std::to_string(bytes / mebibyte) + " MB";
  return std::to_string(bytes) + " bytes";
}

void check_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what) {
  const std::string name = file.string();
  struct stat info {};
  if (::stat(name.c_str(), &info) != 0) {
    const int error = errno;
    if (error == ENOENT) refuse(name, "does not exist");
    refuse(name, "cannot be read: " + std::string(std::strerror(error)));
  }
  check_stat(info, name, max_bytes, what);
}

InputFile::InputFile(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what)
    : name_(file.string()), max_bytes_(max_bytes) {
  check_input_file(file, max_bytes, what);
  // O_NONBLOCK: should the path have become a FIFO since the stat, open() returns at once.
  fd_ = ::open(name_.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd_ < 0) refuse(name_, "cannot be opened for reading: " + std::string(std::strerror(errno)));
  struct stat info {};
  if (::fstat(fd_, &info) != 0) {
    const int error = errno;
    ::close(fd_);
    refuse(name_, "cannot be read: " + std::string(std::strerror(error)));
  }
  try {
    check_stat(info, name_, max_bytes, what);
  } catch (...) {
    ::close(fd_);
    throw;
  }
  size_bytes_ = static_cast<std::uintmax_t>(info.st_size);
  InputLog::note(file);
}

InputFile::~InputFile() {
  if (fd_ >= 0) ::close(fd_);
}

bool InputFile::fill() {
  if (end_) return false;
  if (start_ > 0) {
    buffer_.erase(0, start_);
    start_ = 0;
  }
  constexpr std::size_t kChunk = 64 * 1024;
  const std::size_t old_size = buffer_.size();
  buffer_.resize(old_size + kChunk);
  ssize_t got = 0;
  do {
    got = ::read(fd_, buffer_.data() + old_size, kChunk);
  } while (got < 0 && errno == EINTR);
  if (got < 0) {
    const int error = errno;
    buffer_.resize(old_size);
    refuse(name_, "read error: " + std::string(std::strerror(error)));
  }
  buffer_.resize(old_size + static_cast<std::size_t>(got));
  if (got == 0) {
    end_ = true;
    return false;
  }
  read_bytes_ += static_cast<std::uintmax_t>(got);
  // The size was checked at the open; a file that grows while it is read stops here.
  if (read_bytes_ > max_bytes_) refuse(name_, "grew past " + byte_size_text(max_bytes_) + " while it was read");
  return true;
}

bool InputFile::next_line(std::string& line) {
  std::size_t from = start_;  // each byte is searched for '\n' once, however long the line
  for (;;) {
    const auto newline = buffer_.find('\n', from);
    if (newline != std::string::npos) {
      line.assign(buffer_, start_, newline - start_);
      start_ = newline + 1;
      return true;
    }
    from = buffer_.size() - start_;  // fill() drops the bytes before start_
    if (!fill()) {
      if (start_ >= buffer_.size()) return false;
      line.assign(buffer_, start_, std::string::npos);
      start_ = buffer_.size();
      return true;
    }
  }
}

std::string InputFile::read_all() {
  while (fill()) {
  }
  std::string rest = buffer_.substr(start_);
  buffer_.clear();
  start_ = 0;
  return rest;
}

}  // namespace rpsd::config
