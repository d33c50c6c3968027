// base/gunzip_feed.hpp: zlib's inflate over bytes pushed as they arrive.
#include "base/gunzip_feed.hpp"

#include <zlib.h>

#include <string>

#include "base/gzip.hpp"

namespace gs::base {

namespace {

[[noreturn]] void feedCorrupt(const std::string& why) {
  throw GzipError(GzipError::Kind::corrupt, "corrupt gzip data: " + why);
}

}  // namespace

struct GunzipFeed::Z {
  z_stream s{};
  bool initialized = false;
  unsigned char out[1 << 16];
  ~Z() {
    if (initialized) inflateEnd(&s);
  }
};

GunzipFeed::GunzipFeed() : z_(std::make_unique<Z>()) {
  if (inflateInit2(&z_->s, 16 + MAX_WBITS) != Z_OK) feedCorrupt("zlib could not start");
  z_->initialized = true;
}

GunzipFeed::~GunzipFeed() = default;

void GunzipFeed::feed(std::string_view bytes, const Sink& sink) {
  z_stream& zs = z_->s;
  const auto* in = reinterpret_cast<const unsigned char*>(bytes.data());
  std::size_t left = bytes.size();
  constexpr std::size_t kMaxFeed = 1u << 30;  // avail_in is 32-bit
  while (left > 0) {
    if (between_ != 0) {
      // After a member: another one's magic 1f 8b, or zero padding to the end.
      const unsigned char c = *in;
      ++in;
      --left;
      if (between_ == 1 && c == 0) between_ = 3;
      if (between_ == 3) {
        if (c != 0) feedCorrupt("trailing bytes after the gzip data");
      } else if (between_ == 1) {
        if (c != 0x1f) feedCorrupt("trailing bytes after the gzip data");
        between_ = 2;
      } else {  // the second byte of a member's magic
        if (c != 0x8b) feedCorrupt("trailing bytes after the gzip data");
        if (inflateReset(&zs) != Z_OK) feedCorrupt("zlib could not restart");
        static const unsigned char kMagic[2] = {0x1f, 0x8b};
        zs.next_in = const_cast<unsigned char*>(kMagic);
        zs.avail_in = 2;
        zs.next_out = z_->out;
        zs.avail_out = sizeof z_->out;
        if (inflate(&zs, Z_NO_FLUSH) != Z_OK || zs.avail_in != 0)
          feedCorrupt("zlib could not restart");
        between_ = 0;
      }
      continue;
    }
    const std::size_t take = left < kMaxFeed ? left : kMaxFeed;
    zs.next_in = const_cast<unsigned char*>(in);
    zs.avail_in = static_cast<uInt>(take);
    while (true) {
      zs.next_out = z_->out;
      zs.avail_out = sizeof z_->out;
      const int rc = inflate(&zs, Z_NO_FLUSH);
      const std::size_t made = sizeof z_->out - zs.avail_out;
      if (rc != Z_OK && rc != Z_STREAM_END && rc != Z_BUF_ERROR)
        feedCorrupt(zs.msg != nullptr ? zs.msg : "inflate failed");
      if (made > 0) {
        produced_ += made;
        sink(std::string_view(reinterpret_cast<const char*>(z_->out), made));
      }
      if (rc == Z_STREAM_END) {
        between_ = 1;
        break;
      }
      // Done when the input is used and the output piece was not filled (zlib holds
      // nothing more to give); a call that makes no progress waits for more input.
      if ((zs.avail_in == 0 && zs.avail_out != 0) || (rc == Z_BUF_ERROR && made == 0)) break;
    }
    const std::size_t used = take - zs.avail_in;
    if (used == 0 && between_ == 0) feedCorrupt("inflate made no progress");
    in += used;
    left -= used;
  }
}

void GunzipFeed::finish() const {
  if (between_ == 0 || between_ == 2) feedCorrupt("truncated");
}

}  // namespace gs::base
