// The web page's files, embedded in the firmware (docs/web.md "The page"). The build gzips every file of
// web/assets/ and the register table generated from registers.csv (tools/web/embed_assets.py) and
// compiles the bytes in; the server answers GET of a path with the stored gzip data as it is
// (Content-Encoding: gzip), the content type and the ETag given here.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string_view>

namespace web {

// Most bytes all assets may take gzip-compressed together; the build fails beyond it.
inline constexpr std::size_t kAssetGzipBudget = 65536;

struct Asset {
  std::string_view path;                // "/index.html", "/app.js", ...
  std::string_view content_type;        // "text/html; charset=utf-8", ...
  std::span<const std::uint8_t> gzip;   // one gzip member (RFC 1952) of the content
  std::string_view etag;                // quoted short hash of the content: "\"0123456789abcdef\""
  std::size_t raw_size;                 // bytes of the content before compression
};

// The asset served at `path` (the path of the request target, without its query); "/" is
// "/index.html". nullptr when there is none.
const Asset* FindAsset(std::string_view path);

// Every asset, sorted by path.
std::span<const Asset> AllAssets();

}  // namespace web
