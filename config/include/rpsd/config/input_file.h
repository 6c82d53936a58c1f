// A file a user names, opened the one safe way: regular files only (a FIFO, a device or a
// directory is refused from its stat, before an open() that could block on it or read
// forever), at most a stated size, read line by line so that an error early in the file is
// reported without reading the rest. Every message names the file. Not real-time safe.
#pragma once

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace rpsd::config {

class InputFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The size caps of the files rpsd reads, in bytes.
// yaml-cpp holds about 500 bytes per list item: 1 MB of YAML parses in under 300 MB.
inline constexpr std::uintmax_t kMaxYamlFileBytes = 1u << 20;            // scenarios, studies, nodes, servo parameters
inline constexpr std::uintmax_t kMaxRecordFileBytes = 64u << 20;         // ground-motion records
inline constexpr std::uintmax_t kMaxMatrixMarketFileBytes = 256u << 20;  // structural matrices

// Throws InputFileError "FILE: ..." unless `file` is a regular file of at most max_bytes;
// `what` names the file's kind ("ground-motion record") in the message. Opens nothing.
void check_input_file(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what);

class InputFile {
 public:
  // check_input_file, then opens it (non-blocking, and checked again on the open file).
  InputFile(const std::filesystem::path& file, std::uintmax_t max_bytes, std::string_view what);
  ~InputFile();
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  // The next line without its '\n'; false at the end. Throws if the file grows past max_bytes.
  bool next_line(std::string& line);
  // The rest of the file.
  std::string read_all();
  // The size the file had when it was opened.
  std::uintmax_t size_bytes() const { return size_bytes_; }
  const std::string& name() const { return name_; }

 private:
  bool fill();

  std::string name_;
  std::uintmax_t max_bytes_;
  std::uintmax_t size_bytes_ = 0;
  std::uintmax_t read_bytes_ = 0;
  int fd_ = -1;
  std::string buffer_;
  std::size_t start_ = 0;
  bool end_ = false;
};

// "4 MB" for whole mebibytes, else the byte count.
std::string byte_size_text(std::uintmax_t bytes);

}  // namespace rpsd::config
