// The page embedded in the firmware (docs/web.md "The page"): the build's table of gzipped assets
// (tools/web/embed_assets.py -> web_assets.cc): lookup, content types, ETags, gzip framing with the
// stored size, the size budget, and, when zlib is there, that each asset inflates to its size and that
// the files index.html loads are all embedded.
#include "web/assets.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <regex>
#include <set>
#include <string>
#include <string_view>

#if IPE_HAVE_ZLIB
#define ZLIB_CONST
#include <zlib.h>
#endif

namespace web {
namespace {

std::uint32_t LittleEndian32(std::span<const std::uint8_t> bytes) {
  return static_cast<std::uint32_t>(bytes[0]) | static_cast<std::uint32_t>(bytes[1]) << 8 |
         static_cast<std::uint32_t>(bytes[2]) << 16 | static_cast<std::uint32_t>(bytes[3]) << 24;
}

TEST(WebAssetsTest, RootIsIndexHtml) {
  const Asset* root = FindAsset("/");
  ASSERT_NE(root, nullptr);
  EXPECT_EQ(root, FindAsset("/index.html"));
  EXPECT_EQ(root->path, "/index.html");
  EXPECT_EQ(root->content_type, "text/html; charset=utf-8");
}

TEST(WebAssetsTest, ContentTypes) {
  for (const char* path : {"/app.js", "/registers.js"}) {
    const Asset* asset = FindAsset(path);
    ASSERT_NE(asset, nullptr) << path;
    EXPECT_EQ(asset->content_type, "text/javascript; charset=utf-8") << path;
  }
  const Asset* css = FindAsset("/app.css");
  ASSERT_NE(css, nullptr);
  EXPECT_EQ(css->content_type, "text/css; charset=utf-8");
}

TEST(WebAssetsTest, UnknownPathsFindNothing) {
  for (const char* path : {"", "index.html", "/index.htm", "/index.html/", "/nope", "/api/session", "//", "/APP.JS"}) {
    EXPECT_EQ(FindAsset(path), nullptr) << path;
  }
}

TEST(WebAssetsTest, EveryAssetIsOneGzipMemberWithItsSizeAndAnEtag) {
  ASSERT_GE(AllAssets().size(), 4u);
  std::set<std::string_view> paths;
  std::set<std::string_view> etags;
  const std::regex etag(R"re("[0-9a-f]{16}")re");
  for (const Asset& asset : AllAssets()) {
    SCOPED_TRACE(std::string(asset.path));
    EXPECT_TRUE(paths.insert(asset.path).second) << "twice";
    EXPECT_EQ(FindAsset(asset.path), &asset);
    EXPECT_TRUE(std::regex_match(std::string(asset.etag), etag)) << asset.etag;
    EXPECT_TRUE(etags.insert(asset.etag).second) << "same ETag as another asset";
    EXPECT_GT(asset.raw_size, 0u);
    ASSERT_GE(asset.gzip.size(), 18u);
    // RFC 1952: magic, deflate, no flags, mtime 0 (deterministic), XFL 2 (best compression).
    EXPECT_EQ(asset.gzip[0], 0x1f);
    EXPECT_EQ(asset.gzip[1], 0x8b);
    EXPECT_EQ(asset.gzip[2], 8);
    EXPECT_EQ(asset.gzip[3], 0);
    EXPECT_EQ(LittleEndian32(asset.gzip.subspan(4, 4)), 0u);
    EXPECT_EQ(asset.gzip[8], 2);
    // ISIZE: the size before compression.
    EXPECT_EQ(LittleEndian32(asset.gzip.last(4)), asset.raw_size);
    EXPECT_LT(asset.gzip.size(), asset.raw_size);
  }
  EXPECT_TRUE(std::is_sorted(paths.begin(), paths.end()));
}

TEST(WebAssetsTest, TotalWithinBudget) {
  std::size_t total = 0;
  for (const Asset& asset : AllAssets()) total += asset.gzip.size();
  EXPECT_LE(total, kAssetGzipBudget);
}

#if IPE_HAVE_ZLIB
std::string Inflate(const Asset& asset) {
  z_stream z{};
  EXPECT_EQ(inflateInit2_(&z, 16 + MAX_WBITS, ZLIB_VERSION, static_cast<int>(sizeof(z_stream))), Z_OK);
  z.next_in = asset.gzip.data();
  z.avail_in = static_cast<uInt>(asset.gzip.size());
  std::string out(asset.raw_size + 1, '\0');   // one spare byte: more output than raw_size would show
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = static_cast<uInt>(out.size());
  EXPECT_EQ(inflate(&z, Z_FINISH), Z_STREAM_END) << asset.path;
  EXPECT_EQ(z.avail_in, 0u) << asset.path << ": bytes after the gzip member";
  out.resize(z.total_out);
  inflateEnd(&z);
  return out;
}

TEST(WebAssetsTest, EveryAssetInflatesToItsSize) {
  for (const Asset& asset : AllAssets()) {
    const std::string content = Inflate(asset);
    EXPECT_EQ(content.size(), asset.raw_size) << asset.path;
    const std::uint32_t crc = static_cast<std::uint32_t>(
        crc32(0, reinterpret_cast<const Bytef*>(content.data()), static_cast<uInt>(content.size())));
    EXPECT_EQ(crc, LittleEndian32(asset.gzip.subspan(asset.gzip.size() - 8, 4))) << asset.path;
  }
}

TEST(WebAssetsTest, IndexLoadsOnlyEmbeddedFiles) {
  const Asset* index = FindAsset("/");
  ASSERT_NE(index, nullptr);
  const std::string html = Inflate(*index);
  const std::regex reference(R"re((?:src|href)="([^"#]+)")re");
  std::set<std::string> loaded;
  for (auto it = std::sregex_iterator(html.begin(), html.end(), reference); it != std::sregex_iterator(); ++it) {
    const std::string target = (*it)[1];
    if (target.rfind("data:", 0) == 0) continue;
    EXPECT_EQ(target.find("//"), std::string::npos) << target << ": the page loads nothing from elsewhere";
    EXPECT_NE(FindAsset("/" + target), nullptr) << target << " is not embedded";
    loaded.insert(target);
  }
  EXPECT_EQ(loaded, (std::set<std::string>{"app.css", "app.js", "registers.js"}));
  const std::string registers = Inflate(*FindAsset("/registers.js"));
  EXPECT_NE(registers.find(R"(["0009","acc",)"), std::string::npos) << "acc is not in registers.js";
}
#endif

}  // namespace
}  // namespace web
