// gzip data (RFC 1952) decompressed as its bytes arrive, pushed a piece at a time: a remote
// SPZ v2/v3 file drawn while it arrives (splats/readers.hpp, openGaussianStream). The
// pulling counterpart, over bytes fetched on demand, is base/inflate_stream.hpp.
// Memory: zlib's state (about 40 KiB) and a 64 KiB output piece.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string_view>

namespace gs::base {

class GunzipFeed {
 public:
  /// Receives each piece of decompressed bytes (at most 64 KiB), in order.
  using Sink = std::function<void(std::string_view)>;

  GunzipFeed();
  ~GunzipFeed();
  GunzipFeed(const GunzipFeed&) = delete;
  GunzipFeed& operator=(const GunzipFeed&) = delete;

  /// Decompresses `bytes`, the data's next ones (any split, empty allowed), handing the
  /// output to `sink`. As base::gunzip, concatenated members are one stream (RFC 1952 2.2)
  /// and zero padding after the last member is tolerated. Throws GzipError
  /// (Kind::corrupt): "corrupt gzip data: REASON", REASON zlib's or "trailing bytes after
  /// the gzip data"; exceptions of `sink` pass through. After a throw the feed is spent:
  /// only its destructor may follow.
  void feed(std::string_view bytes, const Sink& sink);
  /// After the data's last byte: throws GzipError "corrupt gzip data: truncated" unless
  /// a member ended last (nothing fed counts as truncated).
  void finish() const;
  /// Decompressed bytes handed to the sink so far.
  std::uint64_t produced() const { return produced_; }

 private:
  struct Z;
  std::unique_ptr<Z> z_;
  std::uint64_t produced_ = 0;
  // Between members: 0 inside one; 1 after a member ended; 2 after a 1f (the next
  // member's magic begun); 3 in zero padding.
  int between_ = 0;
};

}  // namespace gs::base
