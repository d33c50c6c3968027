// Shared by the FFmpeg readers (movie.cpp, movie_audio.cpp): a file held in memory as a
// seekable avio stream, and FFmpeg's error codes as text. Internal to formats/.
#pragma once

extern "C" {
#include <libavformat/avformat.h>
#include <libavutil/error.h>
}

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>

namespace gs::formats {

inline std::string averror(int code) {
  char text[AV_ERROR_MAX_STRING_SIZE] = {};
  av_strerror(code, text, sizeof text);
  return text;
}

/// The file's bytes as a seekable stream for avio.
struct MemoryInput {
  std::string bytes;
  std::size_t position = 0;

  static int read(void* opaque, std::uint8_t* buffer, int size) {
    auto* in = static_cast<MemoryInput*>(opaque);
    const std::size_t left = in->bytes.size() - in->position;
    const std::size_t n = std::min(left, static_cast<std::size_t>(std::max(size, 0)));
    if (n == 0) return AVERROR_EOF;
    std::memcpy(buffer, in->bytes.data() + in->position, n);
    in->position += n;
    return static_cast<int>(n);
  }
  static std::int64_t seek(void* opaque, std::int64_t offset, int whence) {
    auto* in = static_cast<MemoryInput*>(opaque);
    const auto size = static_cast<std::int64_t>(in->bytes.size());
    if (whence & AVSEEK_SIZE) return size;
    std::int64_t base = 0;
    switch (whence & ~AVSEEK_FORCE) {
      case SEEK_SET:
        break;
      case SEEK_CUR:
        base = static_cast<std::int64_t>(in->position);
        break;
      case SEEK_END:
        base = size;
        break;
      default:
        return -1;
    }
    const std::int64_t to = base + offset;
    if (to < 0 || to > size) return -1;
    in->position = static_cast<std::size_t>(to);
    return to;
  }
};

}  // namespace gs::formats
