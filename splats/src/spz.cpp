// Niantic .spz (readers.hpp), versions 2 to 4 (github.com/nianticlabs/spz, load-spz.cc):
// v2 and v3 are gzip of a 16-byte header (NGSP magic, version, count, SH degree,
// fractional bits, flags) and the attribute blocks; v4 is a 32-byte header, a table of
// contents and one zstd stream per attribute. Decoded as splat-transform 3.7's readSpz
// does: raw, without a coordinate conversion (the file's own axes, Transform.PLY). SH
// degree 4 (SPZ allows it) keeps degrees 1-3; the header extensions of v4 are skipped.
#include <zstd.h>

#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "base/byte_order.hpp"
#include "base/gzip.hpp"
#include "reader_support.hpp"

namespace gs::splats {

namespace {

using detail::fail;

constexpr std::uint32_t kMagic = 0x5053474e;  // "NGSP"
constexpr std::size_t kSpzShPerChannel[] = {0, 3, 8, 15, 24};

/// Byte sizes of the attribute blocks of `count` splats, in file order: positions,
/// alphas, colours, scales, rotations, SH.
std::array<std::uint64_t, 6> blockSizes(std::uint64_t count, int version, int degree) {
  return {count * 9,
          count,
          count * 3,
          count * 3,
          count * (version == 2 ? 3u : 4u),
          count * 3 * kSpzShPerChannel[degree]};
}

/// zstd frame `in` decompressed, exactly `expected` bytes (else FormatError). Streamed, so
/// memory grows with the output actually produced, never past `expected`.
std::string unzstd(std::string_view in, std::uint64_t expected, std::string_view name, int stream) {
  struct Free {
    void operator()(ZSTD_DStream* d) const { ZSTD_freeDStream(d); }
  };
  std::unique_ptr<ZSTD_DStream, Free> d(ZSTD_createDStream());
  if (!d) fail(name, "zstd: out of memory");
  ZSTD_initDStream(d.get());
  std::string out;
  ZSTD_inBuffer input{in.data(), in.size(), 0};
  std::size_t last = 1;
  while (true) {
    constexpr std::size_t kChunk = std::size_t{1} << 20;
    const std::size_t old = out.size();
    const std::uint64_t room = expected - old;
    const std::size_t grow = static_cast<std::size_t>(std::min<std::uint64_t>(room + 1, kChunk));
    out.resize(old + grow);
    ZSTD_outBuffer output{out.data() + old, grow, 0};
    last = ZSTD_decompressStream(d.get(), &output, &input);
    out.resize(old + output.pos);
    if (ZSTD_isError(last))
      fail(name, "stream " + std::to_string(stream) + ": zstd: " + ZSTD_getErrorName(last));
    if (out.size() > expected)
      fail(name, "stream " + std::to_string(stream) + " decompresses to more than " +
                     std::to_string(expected) + " bytes");
    if (last == 0 && input.pos == input.size) break;        // frame complete, input used
    if (input.pos == input.size && output.pos == 0) break;  // truncated: no progress
  }
  if (last != 0) fail(name, "stream " + std::to_string(stream) + ": truncated zstd data");
  if (out.size() != expected)
    fail(name, "stream " + std::to_string(stream) + ": expected " + std::to_string(expected) +
                   " bytes, got " + std::to_string(out.size()));
  return out;
}

struct Header {
  std::uint32_t version = 0, count = 0;
  int degree = 0, fractionalBits = 0, flags = 0;
};

Header parseHeader(std::string_view h, std::string_view name) {
  if (h.size() < 16)
    fail(name, "expected a 16-byte SPZ header, got " + std::to_string(h.size()) + " bytes");
  if (base::loadLe<std::uint32_t>(h.data()) != kMagic)
    fail(name, "not an SPZ file (no NGSP magic)");
  Header r;
  r.version = base::loadLe<std::uint32_t>(h.data() + 4);
  if (r.version < 2 || r.version > 4)
    fail(name, "unsupported SPZ version " + std::to_string(r.version));
  r.count = base::loadLe<std::uint32_t>(h.data() + 8);
  r.degree = static_cast<std::uint8_t>(h[12]);
  r.fractionalBits = static_cast<std::uint8_t>(h[13]);
  r.flags = static_cast<std::uint8_t>(h[14]);
  if (r.degree > 4) fail(name, "unsupported SPZ SH degree " + std::to_string(r.degree));
  if (r.count == 0) fail(name, "expected at least one splat, got 0");
  if (r.count > kMaxSplats)
    fail(name,
         std::to_string(r.count) + " splats exceed the limit of " + std::to_string(kMaxSplats));
  return r;
}

GaussianCloud decode(const Header& h, const std::array<std::string_view, 6>& b) {
  const std::size_t count = h.count;
  const int degree = std::min(h.degree, kMaxShDegree);
  const std::size_t fileRest = kSpzShPerChannel[h.degree];  // per channel, in the file
  GaussianCloud cloud;
  detail::allocate(cloud, count, degree);
  const std::size_t keep = static_cast<std::size_t>(cloud.shRestPerSplat());
  const float positionScale = std::ldexp(1.0f, -h.fractionalBits);
  auto byte = [](std::string_view s, std::size_t i) {
    return static_cast<float>(static_cast<std::uint8_t>(s[i]));
  };
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 p;
    for (int k = 0; k < 3; ++k) {
      const char* q = b[0].data() + i * 9 + k * 3;
      std::uint32_t v = static_cast<std::uint8_t>(q[0]) |
                        (static_cast<std::uint32_t>(static_cast<std::uint8_t>(q[1])) << 8) |
                        (static_cast<std::uint32_t>(static_cast<std::uint8_t>(q[2])) << 16);
      if (v & 0x800000u) v |= 0xff000000u;
      p[k] = static_cast<float>(static_cast<std::int32_t>(v)) * positionScale;
    }
    cloud.positions[i] = p;
    cloud.opacities[i] = byte(b[1], i) / 255.0f;
    for (int k = 0; k < 3; ++k) {
      cloud.shDc[i][k] = (byte(b[2], i * 3 + k) / 255.0f - 0.5f) / 0.15f;
      cloud.scales[i][k] = std::exp(byte(b[3], i * 3 + k) / 16.0f - 10.0f);
    }
    if (h.version == 2) {
      const float x = byte(b[4], i * 3) / 127.5f - 1.0f, y = byte(b[4], i * 3 + 1) / 127.5f - 1.0f,
                  z = byte(b[4], i * 3 + 2) / 127.5f - 1.0f;
      cloud.rotations[i] =
          detail::unitQuat(std::sqrt(std::max(0.0f, 1.0f - (x * x + y * y + z * z))), x, y, z);
    } else {
      // Smallest three: 2 bits index of the largest, then 3 x (sign bit, 9-bit magnitude).
      std::uint32_t packed = base::loadLe<std::uint32_t>(b[4].data() + i * 4);
      const unsigned largest = packed >> 30;
      float xyzw[4] = {0, 0, 0, 0};
      float sum = 0.0f;
      for (int j = 3; j >= 0; --j) {
        if (static_cast<unsigned>(j) == largest) continue;
        const float mag = static_cast<float>(packed & 511u);
        const bool negative = (packed >> 9) & 1u;
        packed >>= 10;
        const float v = 0.70710678118654752f * mag / 511.0f;
        xyzw[j] = negative ? -v : v;
        sum += v * v;
      }
      xyzw[largest] = std::sqrt(std::max(0.0f, 1.0f - sum));
      cloud.rotations[i] = detail::unitQuat(xyzw[3], xyzw[0], xyzw[1], xyzw[2]);
    }
    // SH: coefficient-major, RGB inner, (b - 128) / 128.
    glm::vec3* rest = cloud.shRest.data() + i * keep;
    const char* s = b[5].data() + i * fileRest * 3;
    for (std::size_t k = 0; k < keep; ++k)
      for (int c = 0; c < 3; ++c)
        rest[k][c] =
            (static_cast<float>(static_cast<std::uint8_t>(s[k * 3 + c])) - 128.0f) / 128.0f;
  }
  return cloud;
}

GaussianCloud readLegacy(std::string_view bytes, std::string_view name) {
  const std::string head = base::gunzipPrefix(bytes, 16);
  const Header h = parseHeader(head, name);
  if (h.version == 4) fail(name, "SPZ version 4 must not be gzip-compressed");
  if (h.flags & 0x2)
    fail(name, "SPZ header extensions in a version " + std::to_string(h.version) +
                   " file are not supported");
  const auto sizes = blockSizes(h.count, static_cast<int>(h.version), h.degree);
  std::uint64_t total = 16;
  for (std::uint64_t s : sizes) total += s;
  std::string data;
  try {
    data = base::gunzip(bytes, static_cast<std::size_t>(total) + (std::size_t{1} << 20));
  } catch (const base::GzipError& e) {
    fail(name, e.what());
  }
  if (data.size() < total)
    fail(name, "expected " + std::to_string(total) + " bytes of SPZ data for " +
                   std::to_string(h.count) + " splats, got " + std::to_string(data.size()));
  std::array<std::string_view, 6> blocks;
  std::size_t at = 16;
  for (int k = 0; k < 6; ++k) {
    blocks[static_cast<std::size_t>(k)] = std::string_view(data).substr(
        at, static_cast<std::size_t>(sizes[static_cast<std::size_t>(k)]));
    at += static_cast<std::size_t>(sizes[static_cast<std::size_t>(k)]);
  }
  return decode(h, blocks);
}

GaussianCloud readV4(std::string_view bytes, std::string_view name) {
  if (bytes.size() < 32)
    fail(name, "expected a 32-byte SPZ v4 header, got " + std::to_string(bytes.size()) + " bytes");
  const Header h = parseHeader(bytes.substr(0, 16), name);
  if (h.version != 4)
    fail(name, "an uncompressed SPZ file must be version 4, got " + std::to_string(h.version));
  const unsigned streams = static_cast<std::uint8_t>(bytes[15]);
  const std::uint32_t toc = base::loadLe<std::uint32_t>(bytes.data() + 16);
  const unsigned expectedStreams = h.degree == 0 ? 5 : 6;
  if (streams != expectedStreams)
    fail(name, "expected " + std::to_string(expectedStreams) + " SPZ streams, got " +
                   std::to_string(streams));
  if (toc < 32 || static_cast<std::uint64_t>(toc) + streams * 16ull > bytes.size())
    fail(name, "SPZ table of contents at " + std::to_string(toc) + " lies outside the " +
                   std::to_string(bytes.size()) + " bytes");
  const auto sizes = blockSizes(h.count, 4, h.degree);
  std::uint64_t at = toc + streams * 16ull;
  std::array<std::string, 6> data;
  std::array<std::string_view, 6> blocks;
  for (unsigned k = 0; k < streams; ++k) {
    const char* entry = bytes.data() + toc + k * 16;
    const std::uint64_t compressed = base::loadLe<std::uint64_t>(entry);
    const std::uint64_t uncompressed = base::loadLe<std::uint64_t>(entry + 8);
    if (uncompressed != sizes[k])
      fail(name, "stream " + std::to_string(k) + ": expected " + std::to_string(sizes[k]) +
                     " bytes for " + std::to_string(h.count) + " splats, got " +
                     std::to_string(uncompressed));
    if (compressed > bytes.size() - at)
      fail(name, "stream " + std::to_string(k) + ": expected " + std::to_string(compressed) +
                     " compressed bytes, got " + std::to_string(bytes.size() - at));
    data[k] =
        unzstd(bytes.substr(static_cast<std::size_t>(at), static_cast<std::size_t>(compressed)),
               uncompressed, name, static_cast<int>(k));
    blocks[k] = data[k];
    at += compressed;
  }
  return decode(h, blocks);
}

}  // namespace

GaussianCloud readSpzGaussians(std::string_view bytes, std::string_view name) {
  if (base::isGzip(bytes)) return readLegacy(bytes, name);
  if (bytes.size() >= 4 && base::loadLe<std::uint32_t>(bytes.data()) == kMagic)
    return readV4(bytes, name);
  fail(name, "not an SPZ file (neither gzip nor NGSP)");
}

}  // namespace gs::splats
