#include "rpsd/output/results_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <string>
#include <system_error>

namespace rpsd::output {
namespace {

[[noreturn]] void not_written(const std::filesystem::path& file, int error) {
  throw ResultsNotWritten(file.string() + ": cannot write: " + std::strerror(error));
}

bool written_by_rpsd(const std::filesystem::path& dir) {
  for (const char* marker : {"summary.json", "effective-scenario.yaml", "dry-run.json"}) {
    std::error_code ignored;
    if (std::filesystem::is_regular_file(dir / marker, ignored)) return true;
  }
  return false;
}

// Writes all of `text` to fd; false (errno set) when a write fails.
bool write_all(int fd, std::string_view text) {
  const char* next = text.data();
  std::size_t left = text.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, next, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = ENOSPC;
      return false;
    }
    next += n;
    left -= static_cast<std::size_t>(n);
  }
  return true;
}

std::string padded(std::string_view text, std::size_t size) {
  std::string out(text);
  if (out.size() < size) out.append(size - out.size(), ' ');
  return out;
}

// The longest name rpsd writes inside an output folder, with room to spare: a batch's
// "run_001/plot_reference_history.csv.partial".
constexpr std::size_t kLongestNameInside = 64;

// An --out the system cannot hold is the user's input, not a failed write (exit 2, not 5):
// a name longer than NAME_MAX, or a path with no room left for the files rpsd writes in it.
void require_a_path_that_fits(const std::filesystem::path& dir) {
  for (const auto& part : dir) {
    if (part.native().size() > NAME_MAX) {
      throw std::invalid_argument("--out " + dir.string().substr(0, 80) + "...: a name in the path is " +
                                  std::to_string(part.native().size()) + " characters long, more than the " +
                                  std::to_string(NAME_MAX) + " a file system allows");
    }
  }
  std::error_code ignored;
  const std::size_t length = std::filesystem::absolute(dir, ignored).native().size();
  if (length + kLongestNameInside >= PATH_MAX) {
    throw std::invalid_argument("--out " + dir.string().substr(0, 80) + "...: the path is " + std::to_string(length) +
                                " characters long; with the files rpsd writes in it, it must stay below " +
                                std::to_string(PATH_MAX - kLongestNameInside));
  }
}

}  // namespace

void prepare_results_folder(const std::filesystem::path& dir, bool replace) {
  require_a_path_that_fits(dir);
  std::error_code error;
  const auto status = std::filesystem::symlink_status(dir, error);
  if (!std::filesystem::exists(status)) {
    std::filesystem::create_directories(dir, error);
    if (error) throw ResultsNotWritten(dir.string() + ": cannot create the output folder: " + error.message());
    return;
  }
  if (!std::filesystem::is_directory(std::filesystem::status(dir, error))) {
    throw OutputFolderInUse(dir.string() + ": --out names a file, not a folder");
  }
  if (std::filesystem::is_empty(dir, error)) return;
  if (!replace) {
    throw OutputFolderInUse(dir.string() +
                            ": the output folder is not empty; an earlier run's files would sit beside this "
                            "run's. Choose a new --out, or add --replace to clear it first");
  }
  if (!written_by_rpsd(dir)) {
    throw OutputFolderInUse(dir.string() +
                            ": --replace clears only folders rpsd wrote (with a summary.json, "
                            "effective-scenario.yaml or dry-run.json), and this one has none; empty it yourself");
  }
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::filesystem::remove_all(entry.path(), error);
    if (error)
      throw ResultsNotWritten(entry.path().string() + ": cannot remove it to replace the folder: " + error.message());
  }
}

void write_file_whole(const std::filesystem::path& file, std::string_view text) {
  const std::filesystem::path temporary = file.string() + ".partial";
  const int fd = ::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) not_written(file, errno);
  if (!write_all(fd, text)) {
    const int error = errno;
    ::close(fd);
    ::unlink(temporary.c_str());
    not_written(file, error);
  }
  int error = ::fsync(fd) == 0 ? 0 : errno;
  if (::close(fd) != 0 && error == 0) error = errno;
  if (error != 0) {
    ::unlink(temporary.c_str());
    not_written(file, error);
  }
  if (::rename(temporary.c_str(), file.c_str()) != 0) {
    error = errno;
    ::unlink(temporary.c_str());
    not_written(file, error);
  }
}

void reserve_summary(const std::filesystem::path& file, std::string_view running_text) {
  write_file_whole(file, padded(running_text, kSummaryReservedBytes));
}

void write_summary(const std::filesystem::path& file, std::string_view text) {
  try {
    write_file_whole(file, text);
    return;
  } catch (const ResultsNotWritten&) {
    // The disk may be full: the reserved file's blocks are still there to be overwritten.
  }
  const int fd = ::open(file.c_str(), O_WRONLY | O_CLOEXEC);
  if (fd < 0) not_written(file, errno);
  struct stat st {};
  if (::fstat(fd, &st) != 0 || static_cast<std::size_t>(st.st_size) < text.size()) {
    ::close(fd);
    not_written(file, ENOSPC);
  }
  const bool written = write_all(fd, padded(text, static_cast<std::size_t>(st.st_size))) && ::fsync(fd) == 0;
  const int error = errno;
  if (::close(fd) != 0 || !written) not_written(file, written ? errno : error);
}

}  // namespace rpsd::output
