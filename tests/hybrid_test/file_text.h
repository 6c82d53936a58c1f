// A file's whole text, defined once: a unity build compiles all of hybrid_test_tests' files as
// one translation unit.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace rpsd::hybrid_test {

inline std::string text_of(const std::filesystem::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace rpsd::hybrid_test
