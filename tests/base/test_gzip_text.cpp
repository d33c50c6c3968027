// base/gzip.hpp, base/gunzip_feed.hpp, base/inflate_stream.hpp and base/text.hpp.
#include <catch2/catch.hpp>

#include "base/gunzip_feed.hpp"
#include "base/gzip.hpp"
#include "base/inflate_stream.hpp"
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

TEST_CASE("InflateStream: pieces, members, skip, rewind and damage", "[base][gzip]") {
  std::string text;
  for (unsigned i = 0; i < 300000; ++i) text += static_cast<char>('a' + (i * 7919u) % 26u);
  // 5 bytes of something else first: the stream starts at a compressed offset.
  const std::string file =
      "HEAD!" + gs::test::gzip(text.substr(0, 123456)) + gs::test::gzip(text.substr(123456));
  std::size_t fetches = 0;
  const InflateStream::Source source = [&](std::uint64_t offset, char* dst, std::size_t n) {
    ++fetches;
    if (offset >= file.size()) return std::size_t{0};
    const std::size_t got = std::min<std::size_t>(n, file.size() - offset);
    std::copy_n(file.data() + offset, got, dst);
    return got;
  };
  InflateStream stream(source, 5);
  std::string out(1000, '\0');
  CHECK(stream.read(out.data(), out.size()) == 1000);
  CHECK(out == text.substr(0, 1000));
  CHECK(stream.skip(200000) == 200000);  // across the second member's start
  CHECK(stream.position() == 201000);
  out.assign(text.size(), '\0');
  CHECK(stream.read(out.data(), out.size()) == text.size() - 201000);  // fewer: the end
  CHECK(out.substr(0, text.size() - 201000) == text.substr(201000));
  CHECK(stream.read(out.data(), 10) == 0);
  stream.rewind();
  CHECK(stream.position() == 0);
  CHECK(stream.read(out.data(), 26) == 26);
  CHECK(out.substr(0, 26) == text.substr(0, 26));
  CHECK(fetches >= 2);

  // The source hands out the first member and one byte of the second's magic: the byte is
  // kept and the second member still read.
  {
    const std::string first = gs::test::gzip("abc"), second = gs::test::gzip("defg");
    const std::string two = first + second;
    bool firstCall = true;
    InflateStream split(
        [&](std::uint64_t offset, char* dst, std::size_t n) {
          std::size_t got =
              std::min<std::size_t>(n, two.size() - std::min<std::size_t>(offset, two.size()));
          if (firstCall) got = std::min(got, first.size() + 1);
          firstCall = false;
          std::copy_n(two.data() + offset, got, dst);
          return got;
        },
        0);
    std::string both(16, '\0');
    CHECK(split.read(both.data(), both.size()) == 7);
    CHECK(both.substr(0, 7) == "abcdefg");
  }
  // Cut inside the first member: truncated, at the compressed offset where it ran out.
  const std::string cut = file.substr(0, 5 + 100);
  InflateStream short_(
      [&](std::uint64_t offset, char* dst, std::size_t n) {
        if (offset >= cut.size()) return std::size_t{0};
        const std::size_t got = std::min<std::size_t>(n, cut.size() - offset);
        std::copy_n(cut.data() + offset, got, dst);
        return got;
      },
      5);
  CHECK_THROWS_WITH(short_.skip(text.size()),
                    "corrupt gzip data at compressed byte offset 105: truncated");
  // Not gzip at all: zlib's reason.
  InflateStream garbage(
      [](std::uint64_t, char* dst, std::size_t n) {
        std::fill_n(dst, n, 'x');
        return n;
      },
      0);
  CHECK_THROWS_AS(garbage.read(out.data(), 10), GzipError);
}

TEST_CASE("GunzipFeed: every split of members and padding and the damage gunzip names",
          "[base][gzip]") {
  std::string text;
  for (unsigned i = 0; i < 200000; ++i) text += static_cast<char>('a' + (i * 7919u) % 26u);
  const std::string two =
      gs::test::gzip(text.substr(0, 70000)) + gs::test::gzip(text.substr(70000)) + "\0\0\0";
  // Pushed in pieces of every size from 1 byte to all at once: the same bytes out.
  for (const std::size_t piece : {std::size_t{1}, std::size_t{2}, std::size_t{3}, std::size_t{977},
                                  std::size_t{65536}, two.size()}) {
    INFO("pieces of " << piece);
    GunzipFeed feed;
    std::string out;
    for (std::size_t at = 0; at < two.size(); at += piece)
      feed.feed(std::string_view(two).substr(at, piece),
                [&](std::string_view bytes) { out.append(bytes); });
    CHECK_NOTHROW(feed.finish());
    CHECK(feed.produced() == text.size());
    CHECK(out == text);
  }
  const auto whyOf = [](std::string_view bytes) {
    try {
      GunzipFeed feed;
      feed.feed(bytes, [](std::string_view) {});
      feed.finish();
    } catch (const GzipError& e) {
      CHECK(e.kind == GzipError::Kind::corrupt);
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string one = gs::test::gzip(text);
  CHECK(whyOf(one) == "no error");
  CHECK(whyOf("") == "corrupt gzip data: truncated");
  CHECK(whyOf(one.substr(0, one.size() - 9)) == "corrupt gzip data: truncated");
  CHECK(whyOf(one + "\x1f") == "corrupt gzip data: truncated");  // a member's magic begun
  CHECK(whyOf(one + "junk") == "corrupt gzip data: trailing bytes after the gzip data");
  CHECK(whyOf(one + std::string(4, '\0') + "x") ==
        "corrupt gzip data: trailing bytes after the gzip data");
  CHECK(whyOf(one + "\x1fx") == "corrupt gzip data: trailing bytes after the gzip data");
  std::string damaged = one;
  damaged[12] ^= 0x5a;  // inside the deflate data
  CHECK(whyOf(damaged).rfind("corrupt gzip data: ", 0) == 0);
  CHECK(whyOf(damaged) != "no error");
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
