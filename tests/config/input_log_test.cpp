#include "rpsd/config/input_log.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rpsd/config/input_file.h"

namespace rpsd::config {
namespace {

namespace fs = std::filesystem;

fs::path write_file(const std::string& name) {
  const fs::path path = fs::temp_directory_path() / ("rpsd-input-log-" + name);
  std::ofstream(path) << "x\n";
  return path;
}

// Every file opened while a log lives is listed once, absolute, in the order first opened;
// an inner log takes what is opened while it lives, and the outer one goes on after it.
TEST(InputLog, ListsEachOpenedFileOnceInOrderInTheInnermostLog) {
  const fs::path a = write_file("a"), b = write_file("b"), c = write_file("c");
  InputLog outer;
  { InputFile file(a, 100, "test file"); }
  {
    InputLog inner;
    InputFile file(b, 100, "test file");
    EXPECT_EQ(inner.files(), std::vector<fs::path>{b});
  }
  { InputFile file(c, 100, "test file"); }
  { InputFile file(a.parent_path() / "." / a.filename(), 100, "test file"); }  // a again, spelt otherwise
  EXPECT_EQ(outer.files(), (std::vector<fs::path>{a, c}));
}

// Outside any log nothing is kept, and a file refused is not an input.
TEST(InputLog, KeepsNothingWithoutALogAndNoRefusedFile) {
  const fs::path a = write_file("d");
  { InputFile file(a, 100, "test file"); }
  InputLog log;
  EXPECT_THROW(InputFile(fs::temp_directory_path(), 100, "test file"), InputFileError);
  EXPECT_TRUE(log.files().empty());
}

}  // namespace
}  // namespace rpsd::config
