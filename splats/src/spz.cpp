// Niantic .spz (readers.hpp), versions 2 to 4 (github.com/nianticlabs/spz, load-spz.cc):
// v2 and v3 are gzip of a 16-byte header (NGSP magic, version, count, SH degree,
// fractional bits, flags) and the attribute blocks; v4 is a 32-byte header, a table of
// contents and one zstd stream per attribute. Decoded as splat-transform 3.7's readSpz
// does: raw, without a coordinate conversion (the file's own axes, Transform.PLY). SH
// degree 4 (SPZ allows it) keeps degrees 1-3; the header extensions of v4 are skipped.
#include <zstd.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "base/byte_order.hpp"
#include "base/gunzip_feed.hpp"
#include "base/gzip.hpp"
#include "base/inflate_stream.hpp"
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

/// Bytes of one splat in each attribute block (as blockSizes, for one splat).
std::array<std::size_t, 6> splatBytes(const Header& h) {
  const auto sizes = blockSizes(1, static_cast<int>(h.version), h.degree);
  return {static_cast<std::size_t>(sizes[0]), static_cast<std::size_t>(sizes[1]),
          static_cast<std::size_t>(sizes[2]), static_cast<std::size_t>(sizes[3]),
          static_cast<std::size_t>(sizes[4]), static_cast<std::size_t>(sizes[5])};
}

/// Decodes `count` splats into `cloud` (allocated for them at min(degree, 3)) from the
/// attribute blocks' bytes of those splats, `b[k]` at the first one's.
void decode(const Header& h, const std::array<const char*, 6>& b, std::size_t count,
            GaussianCloud& cloud) {
  const std::size_t fileRest = kSpzShPerChannel[h.degree];  // per channel, in the file
  const std::size_t keep = static_cast<std::size_t>(cloud.shRestPerSplat());
  const float positionScale = std::ldexp(1.0f, -h.fractionalBits);
  auto byte = [](const char* s, std::size_t i) {
    return static_cast<float>(static_cast<std::uint8_t>(s[i]));
  };
  for (std::size_t i = 0; i < count; ++i) {
    glm::vec3 p;
    for (int k = 0; k < 3; ++k) {
      const char* q = b[0] + i * 9 + k * 3;
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
      std::uint32_t packed = base::loadLe<std::uint32_t>(b[4] + i * 4);
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
    const char* s = b[5] + i * fileRest * 3;
    for (std::size_t k = 0; k < keep; ++k)
      for (int c = 0; c < 3; ++c)
        rest[k][c] =
            (static_cast<float>(static_cast<std::uint8_t>(s[k * 3 + c])) - 128.0f) / 128.0f;
  }
}

/// The whole cloud of `count` splats from the blocks `b` (each holding its block whole).
GaussianCloud decodeWhole(const Header& h, const std::array<std::string_view, 6>& b) {
  GaussianCloud cloud;
  detail::allocate(cloud, h.count, std::min(h.degree, kMaxShDegree));
  decode(h, {b[0].data(), b[1].data(), b[2].data(), b[3].data(), b[4].data(), b[5].data()}, h.count,
         cloud);
  return cloud;
}

/// The header of a v2/v3 (gzip) file, its first 16 decompressed bytes `head`: v4 and the
/// header extensions of v2/v3 refused. `total` is set to the decompressed bytes it says.
Header parseLegacyHeader(std::string_view head, std::string_view name, std::uint64_t& total) {
  const Header h = parseHeader(head, name);
  if (h.version == 4) fail(name, "SPZ version 4 must not be gzip-compressed");
  if (h.flags & 0x2)
    fail(name, "SPZ header extensions in a version " + std::to_string(h.version) +
                   " file are not supported");
  total = 16;
  for (std::uint64_t s : blockSizes(h.count, static_cast<int>(h.version), h.degree)) total += s;
  return h;
}

GaussianCloud readLegacy(std::string_view bytes, std::string_view name) {
  std::uint64_t total = 0;
  const Header h = parseLegacyHeader(base::gunzipPrefix(bytes, 16), name, total);
  const auto sizes = blockSizes(h.count, static_cast<int>(h.version), h.degree);
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
  return decodeWhole(h, blocks);
}

/// A v4 file's header and where its streams lie.
struct V4Layout {
  Header h;
  unsigned streams = 0;
  std::array<std::uint64_t, 6> offset{}, compressed{}, uncompressed{};
};

/// Reads a v4 file's header and table of contents through `bytesAt(offset, n)` (n bytes
/// at offset, within the file's `fileBytes`), checking that every stream lies within the
/// file and decompresses to its attribute block's size.
V4Layout parseV4(const std::function<std::string(std::uint64_t, std::size_t)>& bytesAt,
                 std::uint64_t fileBytes, std::string_view name) {
  if (fileBytes < 32)
    fail(name, "expected a 32-byte SPZ v4 header, got " + std::to_string(fileBytes) + " bytes");
  const std::string head = bytesAt(0, 32);
  V4Layout r;
  r.h = parseHeader(head, name);
  const Header& h = r.h;
  if (h.version != 4)
    fail(name, "an uncompressed SPZ file must be version 4, got " + std::to_string(h.version));
  r.streams = static_cast<std::uint8_t>(head[15]);
  const std::uint32_t toc = base::loadLe<std::uint32_t>(head.data() + 16);
  const unsigned expectedStreams = h.degree == 0 ? 5 : 6;
  if (r.streams != expectedStreams)
    fail(name, "expected " + std::to_string(expectedStreams) + " SPZ streams, got " +
                   std::to_string(r.streams));
  if (toc < 32 || static_cast<std::uint64_t>(toc) + r.streams * 16ull > fileBytes)
    fail(name, "SPZ table of contents at " + std::to_string(toc) + " lies outside the " +
                   std::to_string(fileBytes) + " bytes");
  const std::string entries = bytesAt(toc, r.streams * 16u);
  const auto sizes = blockSizes(h.count, 4, h.degree);
  std::uint64_t at = toc + r.streams * 16ull;
  for (unsigned k = 0; k < r.streams; ++k) {
    const char* entry = entries.data() + k * 16;
    const std::uint64_t compressed = base::loadLe<std::uint64_t>(entry);
    const std::uint64_t uncompressed = base::loadLe<std::uint64_t>(entry + 8);
    if (uncompressed != sizes[k])
      fail(name, "stream " + std::to_string(k) + ": expected " + std::to_string(sizes[k]) +
                     " bytes for " + std::to_string(h.count) + " splats, got " +
                     std::to_string(uncompressed));
    if (compressed > fileBytes - at)
      fail(name, "stream " + std::to_string(k) + ": expected " + std::to_string(compressed) +
                     " compressed bytes, got " + std::to_string(fileBytes - at));
    r.offset[k] = at;
    r.compressed[k] = compressed;
    r.uncompressed[k] = uncompressed;
    at += compressed;
  }
  return r;
}

GaussianCloud readV4(std::string_view bytes, std::string_view name) {
  const V4Layout v4 = parseV4(
      [&](std::uint64_t offset, std::size_t n) {
        return std::string(bytes.substr(static_cast<std::size_t>(offset), n));
      },
      bytes.size(), name);
  std::array<std::string, 6> data;
  std::array<std::string_view, 6> blocks;
  for (unsigned k = 0; k < v4.streams; ++k) {
    data[k] = unzstd(bytes.substr(static_cast<std::size_t>(v4.offset[k]),
                                  static_cast<std::size_t>(v4.compressed[k])),
                     v4.uncompressed[k], name, static_cast<int>(k));
    blocks[k] = data[k];
  }
  return decodeWhole(v4.h, blocks);
}

/// One attribute block of an SPZ file read forward a piece at a time.
class BlockStream {
 public:
  virtual ~BlockStream() = default;
  /// Exactly `n` bytes of the block into `dst` (FormatError naming the file when it ends
  /// or is damaged before).
  virtual void read(char* dst, std::size_t n) = 0;
  /// After the block's last byte: checks that its data end as the whole-file reader
  /// requires (FormatError otherwise).
  virtual void finish() = 0;
  virtual void rewind() = 0;
};

/// A v2/v3 block: the gzip data inflated from its start and the blocks before it skipped
/// (each block has its own inflate, so the blocks are read side by side).
class InflatedBlock final : public BlockStream {
 public:
  InflatedBlock(const detail::PieceFile& file, std::uint64_t skip)
      : file_(file),
        inflate_(
            [&file](std::uint64_t offset, char* dst, std::size_t n) {
              const std::size_t got =
                  offset >= file.size()
                      ? 0
                      : static_cast<std::size_t>(std::min<std::uint64_t>(n, file.size() - offset));
              file.read(offset, dst, got);
              return got;
            },
            0),
        skip_(skip) {}
  void read(char* dst, std::size_t n) override {
    try {
      if (inflate_.position() == 0 && skip_ > 0 && inflate_.skip(skip_) != skip_)
        fail(file_.path(), "the SPZ data ends before byte " + std::to_string(skip_));
      const std::size_t got = inflate_.read(dst, n);
      if (got != n)
        fail(file_.path(), "the SPZ data ends at byte " + std::to_string(inflate_.position()) +
                               ", " + std::to_string(n - got) + " bytes short");
    } catch (const base::GzipError& e) {
      fail(file_.path(), e.what());
    }
  }
  /// The gzip data to their end, as readSpzGaussians inflates them: the trailers' CRC
  /// checked, at most 1 MiB more than the blocks.
  void finish() override {
    try {
      const std::uint64_t slack = std::uint64_t{1} << 20;
      if (inflate_.skip(slack + 1) > slack)
        fail(file_.path(), "decompressed data exceeds the SPZ blocks by more than 1 MiB");
    } catch (const base::GzipError& e) {
      fail(file_.path(), e.what());
    }
  }
  void rewind() override { inflate_.rewind(); }

 private:
  const detail::PieceFile& file_;
  base::InflateStream inflate_;
  std::uint64_t skip_;
};

/// A v4 block: its zstd stream decompressed forward, its compressed bytes read 256 KiB at
/// a time.
class ZstdBlock final : public BlockStream {
 public:
  ZstdBlock(const detail::PieceFile& file, std::uint64_t offset, std::uint64_t compressed,
            std::uint64_t uncompressed, int stream)
      : file_(file), offset_(offset), compressed_(compressed), stream_(stream), input_(1u << 18) {
    if (!d_) fail(file.path(), "zstd: out of memory");
    // Six streams are open at once: a frame may ask for no larger window than its block
    // could use (at least 8 MiB, what zstd's levels up to 19 take; 128 MiB is zstd's own
    // limit), so a small hostile file cannot make them take 6 x 128 MiB.
    const int windowLog = std::clamp(static_cast<int>(std::bit_width(uncompressed)) + 1, 23, 27);
    ZSTD_DCtx_setParameter(d_.get(), ZSTD_d_windowLogMax, windowLog);
    rewind();
  }
  void read(char* dst, std::size_t n) override {
    ZSTD_outBuffer out{dst, n, 0};
    while (out.pos < n) {
      const std::size_t before = out.pos;
      step(out);
      if (out.pos < n && out.pos == before && inputUsed())
        fail(file_.path(), "stream " + std::to_string(stream_) + " ends " +
                               std::to_string(n - out.pos) + " bytes short");
    }
  }
  /// The frame to its end, as readSpzGaussians decompresses it: complete, its compressed
  /// bytes used up, not a byte more than the block.
  void finish() override {
    char extra = 0;
    while (!(inputUsed() && hint_ == 0)) {
      const bool drained = inputUsed();
      ZSTD_outBuffer out{&extra, 1, 0};
      step(out);
      if (out.pos > 0)
        fail(file_.path(),
             "stream " + std::to_string(stream_) + " decompresses to more than its block's bytes");
      if (drained && hint_ != 0)
        fail(file_.path(), "stream " + std::to_string(stream_) + ": truncated zstd data");
    }
  }
  void rewind() override {
    ZSTD_initDStream(d_.get());
    hint_ = 1;
    used_ = 0;
    in_ = ZSTD_inBuffer{input_.data(), 0, 0};
  }

 private:
  /// One ZSTD_decompressStream call into `out`, its input refilled first when used up;
  /// its hint (0: a frame ended) kept in hint_. FormatError on a zstd error.
  void step(ZSTD_outBuffer& out) {
    if (in_.pos == in_.size && used_ < compressed_) {
      const std::size_t got =
          static_cast<std::size_t>(std::min<std::uint64_t>(input_.size(), compressed_ - used_));
      file_.read(offset_ + used_, input_.data(), got);
      used_ += got;
      in_ = ZSTD_inBuffer{input_.data(), got, 0};
    }
    const std::size_t rc = ZSTD_decompressStream(d_.get(), &out, &in_);
    if (ZSTD_isError(rc))
      fail(file_.path(), "stream " + std::to_string(stream_) + ": zstd: " + ZSTD_getErrorName(rc));
    hint_ = rc;
  }
  bool inputUsed() const { return in_.pos == in_.size && used_ == compressed_; }
  struct Free {
    void operator()(ZSTD_DStream* d) const { ZSTD_freeDStream(d); }
  };
  const detail::PieceFile& file_;
  std::uint64_t offset_, compressed_, used_ = 0;
  std::size_t hint_ = 1;  // the last ZSTD_decompressStream's return: 0 when a frame ended
  int stream_;
  std::vector<char> input_;
  std::unique_ptr<ZSTD_DStream, Free> d_{ZSTD_createDStream()};
  ZSTD_inBuffer in_{};
};

/// An SPZ file read a batch of splats at a time: one BlockStream per attribute block, read
/// side by side.
class SpzBatches final : public GaussianBatchReader {
 public:
  explicit SpzBatches(const std::string& path) : file_(path) {
    const std::string head = file_.head(64);
    if (base::isGzip(head)) {
      gzip_ = true;
      InflatedBlock first(file_, 0);
      std::string h16(16, '\0');
      first.read(h16.data(), h16.size());
      std::uint64_t total = 0;
      h_ = parseLegacyHeader(h16, path, total);
      const auto sizes = blockSizes(h_.count, static_cast<int>(h_.version), h_.degree);
      // Deflate's largest ratio is 1032:1: a header claiming more cannot be true.
      if (total / 1032 > file_.size())
        fail(path, std::to_string(file_.size()) + " bytes of gzip data cannot hold the " +
                       std::to_string(total) + " bytes of " + std::to_string(h_.count) + " splats");
      std::uint64_t at = 16;
      for (std::size_t k = 0; k < 6; ++k) {
        if (sizes[k] > 0) blocks_[k] = std::make_unique<InflatedBlock>(file_, at);
        at += sizes[k];
      }
    } else if (head.size() >= 4 && base::loadLe<std::uint32_t>(head.data()) == kMagic) {
      const V4Layout v4 = parseV4(
          [&](std::uint64_t offset, std::size_t n) {
            std::string bytes(n, '\0');
            file_.read(offset, bytes.data(), n);
            return bytes;
          },
          file_.size(), path);
      h_ = v4.h;
      for (unsigned k = 0; k < v4.streams; ++k)
        if (v4.uncompressed[k] > 0)
          blocks_[k] = std::make_unique<ZstdBlock>(file_, v4.offset[k], v4.compressed[k],
                                                   v4.uncompressed[k], static_cast<int>(k));
    } else {
      fail(path, "not an SPZ file (neither gzip nor NGSP)");
    }
    bytes_ = splatBytes(h_);
  }
  std::uint64_t size() const override { return h_.count; }
  int shDegree() const override { return std::min(h_.degree, kMaxShDegree); }
  std::size_t rowBytes() const override {
    std::size_t n = 0;
    for (std::size_t b : bytes_) n += b;
    return n;
  }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, size() - next_));
    std::array<const char*, 6> at{};
    for (std::size_t k = 0; k < 6; ++k) {
      data_[k].resize(n * bytes_[k]);
      if (blocks_[k] && n > 0) blocks_[k]->read(data_[k].data(), data_[k].size());
      at[k] = data_[k].data();
    }
    next_ += n;
    if (n > 0 && next_ == size()) {  // the last batch: the data end as they must
      if (gzip_) {
        // Every block's inflate reads the same gzip data: the last block's reaches its end.
        for (std::size_t k = 6; k-- > 0;)
          if (blocks_[k]) {
            blocks_[k]->finish();
            break;
          }
      } else {
        for (auto& b : blocks_)
          if (b) b->finish();
      }
    }
    batch = GaussianCloud{};
    detail::allocate(batch, n, shDegree());
    decode(h_, at, n, batch);
    return n;
  }
  void rewind() override {
    next_ = 0;
    for (auto& b : blocks_)
      if (b) b->rewind();
  }

 private:
  detail::PieceFile file_;
  Header h_;
  std::array<std::size_t, 6> bytes_{};
  std::array<std::unique_ptr<BlockStream>, 6> blocks_;
  bool gzip_ = false;  // v2/v3 (else v4)
  std::array<std::vector<char>, 6> data_;
  std::uint64_t next_ = 0;
};

/// An SPZ v4 file read by columns: one per zstd stream.
class SpzColumns final : public GaussianColumnDecoder {
 public:
  explicit SpzColumns(const V4Layout& v4) : h_(v4.h) {
    const auto bytes = splatBytes(h_);
    for (unsigned k = 0; k < v4.streams; ++k)
      columns_.push_back(
          Column{v4.offset[k], v4.compressed[k], bytes[k], true, {}, 0, false, 0, false, 0});
  }
  const std::vector<Column>& columns() const override { return columns_; }
  std::uint64_t size() const override { return h_.count; }
  int shDegree() const override { return std::min(h_.degree, kMaxShDegree); }
  void decode(const std::vector<const char*>& records, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, h_.count);
    if (records.size() != columns_.size())
      throw FormatError("SPZ columns: expected " + std::to_string(columns_.size()) +
                        " of them, got " + std::to_string(records.size()));
    static const char kNone = 0;  // the SH column of degree 0: none, never read
    std::array<const char*, 6> at{};
    at.fill(&kNone);
    for (std::size_t k = 0; k < columns_.size() && k < records.size(); ++k) at[k] = records[k];
    batch = GaussianCloud{};
    detail::allocate(batch, n, shDegree());
    splats::decode(h_, at, n, batch);
  }

 private:
  Header h_;
  std::vector<Column> columns_;
};

/// An SPZ v2/v3 file decoded as its gzip data arrive (GaussianStreamDecoder).
class SpzStream final : public GaussianStreamDecoder {
 public:
  SpzStream(const Header& h, std::string name) : h_(h), name_(std::move(name)) {
    const auto sizes = blockSizes(h_.count, static_cast<int>(h_.version), h_.degree);
    record_ = splatBytes(h_);
    std::uint64_t at = 0;
    for (std::size_t k = 0; k < 6; ++k) {
      start_[k] = at;
      at += sizes[k];
      if (sizes[k] > 0) last_ = k;
    }
    total_ = 16 + at;
  }
  std::uint64_t size() const override { return h_.count; }
  int shDegree() const override { return std::min(h_.degree, kMaxShDegree); }
  std::uint64_t decoded() const override { return decoded_; }
  std::uint64_t inflated() const override { return produced_; }
  void feed(std::string_view bytes) override {
    try {
      gunzip_.feed(bytes, [this](std::string_view out) { take(out); });
    } catch (const base::GzipError& e) {
      fail(name_, e.what());
    }
  }
  std::size_t next(GaussianCloud& batch, std::size_t max) override {
    const std::size_t lastBytes = record_[last_];
    const auto n = static_cast<std::size_t>(
        std::min<std::uint64_t>(max, (tail_.size() - tailAt_) / lastBytes));
    batch = GaussianCloud{};
    detail::allocate(batch, n, shDegree());
    if (n == 0) return 0;
    static const char kNone = 0;  // the SH block of degree 0: none, never read
    std::array<const char*, 6> at{};
    at.fill(&kNone);
    for (std::size_t k = 0; k < last_; ++k)
      at[k] = held_.data() + start_[k] + decoded_ * record_[k];
    at[last_] = tail_.data() + tailAt_;
    decode(h_, at, n, batch);
    decoded_ += n;
    tailAt_ += n * lastBytes;
    if (tailAt_ * 2 >= tail_.size()) {  // the given records go once they are half of it
      tail_.erase(0, tailAt_);
      tailAt_ = 0;
    }
    if (decoded_ == h_.count) std::string().swap(held_);
    return n;
  }
  void finish() override {
    try {
      gunzip_.finish();
    } catch (const base::GzipError& e) {
      fail(name_, e.what());
    }
    if (produced_ < total_)
      fail(name_, "expected " + std::to_string(total_) + " bytes of SPZ data for " +
                      std::to_string(h_.count) + " splats, got " + std::to_string(produced_));
  }

 private:
  /// Decompressed bytes, in order: the header skipped, the blocks before the last held,
  /// the last one's records queued, at most 1 MiB after the blocks (as readLegacy).
  void take(std::string_view out) {
    const std::uint64_t lastStart = 16 + start_[last_];
    while (!out.empty()) {
      std::uint64_t n = out.size();
      if (produced_ < 16) {
        n = std::min<std::uint64_t>(n, 16 - produced_);
      } else if (produced_ < lastStart) {
        n = std::min<std::uint64_t>(n, lastStart - produced_);
        held_.append(out.substr(0, static_cast<std::size_t>(n)));
      } else if (produced_ < total_) {
        n = std::min<std::uint64_t>(n, total_ - produced_);
        tail_.append(out.substr(0, static_cast<std::size_t>(n)));
      } else if (produced_ + n - total_ > (std::uint64_t{1} << 20)) {
        fail(name_, "decompressed data exceeds the SPZ blocks by more than 1 MiB");
      }
      produced_ += n;
      out.remove_prefix(static_cast<std::size_t>(n));
    }
  }

  Header h_;
  std::string name_;
  std::array<std::size_t, 6> record_{};
  std::array<std::uint64_t, 6> start_{};  // each block's first byte after the header
  std::size_t last_ = 0;                  // the last block that is not empty
  std::uint64_t total_ = 0;               // the header and the blocks, decompressed
  base::GunzipFeed gunzip_;
  std::uint64_t produced_ = 0, decoded_ = 0;
  std::string held_;  // the blocks before the last, whole as they came
  std::string tail_;  // the last block's records from decoded_ on (from tailAt_)
  std::size_t tailAt_ = 0;
};

}  // namespace

GaussianColumns openSpzColumns(std::string_view head, const std::string& name,
                               std::uint64_t fileBytes) {
  GaussianColumns found;
  if (head.size() < 4 || base::loadLe<std::uint32_t>(head.data()) != kMagic) return found;
  // The header and the table of contents first (a table said to lie further in than
  // 1 MiB: read whole instead of waiting for it).
  const std::uint64_t need = head.size() < 32 ? 32
                                              : base::loadLe<std::uint32_t>(head.data() + 16) +
                                                    static_cast<std::uint8_t>(head[15]) * 16ull;
  if (need > (std::uint64_t{1} << 20)) return found;
  if (head.size() < need && need <= fileBytes) {
    found.needMore = true;
    return found;
  }
  const V4Layout v4 = parseV4(
      [&](std::uint64_t offset, std::size_t n) {
        if (offset > head.size() || n > head.size() - offset)
          fail(name, "expected an SPZ table of contents at byte " + std::to_string(offset) +
                         ", got " + std::to_string(head.size()) + " bytes");
        return std::string(head.substr(static_cast<std::size_t>(offset), n));
      },
      fileBytes, name);
  found.decoder = std::make_unique<SpzColumns>(v4);
  return found;
}

GaussianStream openGaussianStream(std::string_view head, const std::string& name,
                                  std::uint64_t fileBytes) {
  GaussianStream found;
  if (!base::isGzip(head)) {
    // One byte may be the gzip magic's first.
    found.needMore = head.size() == 1 && static_cast<std::uint8_t>(head[0]) == 0x1f;
    return found;
  }
  const std::string h16 = base::gunzipPrefix(head, 16);
  if (h16.size() < 4 || base::loadLe<std::uint32_t>(h16.data()) != kMagic) {
    // Not yet known: a gzip header with a long name or comment field, or the first
    // deflate block's bytes still to come (a damaged start stays undecided: read whole).
    found.needMore = h16.size() < 4 && head.size() < 4096;
    return found;
  }
  if (h16.size() < 16) {
    found.needMore = head.size() < 4096;
    return found;
  }
  std::uint64_t total = 0;
  const Header h = parseLegacyHeader(h16, name, total);
  // Deflate's largest ratio is 1032:1: a header claiming more cannot be true.
  if (fileBytes > 0 && total / 1032 > fileBytes)
    fail(name, std::to_string(fileBytes) + " bytes of gzip data cannot hold the " +
                   std::to_string(total) + " bytes of " + std::to_string(h.count) + " splats");
  try {
    found.decoder = std::make_unique<SpzStream>(h, name);
  } catch (const base::GzipError& e) {  // zlib that cannot start
    fail(name, e.what());
  }
  return found;
}

GaussianCloud readSpzGaussians(std::string_view bytes, std::string_view name) {
  if (base::isGzip(bytes)) return readLegacy(bytes, name);
  if (bytes.size() >= 4 && base::loadLe<std::uint32_t>(bytes.data()) == kMagic)
    return readV4(bytes, name);
  fail(name, "not an SPZ file (neither gzip nor NGSP)");
}

std::unique_ptr<GaussianBatchReader> openSpzGaussianBatches(const std::string& path) {
  return std::make_unique<SpzBatches>(path);
}

}  // namespace gs::splats
