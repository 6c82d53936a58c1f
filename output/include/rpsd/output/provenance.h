// Where a result came from: the rpsd that wrote it (version, commit) and every file it read,
// each with its SHA-256, so that a summary.json names exactly what produced it. Not
// real-time safe.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace rpsd::output {

// The SHA-256 of a file's bytes, as 64 lowercase hex digits. Throws std::runtime_error naming
// the file when it cannot be read.
std::string sha256_of_file(const std::filesystem::path& file);

// {"rpsd": {"version", "commit"}, "inputs": [{"file", "sha256"}, ...]} for the files a run
// read (a scenario and what it names, a site-server file).
nlohmann::json provenance_json(const std::vector<std::filesystem::path>& input_files);

}  // namespace rpsd::output
