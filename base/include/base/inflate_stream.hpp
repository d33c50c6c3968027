// gzip (RFC 1952) or zlib (RFC 1950) data decompressed forward, a piece at a time, from
// compressed bytes fetched on demand (never held whole): the slab readers' NRRD and NIfTI
// gzip data (formats/src/slab_io.hpp) and the piecewise SPZ reader (splats/readers.hpp,
// openGaussianBatches). Memory: zlib's state (about 40 KiB) and a 256 KiB input buffer.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace gs::base {

class InflateStream {
 public:
  /// Up to `n` compressed bytes at byte `offset` of the source into `dst`; fewer only at
  /// its end (0 past it). May throw; its exceptions pass through read() and skip().
  using Source = std::function<std::size_t(std::uint64_t offset, char* dst, std::size_t n)>;

  /// The data from compressed byte `compressedOffset` of `source` on. Concatenated gzip
  /// members are one stream (RFC 1952 2.2); anything else after a member ends the data.
  InflateStream(Source source, std::uint64_t compressedOffset);
  ~InflateStream();
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;

  /// Decompressed bytes handed out (or skipped) so far.
  std::uint64_t position() const { return position_; }
  /// Up to `n` decompressed bytes into `dst`; fewer only at the end of the data. Throws
  /// GzipError (Kind::corrupt) "corrupt gzip data at compressed byte offset O: REASON"
  /// (REASON zlib's, or "truncated" when the source ends inside a member).
  std::size_t read(char* dst, std::size_t n);
  /// Skips `n` decompressed bytes (inflating them); returns how many there were (fewer
  /// at the end). Throws as read().
  std::uint64_t skip(std::uint64_t n);
  /// Back to the start of the data (the next read inflates from `compressedOffset`).
  void rewind();

 private:
  void start();
  std::size_t refill();
  Source source_;
  std::uint64_t begin_;
  std::uint64_t inputOffset_ = 0;  // next compressed byte to fetch
  std::uint64_t position_ = 0;
  bool ended_ = false;
  std::vector<unsigned char> input_;
  struct Z;
  std::unique_ptr<Z> z_;
};

}  // namespace gs::base
