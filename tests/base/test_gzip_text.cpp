// base/gzip.hpp and base/text.hpp.
#include <catch2/catch.hpp>

#include "base/gzip.hpp"
#include "base/text.hpp"
#include "test_support.hpp"

using namespace gs::base;

TEST_CASE("gunzip: members, limits and damage as typed errors", "[base][gzip]") {
  const std::string text(100000, 'v');
  const std::string gz = gs::test::gzip(text);
  CHECK(isGzip(gz));
  CHECK_FALSE(isGzip("plain"));
  CHECK(gunzip(gz, 1 << 20) == text);
  CHECK(gunzip(gz + gs::test::gzip("w"), 1 << 20) == text + "w");  // concatenated members
  CHECK(gunzip(gz + std::string(16, '\0'), 1 << 20) == text);      // zero padding
  CHECK(gunzipIfCompressed("plain", 1) == "plain");
  CHECK(gunzipPrefix(gz, 10) == std::string(10, 'v'));
  CHECK(gunzipPrefix(gz.substr(0, gz.size() / 2), 5) == std::string(5, 'v'));
  CHECK(gunzipPrefix("plain", 10).empty());

  auto kindOf = [](std::string_view bytes, std::size_t max) {
    try {
      (void)gunzip(bytes, max);
    } catch (const GzipError& e) {
      return std::pair{e.kind, std::string(e.what())};
    }
    FAIL("no GzipError");
    return std::pair{GzipError::Kind::corrupt, std::string()};
  };
  const auto [big, bigWhy] = kindOf(gz, 1000);
  CHECK(big == GzipError::Kind::tooLarge);
  CHECK(bigWhy == "decompressed data exceeds 1000 bytes");
  const auto [cut, cutWhy] = kindOf(gz.substr(0, gz.size() - 9), 1 << 20);
  CHECK(cut == GzipError::Kind::corrupt);
  CHECK(cutWhy == "corrupt gzip data: truncated");
  const auto [tail, tailWhy] = kindOf(gz + "junk", 1 << 20);
  CHECK(tail == GzipError::Kind::corrupt);
  CHECK(tailWhy == "corrupt gzip data: trailing bytes after the gzip data");
}

TEST_CASE("case-insensitive text helpers", "[base][text]") {
  CHECK(toLower("HeLLo.WRL") == "hello.wrl");
  CHECK(equalsNoCase("File", "fILE"));
  CHECK_FALSE(equalsNoCase("file", "files"));
  CHECK(startsWithNoCase("HTTP://h", "http://"));
  CHECK_FALSE(startsWithNoCase("ht", "http"));
  CHECK(endsWithNoCase("a.Nii.Gz", ".nii.gz"));
  CHECK_FALSE(endsWithNoCase("gz", ".gz"));
}
