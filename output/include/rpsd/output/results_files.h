// Results are whole or say they are not: each file is written whole or not at all (a
// temporary file beside it, synced, then renamed over it), every write is checked, and an
// output folder holds one run's files only. Not real-time safe.
#pragma once

#include <cstddef>
#include <filesystem>
#include <stdexcept>
#include <string_view>

namespace rpsd::output {

// A result file could not be written (a full disk, no permission): exit code 5.
class ResultsNotWritten : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The output folder holds another run's files and the user did not ask to replace them, or
// it is not a folder rpsd wrote: exit code 2.
class OutputFolderInUse : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Makes `dir` ready for one run: created when missing; when it holds anything, refused
// unless `replace`, and then emptied first, but only if rpsd wrote it (it holds a
// summary.json, effective-scenario.yaml or dry-run.json), so that a mistyped --out never
// clears someone's home folder. An --out the file system cannot hold (a name longer than
// NAME_MAX, a path too long for the files written in it) is std::invalid_argument: exit 2.
void prepare_results_folder(const std::filesystem::path& dir, bool replace);

// Writes `text` to `file`: the old file, if any, stays until the new one is whole on disk.
// Throws ResultsNotWritten naming the file and the system's reason.
void write_file_whole(const std::filesystem::path& file, std::string_view text);

// summary.json is reserved when a run starts: written "running", padded with spaces (valid
// JSON) to kSummaryReservedBytes, so that the final summary fits even on a disk the run has
// filled. write_summary writes it whole when it can and, on a full disk, over the reserved
// bytes in place; it throws ResultsNotWritten when neither works.
inline constexpr std::size_t kSummaryReservedBytes = 64 * 1024;
void reserve_summary(const std::filesystem::path& file, std::string_view running_text);
void write_summary(const std::filesystem::path& file, std::string_view text);

}  // namespace rpsd::output
