// The page's files, built into the binary (cmake/EmbedFiles.cmake over monitor/web/): the
// page works on a lab PC with nothing beside rpsd and no network beyond the monitor's.
#pragma once

#include <optional>
#include <string_view>

namespace rpsd::monitor {

struct WebAsset {
  std::string_view bytes;
  std::string_view content_type;
};

// "index.html", "monitor.js", "vendor/uplot/uPlot.iife.min.js", ...; nullopt for any other.
std::optional<WebAsset> find_web_asset(std::string_view path);

}  // namespace rpsd::monitor
