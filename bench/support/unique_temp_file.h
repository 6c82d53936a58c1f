// A temporary file no other process shares: created empty under the system's temporary
// folder with a name drawn by mkstemps, so two bench runs at once never write the same file,
// and removed by the destructor whatever happens. Not real-time safe (benchmark drivers only).
#pragma once

#include <filesystem>
#include <string>

namespace rpsd::bench {

class UniqueTempFile {
 public:
  // `stem` and `suffix` frame the drawn part: "rpsd-bench-time_history-" and ".csv" give
  // /tmp/rpsd-bench-time_history-Ab12Cd.csv. Throws std::runtime_error naming the pattern
  // when the file cannot be created.
  UniqueTempFile(const std::string& stem, const std::string& suffix);
  ~UniqueTempFile();
  UniqueTempFile(const UniqueTempFile&) = delete;
  UniqueTempFile& operator=(const UniqueTempFile&) = delete;

  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

}  // namespace rpsd::bench
