#include "unique_temp_file.h"

#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <vector>

namespace rpsd::bench {

UniqueTempFile::UniqueTempFile(const std::string& stem, const std::string& suffix) {
  const std::string pattern = (std::filesystem::temp_directory_path() / (stem + "XXXXXX" + suffix)).string();
  std::vector<char> name(pattern.begin(), pattern.end());
  name.push_back('\0');
  const int fd = ::mkstemps(name.data(), static_cast<int>(suffix.size()));
  if (fd < 0) throw std::runtime_error(pattern + ": cannot create a temporary file: " + std::strerror(errno));
  ::close(fd);
  path_ = name.data();
}

UniqueTempFile::~UniqueTempFile() {
  std::error_code ignored;
  std::filesystem::remove(path_, ignored);
}

}  // namespace rpsd::bench
