// data: URLs (RFC 2397): base64 and %-encoded forms, round trips, bad input.
#include "base/data_url.hpp"
#include "base/url.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

using namespace gs::base;

TEST_CASE("data: URLs decode and round-trip", "[base][data-url]") {
  std::string bytes, type, error;
  REQUIRE(decodeDataUrl("data:text/plain;base64,aGVsbG8=", bytes, type, error));
  CHECK(bytes == "hello");
  CHECK(type == "text/plain");
  REQUIRE(decodeDataUrl("DATA:,a%20b", bytes, type, error));
  CHECK(bytes == "a b");
  CHECK(type.empty());
  for (const std::string& s :
       std::vector<std::string>{"", "a", "ab", "abc", std::string("\0\xff\x10\x80", 4)}) {
    const std::string url = makeDataUrl("application/octet-stream", s);
    REQUIRE(decodeDataUrl(url, bytes, type, error));
    CHECK(bytes == s);
    CHECK(type == "application/octet-stream");
  }
  CHECK_FALSE(decodeDataUrl("data:image/png;base64", bytes, type, error));  // no ','
  CHECK_FALSE(decodeDataUrl("data:;base64,ab*d", bytes, type, error));
  CHECK(error.find("base64") != std::string::npos);
  CHECK_FALSE(decodeDataUrl("http://x/y", bytes, type, error));
}

TEST_CASE("network content may reference data: URLs but not local files", "[base][data-url]") {
  std::string error;
  CHECK(mayReference("http://example.com/a.gltf", "data:image/png;base64,AAAA", error));
  CHECK_FALSE(mayReference("http://example.com/a.gltf", "file:///etc/passwd", error));
  // A data: URL's content (which a remote world may have named) takes the network's rules.
  const std::string world = makeDataUrl("model/vrml", std::string(100, ' '));
  CHECK(mayReference(world, "http://example.com/t.png", error));
  CHECK(mayReference(world, "data:image/png;base64,AAAA", error));
  error.clear();
  CHECK_FALSE(mayReference(world, "file:///etc/passwd", error));
  CHECK_FALSE(mayReference(world, "/etc/passwd", error));
  CHECK(error.find("content of a data: URL, as from the network") != std::string::npos);
  CHECK(error.size() < 200);  // the data: URL shown by its start
}
