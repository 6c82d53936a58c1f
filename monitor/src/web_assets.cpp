#include "rpsd/monitor/web_assets.h"

#include <cstddef>

namespace rpsd::monitor {
namespace detail {
struct EmbeddedAsset {
  std::string_view path;
  std::string_view bytes;
};
extern const EmbeddedAsset kEmbeddedAssets[];  // generated: web_assets_data.cpp
extern const std::size_t kEmbeddedAssetCount;
}  // namespace detail

namespace {
std::string_view content_type_of(std::string_view path) {
  const auto ends = [&](std::string_view ext) {
    return path.size() >= ext.size() && path.substr(path.size() - ext.size()) == ext;
  };
  if (ends(".html")) return "text/html; charset=utf-8";
  if (ends(".js")) return "text/javascript; charset=utf-8";
  if (ends(".css")) return "text/css; charset=utf-8";
  return "text/plain; charset=utf-8";
}
}  // namespace

std::optional<WebAsset> find_web_asset(std::string_view path) {
  for (std::size_t i = 0; i < detail::kEmbeddedAssetCount; ++i) {
    if (detail::kEmbeddedAssets[i].path == path)
      return WebAsset{detail::kEmbeddedAssets[i].bytes, content_type_of(path)};
  }
  return std::nullopt;
}

}  // namespace rpsd::monitor
