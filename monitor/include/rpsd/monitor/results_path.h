// The viewer reads only files under --results: a path from a browser is relative, has no
// `..` and no NUL, and what it names (symbolic links followed) must lie under the results
// folder, or it is refused.
#pragma once

#include <filesystem>
#include <optional>
#include <string_view>

namespace rpsd::monitor {

// The canonical path of `relative` under `root` ("" is root itself), if it exists and lies
// under root; nullopt otherwise. Not real-time safe (it asks the file system).
std::optional<std::filesystem::path> resolve_under(const std::filesystem::path& root, std::string_view relative);

// A file name the viewer serves from a folder: one name (no separator), of a kind rpsd
// writes (.csv, .json, .yaml, .md, .png, .txt).
bool servable_file_name(std::string_view name);

}  // namespace rpsd::monitor
