#include "base/gzip.hpp"

#include <zlib.h>

#include <algorithm>

namespace gs::base {

namespace {

struct Inflater {
  z_stream zs{};
  bool ok = false;
  Inflater() { ok = inflateInit2(&zs, 16 + MAX_WBITS) == Z_OK; }
  ~Inflater() {
    if (ok) inflateEnd(&zs);
  }
  Inflater(const Inflater&) = delete;
  Inflater& operator=(const Inflater&) = delete;
};

[[noreturn]] void corrupt(const std::string& why) {
  throw GzipError(GzipError::Kind::corrupt, "corrupt gzip data: " + why);
}

// Inflates `bytes` into `out`. With `prefixOnly`, stops without error at `maxBytes` and
// at the first problem; otherwise throws GzipError.
void inflateInto(std::string_view bytes, std::size_t maxBytes, bool prefixOnly, std::string& out) {
  Inflater z;
  if (!z.ok) {
    if (prefixOnly) return;
    corrupt("zlib could not start");
  }
  z_stream& zs = z.zs;
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
      if (rest == 0 || prefixOnly) return;
      if (zs.avail_in >= 2 && zs.next_in[0] == 0x1f && zs.next_in[1] == 0x8b) {
        if (inflateReset(&zs) != Z_OK) corrupt("zlib could not restart");
        memberDone = false;
        continue;
      }
      bool zeros = true;
      for (uInt i = 0; i < zs.avail_in; ++i) zeros = zeros && zs.next_in[i] == 0;
      if (zeros && inLeft == 0) return;
      corrupt("trailing bytes after the gzip data");
    }
    const std::size_t old = out.size();
    const std::size_t room = maxBytes - std::min(maxBytes, old);
    if (prefixOnly && room == 0) return;
    const std::size_t grow =
        room >= kChunk ? kChunk : (prefixOnly ? room : room + 1);  // +1 detects overflow
    out.resize(old + grow);
    zs.next_out = reinterpret_cast<unsigned char*>(out.data() + old);
    zs.avail_out = static_cast<uInt>(grow);
    const int rc = inflate(&zs, Z_NO_FLUSH);
    out.resize(old + (grow - zs.avail_out));
    if (out.size() > maxBytes)
      throw GzipError(GzipError::Kind::tooLarge,
                      "decompressed data exceeds " + std::to_string(maxBytes) + " bytes");
    if (rc == Z_STREAM_END) {
      memberDone = true;
      continue;
    }
    const bool stuck = rc == Z_BUF_ERROR && zs.avail_in == 0 && inLeft == 0;
    const bool failed = rc != Z_OK && rc != Z_BUF_ERROR;
    if (prefixOnly && (stuck || failed)) return;
    if (stuck) corrupt("truncated");
    if (failed) corrupt(zs.msg != nullptr ? zs.msg : "inflate failed");
  }
}

}  // namespace

bool isGzip(std::string_view bytes) {
  return bytes.size() >= 2 && static_cast<unsigned char>(bytes[0]) == 0x1f &&
         static_cast<unsigned char>(bytes[1]) == 0x8b;
}

std::string gunzip(std::string_view bytes, std::size_t maxBytes) {
  std::string out;
  inflateInto(bytes, maxBytes, false, out);
  return out;
}

std::string gunzipIfCompressed(std::string_view bytes, std::size_t maxBytes) {
  if (!isGzip(bytes)) return std::string(bytes);
  return gunzip(bytes, maxBytes);
}

std::string gunzipPrefix(std::string_view bytes, std::size_t maxBytes) {
  std::string out;
  if (!isGzip(bytes)) return out;
  inflateInto(bytes, maxBytes, true, out);
  return out;
}

}  // namespace gs::base
