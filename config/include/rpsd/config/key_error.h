// A value refused at a key, with the key's path carried typed ("limits[0].max_stroke_m"), so
// that a file reader can point at the key's line without parsing the message. what() reads
// "path: problem", as a plain std::invalid_argument naming its key always has.
#pragma once

#include <stdexcept>
#include <string>
#include <utility>

namespace rpsd::config {

class KeyError : public std::invalid_argument {
 public:
  KeyError(const std::string& key, const std::string& problem) : KeyError(key, key, problem) {}

  // The same problem with its key one section down: "parent.key".
  KeyError under(const std::string& parent) const { return {parent + "." + path_, leaf_, problem_}; }

  const std::string& path() const noexcept { return path_; }  // "limits[0].max_stroke_m"
  const std::string& leaf() const noexcept { return leaf_; }  // "max_stroke_m": the key in its own section
  const std::string& problem() const noexcept { return problem_; }

 private:
  KeyError(const std::string& path, const std::string& leaf, const std::string& problem)
      : std::invalid_argument(path + ": " + problem), path_(path), leaf_(leaf), problem_(problem) {}

  std::string path_;
  std::string leaf_;
  std::string problem_;
};

}  // namespace rpsd::config
