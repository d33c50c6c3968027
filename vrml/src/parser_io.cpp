// Bytes in for the parser: gzip (RFC 1952, through zlib), local files and URL
// resolution for EXTERNPROTO and the Inline self-reference check.
#include "parser_impl.hpp"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

namespace gs::vrml::parsing {

void gunzipInto(std::string_view bytes, const std::string& url, std::size_t maxBytes,
                std::string& out) {
  auto fail = [&](const std::string& why) {
    throw ParseError(Diagnostic{Severity::error, {url, 0, 0}, "corrupt gzip data: " + why});
  };
  z_stream zs{};
  if (inflateInit2(&zs, 16 + MAX_WBITS) != Z_OK) fail("zlib could not start");
  struct End {
    z_stream& z;
    ~End() { inflateEnd(&z); }
  } end{zs};
  out.clear();
  const auto* in = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t inLeft = bytes.size();
  constexpr std::size_t kChunk = 1 << 16;
  constexpr std::size_t kMaxFeed = 1u << 30;  // avail_in is 32-bit
  bool memberDone = false;
  while (true) {
    if (zs.avail_in == 0 && inLeft > 0) {
      const std::size_t feed = std::min(inLeft, kMaxFeed);
      zs.next_in = const_cast<unsigned char*>(in);
      zs.avail_in = static_cast<uInt>(feed);
      in += feed;
      inLeft -= feed;
    }
    if (memberDone) {
      // Another member may follow (concatenated gzip, RFC 1952 2.2); zero padding is
      // tolerated, anything else is trailing garbage.
      const std::size_t rest = zs.avail_in + inLeft;
      if (rest == 0) return;
      if (zs.avail_in >= 2 && zs.next_in[0] == 0x1f && zs.next_in[1] == 0x8b) {
        if (inflateReset(&zs) != Z_OK) fail("zlib could not restart");
        memberDone = false;
        continue;
      }
      bool zeros = true;
      for (uInt i = 0; i < zs.avail_in; ++i) zeros = zeros && zs.next_in[i] == 0;
      if (zeros && inLeft == 0) return;
      fail("trailing bytes after the gzip data");
    }
    const std::size_t old = out.size();
    const std::size_t room = maxBytes - std::min(maxBytes, old);
    const std::size_t grow = room >= kChunk ? kChunk : room + 1;  // +1 detects overflow
    out.resize(old + grow);
    zs.next_out = reinterpret_cast<unsigned char*>(out.data() + old);
    zs.avail_out = static_cast<uInt>(grow);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    out.resize(old + (grow - zs.avail_out));
    if (out.size() > maxBytes)
      throw ParseError(Diagnostic{Severity::error,
                                  {url, 0, 0},
                                  "decompressed data exceeds " + std::to_string(maxBytes) +
                                      " bytes (ParseLimits::maxInputBytes)"});
    if (rc == Z_STREAM_END) {
      memberDone = true;
      continue;
    }
    if (rc == Z_BUF_ERROR && zs.avail_in == 0 && inLeft == 0) fail("truncated");
    if (rc != Z_OK && rc != Z_BUF_ERROR) fail(zs.msg != nullptr ? zs.msg : "inflate failed");
  }
}

bool readFile(const std::string& path, std::size_t maxBytes, std::string& bytes,
              std::string& error) {
  std::string p = path;
  if (p.starts_with("file://"))
    p = p.substr(7);
  else if (p.starts_with("file:"))
    p = p.substr(5);
  std::FILE* f = std::fopen(p.c_str(), "rb");
  if (f == nullptr) {
    error = "cannot open '" + path + "': " + std::strerror(errno);
    return false;
  }
  struct Closer {
    std::FILE* f;
    ~Closer() { std::fclose(f); }
  } closer{f};
  bytes.clear();
  std::error_code ec;
  const auto size = std::filesystem::file_size(p, ec);
  if (!ec && size > maxBytes) {
    error = "'" + path + "' is larger than " + std::to_string(maxBytes) +
            " bytes (ParseLimits::maxInputBytes)";
    return false;
  }
  if (!ec) bytes.reserve(static_cast<std::size_t>(size));
  char buf[1 << 16];
  while (true) {
    const std::size_t n = std::fread(buf, 1, sizeof buf, f);
    bytes.append(buf, n);
    if (bytes.size() > maxBytes) {
      error = "'" + path + "' is larger than " + std::to_string(maxBytes) + " bytes";
      return false;
    }
    if (n < sizeof buf) break;
  }
  if (std::ferror(f) != 0) {
    error = "cannot read '" + path + "': " + std::strerror(errno);
    return false;
  }
  return true;
}

bool hasScheme(std::string_view url) {
  std::size_t i = 0;
  while (i < url.size() && (std::isalnum(static_cast<unsigned char>(url[i])) != 0 ||
                            url[i] == '+' || url[i] == '-' || url[i] == '.'))
    ++i;
  return i >= 2 && i < url.size() && url[i] == ':' &&
         std::isalpha(static_cast<unsigned char>(url[0])) != 0;
}

std::string resolveUrl(const std::string& base, const std::string& url) {
  if (hasScheme(url) || url.starts_with('/')) return url;
  const std::size_t slash = base.find_last_of('/');
  if (slash == std::string::npos) return url;
  return base.substr(0, slash + 1) + url;
}

bool urlNamesFile(const std::string& base, const std::string& url) {
  if (base.empty() || hasScheme(base) || hasScheme(url) || url.empty() || url[0] == '#')
    return false;
  const std::string target = resolveUrl(base, url.substr(0, url.find('#')));
  std::error_code e1, e2;
  const auto a = std::filesystem::weakly_canonical(base, e1);
  const auto b = std::filesystem::weakly_canonical(target, e2);
  return !e1 && !e2 && a == b;
}

}  // namespace gs::vrml::parsing

namespace gs::vrml {

std::string gunzipIfCompressed(std::string_view bytes, const std::string& url,
                               std::size_t maxBytes) {
  if (!parsing::isGzip(bytes)) return std::string(bytes);
  std::string out;
  parsing::gunzipInto(bytes, url, maxBytes, out);
  return out;
}

}  // namespace gs::vrml
