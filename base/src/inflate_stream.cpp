// base/inflate_stream.hpp: zlib's inflate over compressed bytes fetched 256 KiB at a time.
#include "base/inflate_stream.hpp"

#include <zlib.h>

#include <algorithm>
#include <string>

#include "base/gzip.hpp"

namespace gs::base {

struct InflateStream::Z {
  z_stream s{};
  bool initialized = false;
  ~Z() {
    if (initialized) inflateEnd(&s);
  }
};

InflateStream::InflateStream(Source source, std::uint64_t compressedOffset)
    : source_(std::move(source)), begin_(compressedOffset), input_(256 * 1024) {
  start();
}

InflateStream::~InflateStream() = default;

void InflateStream::start() {
  z_ = std::make_unique<Z>();
  // 15 + 32: a gzip or a zlib header, detected.
  if (inflateInit2(&z_->s, 15 + 32) != Z_OK)
    throw GzipError(GzipError::Kind::corrupt, "cannot start zlib's inflate");
  z_->initialized = true;
  inputOffset_ = begin_;
  position_ = 0;
  ended_ = false;
}

void InflateStream::rewind() {
  start();
}

std::size_t InflateStream::refill() {
  const std::size_t got =
      source_(inputOffset_, reinterpret_cast<char*>(input_.data()), input_.size());
  inputOffset_ += got;
  z_->s.next_in = input_.data();
  z_->s.avail_in = static_cast<uInt>(got);
  return got;
}

std::size_t InflateStream::read(char* dst, std::size_t n) {
  std::size_t done = 0;
  z_stream& s = z_->s;
  while (done < n && !ended_) {
    if (s.avail_in == 0 && refill() == 0)
      throw GzipError(GzipError::Kind::corrupt, "corrupt gzip data at compressed byte offset " +
                                                    std::to_string(inputOffset_) + ": truncated");
    const std::size_t want = std::min<std::size_t>(n - done, 1u << 30);
    s.next_out = reinterpret_cast<Bytef*>(dst + done);
    s.avail_out = static_cast<uInt>(want);
    const int rc = inflate(&s, Z_NO_FLUSH);
    const std::size_t produced = want - s.avail_out;
    done += produced;
    position_ += produced;
    if (rc == Z_STREAM_END) {
      // Another gzip member may follow (RFC 1952 2.2); anything else ends the data. Its
      // two magic bytes may straddle the input buffer's end: the one left is kept.
      if (s.avail_in < 2) {
        const std::size_t have = s.avail_in;
        if (have == 1) input_[0] = *s.next_in;
        const std::size_t got = source_(inputOffset_, reinterpret_cast<char*>(input_.data()) + have,
                                        input_.size() - have);
        inputOffset_ += got;
        s.next_in = input_.data();
        s.avail_in = static_cast<uInt>(have + got);
      }
      if (s.avail_in >= 2 && s.next_in[0] == 0x1f && s.next_in[1] == 0x8b)
        inflateReset(&s);
      else
        ended_ = true;
    } else if (rc != Z_OK && !(rc == Z_BUF_ERROR && produced > 0)) {
      const std::uint64_t at = inputOffset_ - s.avail_in;
      throw GzipError(GzipError::Kind::corrupt, "corrupt gzip data at compressed byte offset " +
                                                    std::to_string(at) + ": " +
                                                    (s.msg ? s.msg : zError(rc)));
    }
  }
  return done;
}

std::uint64_t InflateStream::skip(std::uint64_t n) {
  std::vector<char> scratch(std::min<std::uint64_t>(n, 1u << 20));
  std::uint64_t done = 0;
  while (done < n) {
    const std::size_t got =
        read(scratch.data(),
             static_cast<std::size_t>(std::min<std::uint64_t>(n - done, scratch.size())));
    if (got == 0) break;
    done += got;
  }
  return done;
}

}  // namespace gs::base
