// MovieDecoder over FFmpeg (libavformat demuxes from memory through a custom AVIOContext,
// libavcodec decodes, libswscale converts to RGBA). ISO/IEC 14772-1:1997 6.28.
#include "formats/movie.hpp"

#include "ffmpeg_input.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/imgutils.h>
#include <libavutil/pixdesc.h>
#include <libswscale/swscale.h>
}

#include <algorithm>
#include <cmath>
#include <cstring>

namespace gs::formats {

struct MovieDecoder::Impl {
  MemoryInput input;
  AVIOContext* io = nullptr;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  SwsContext* sws = nullptr;
  AVFrame* frame = nullptr;  // the decoder's output (emptied by a failed receive)
  AVFrame* shown = nullptr;  // the last frame decoded: frame `decoded`
  AVPacket* packet = nullptr;
  int stream = -1;
  int width = 0, height = 0;
  double frameDuration = 1.0 / 25.0;
  std::int64_t frameCount = 0;
  std::int64_t decoded = -1;   // index of the frame in `frame`; -1: none since the rewind
  std::uint64_t pictures = 0;  // frames the codec produced since open
  bool bottomFirst = false;    // rows of the frames handed out: bottom first
  bool demuxEnded = false, decoderDrained = false;
  std::string name;

  ~Impl() {
    sws_freeContext(sws);
    av_frame_free(&frame);
    av_frame_free(&shown);
    av_packet_free(&packet);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
    if (io != nullptr) av_freep(&io->buffer);
    avio_context_free(&io);
  }

  bool rewind() {
    // Time stamps first (most containers), then bytes (MPEG program streams whose time
    // stamps are sparse).
    int r = av_seek_frame(format, stream,
                          format->streams[stream]->start_time == AV_NOPTS_VALUE
                              ? 0
                              : format->streams[stream]->start_time,
                          AVSEEK_FLAG_BACKWARD);
    if (r < 0) r = av_seek_frame(format, -1, 0, AVSEEK_FLAG_BYTE);
    if (r < 0) r = avformat_seek_file(format, -1, INT64_MIN, 0, INT64_MAX, 0);
    avcodec_flush_buffers(codec);
    decoded = -1;
    demuxEnded = decoderDrained = false;
    return r >= 0;
  }

  /// The next frame into `frame`; false at the end of the stream or on an error.
  bool nextFrame(std::string& error) {
    for (;;) {
      const int r = avcodec_receive_frame(codec, frame);
      if (r == 0) {
        ++decoded;
        ++pictures;
        av_frame_unref(shown);
        av_frame_move_ref(shown, frame);
        return true;
      }
      if (r == AVERROR_EOF) {
        decoderDrained = true;
        return false;
      }
      if (r != AVERROR(EAGAIN)) {
        error = name + ": cannot decode the video: " + averror(r);
        return false;
      }
      if (demuxEnded) return false;
      // Feed the decoder the next packet of our stream (or the end of the stream).
      for (;;) {
        const int rr = av_read_frame(format, packet);
        if (rr < 0) {
          demuxEnded = true;
          avcodec_send_packet(codec, nullptr);
          break;
        }
        if (packet->stream_index != stream) {
          av_packet_unref(packet);
          continue;
        }
        const int s = avcodec_send_packet(codec, packet);
        av_packet_unref(packet);
        if (s < 0 && s != AVERROR(EAGAIN) && s != AVERROR_INVALIDDATA) {
          error = name + ": cannot decode the video: " + averror(s);
          return false;
        }
        break;
      }
    }
  }
};

MovieDecoder::MovieDecoder(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
MovieDecoder::~MovieDecoder() = default;

std::unique_ptr<MovieDecoder> MovieDecoder::open(std::string bytes, const std::string& name,
                                                 std::string& error, const MovieLimits& limits) {
  auto d = std::make_unique<Impl>();
  d->name = name;
  d->input.bytes = std::move(bytes);
  av_log_set_level(AV_LOG_QUIET);
  constexpr int kBuffer = 64 * 1024;
  auto* buffer = static_cast<std::uint8_t*>(av_malloc(kBuffer));
  d->io = avio_alloc_context(buffer, kBuffer, 0, &d->input, &MemoryInput::read, nullptr,
                             &MemoryInput::seek);
  if (d->io == nullptr) {
    av_free(buffer);
    error = name + ": out of memory";
    return nullptr;
  }
  d->format = avformat_alloc_context();
  d->format->pb = d->io;
  d->format->flags |= AVFMT_FLAG_CUSTOM_IO;
  if (const int r = avformat_open_input(&d->format, name.c_str(), nullptr, nullptr); r < 0) {
    error = name + ": not a movie FFmpeg reads (" + averror(r) + ")";
    return nullptr;  // avformat_open_input freed the format context
  }
  if (const int r = avformat_find_stream_info(d->format, nullptr); r < 0) {
    error = name + ": cannot read the movie's streams (" + averror(r) + ")";
    return nullptr;
  }
  const AVCodec* codec = nullptr;
  d->stream = av_find_best_stream(d->format, AVMEDIA_TYPE_VIDEO, -1, -1, &codec, 0);
  if (d->stream < 0 || codec == nullptr) {
    error = name + ": no video stream FFmpeg can decode";
    return nullptr;
  }
  AVStream* st = d->format->streams[d->stream];
  d->width = st->codecpar->width;
  d->height = st->codecpar->height;
  if (d->width <= 0 || d->height <= 0 || d->width > limits.maxSide || d->height > limits.maxSide ||
      static_cast<std::int64_t>(d->width) * d->height > limits.maxPixels) {
    error = name + ": a movie of " + std::to_string(d->width) + " x " + std::to_string(d->height) +
            " pixels is over the limit";
    return nullptr;
  }
  d->codec = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(d->codec, st->codecpar);
  d->codec->thread_count = 1;
  if (const int r = avcodec_open2(d->codec, codec, nullptr); r < 0) {
    error = name + ": cannot open the " + codec->name + " decoder (" + averror(r) + ")";
    return nullptr;
  }
  AVRational rate = st->avg_frame_rate;
  if (rate.num <= 0 || rate.den <= 0) rate = st->r_frame_rate;
  if (rate.num > 0 && rate.den > 0 && av_q2d(rate) <= 1000.0) d->frameDuration = 1.0 / av_q2d(rate);
  d->frame = av_frame_alloc();
  d->shown = av_frame_alloc();
  d->packet = av_packet_alloc();
  // Count the frames: one packet per frame once libavformat has parsed the stream.
  while (av_read_frame(d->format, d->packet) >= 0) {
    if (d->packet->stream_index == d->stream) ++d->frameCount;
    av_packet_unref(d->packet);
  }
  if (d->frameCount == 0) {
    error = name + ": the video stream has no frames";
    return nullptr;
  }
  d->rewind();
  return std::unique_ptr<MovieDecoder>(new MovieDecoder(std::move(d)));
}

int MovieDecoder::width() const {
  return impl_->width;
}
int MovieDecoder::height() const {
  return impl_->height;
}
double MovieDecoder::frameDuration() const {
  return impl_->frameDuration;
}
std::int64_t MovieDecoder::frameCount() const {
  return impl_->frameCount;
}
double MovieDecoder::duration() const {
  return static_cast<double>(impl_->frameCount) * impl_->frameDuration;
}

std::int64_t MovieDecoder::frameIndexAt(double t) const {
  if (!(t > 0.0)) return 0;  // also NaN
  const double k = std::floor(t / impl_->frameDuration + 1e-6);
  return std::clamp(static_cast<std::int64_t>(std::min(k, 9e15)), std::int64_t{0},
                    impl_->frameCount - 1);
}

bool MovieDecoder::decodeFrame(std::int64_t index, VideoFrame& out, std::string& error) {
  Impl& d = *impl_;
  index = std::clamp(index, std::int64_t{0}, d.frameCount - 1);
  if (index < d.decoded) d.rewind();
  while (d.decoded < index) {
    std::string problem;
    if (!d.nextFrame(problem)) {
      // The stream ended (or a frame was damaged) early: keep the last good frame.
      if (d.decoded < 0) error = problem;
      break;
    }
  }
  if (d.decoded < 0) {
    if (error.empty()) error = d.name + ": no frame could be decoded";
    return false;
  }
  const int w = d.shown->width, h = d.shown->height;
  if (w != d.width || h != d.height || w <= 0 || h <= 0) {
    error = d.name + ": the frame size changed inside the stream";
    return false;
  }
  d.sws = sws_getCachedContext(d.sws, w, h, static_cast<AVPixelFormat>(d.shown->format), w, h,
                               AV_PIX_FMT_RGBA, SWS_BILINEAR, nullptr, nullptr, nullptr);
  if (d.sws == nullptr) {
    error = d.name + ": cannot convert the frame's pixel format";
    return false;
  }
  out.width = w;
  out.height = h;
  out.index = d.decoded;
  out.time = static_cast<double>(d.decoded) * d.frameDuration;
  out.rgba.resize(static_cast<std::size_t>(w) * h * 4);
  std::uint8_t* planes[4] = {out.rgba.data(), nullptr, nullptr, nullptr};
  int strides[4] = {w * 4, 0, 0, 0};
  sws_scale(d.sws, d.shown->data, d.shown->linesize, 0, h, planes, strides);
  out.translucent = false;
  const AVPixFmtDescriptor* format =
      av_pix_fmt_desc_get(static_cast<AVPixelFormat>(d.shown->format));
  if (format != nullptr && (format->flags & (AV_PIX_FMT_FLAG_ALPHA | AV_PIX_FMT_FLAG_PAL)) != 0)
    for (std::size_t i = 3; i < out.rgba.size(); i += 4)
      if (out.rgba[i] != 255) {
        out.translucent = true;
        break;
      }
  out.bottomRowFirst = d.bottomFirst;
  if (d.bottomFirst) {  // swap rows in place: one row of scratch
    const std::size_t row = static_cast<std::size_t>(w) * 4;
    std::vector<std::uint8_t> scratch(row);
    for (int y = 0; y < h / 2; ++y) {
      std::uint8_t* top = out.rgba.data() + static_cast<std::size_t>(y) * row;
      std::uint8_t* bottom = out.rgba.data() + static_cast<std::size_t>(h - 1 - y) * row;
      std::memcpy(scratch.data(), top, row);
      std::memcpy(top, bottom, row);
      std::memcpy(bottom, scratch.data(), row);
    }
  }
  return true;
}

void MovieDecoder::setBottomRowFirst(bool bottomFirst) {
  impl_->bottomFirst = bottomFirst;
}

std::uint64_t MovieDecoder::framesDecoded() const {
  return impl_->pictures;
}

}  // namespace gs::formats
