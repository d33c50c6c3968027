// writeMovie: MPEG-1 video + MP2 audio in an MPEG program stream through libavformat and
// libavcodec's built-in encoders (mpeg1video, mp2).
#include "movie_maker.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
#include <libavutil/channel_layout.h>
}

#include <cmath>
#include <cstdint>

namespace gs::test {

namespace {

struct Encoder {
  AVCodecContext* codec = nullptr;
  AVStream* stream = nullptr;
  AVFrame* frame = nullptr;
  ~Encoder() {
    av_frame_free(&frame);
    avcodec_free_context(&codec);
  }
};

/// Sends `frame` (null: flush) and writes every packet the encoder gives.
bool encode(AVFormatContext* out, Encoder& e, const AVFrame* frame) {
  if (avcodec_send_frame(e.codec, frame) < 0) return false;
  AVPacket* p = av_packet_alloc();
  bool ok = true;
  for (;;) {
    const int r = avcodec_receive_packet(e.codec, p);
    if (r == AVERROR(EAGAIN) || r == AVERROR_EOF) break;
    if (r < 0) {
      ok = false;
      break;
    }
    av_packet_rescale_ts(p, e.codec->time_base, e.stream->time_base);
    p->stream_index = e.stream->index;
    if (av_interleaved_write_frame(out, p) < 0) ok = false;
  }
  av_packet_free(&p);
  return ok;
}

}  // namespace

bool writeMovie(const std::string& path, const MovieSpec& spec, std::string& error) {
  av_log_set_level(AV_LOG_ERROR);  // not the muxer's notes on buffer sizes
  AVFormatContext* out = nullptr;
  if (avformat_alloc_output_context2(&out, nullptr, "mpeg", path.c_str()) < 0 || !out) {
    error = "no MPEG program stream muxer";
    return false;
  }
  Encoder video, audio;
  bool ok = true;
  auto fail = [&](const std::string& why) {
    error = why;
    ok = false;
  };
  // Video: mpeg1video, YUV 4:2:0, a grey level that changes with the frame.
  const AVCodec* vc = avcodec_find_encoder(AV_CODEC_ID_MPEG1VIDEO);
  if (!vc) fail("no mpeg1video encoder");
  if (ok) {
    video.stream = avformat_new_stream(out, nullptr);
    video.codec = avcodec_alloc_context3(vc);
    video.codec->width = spec.width;
    video.codec->height = spec.height;
    video.codec->time_base = AVRational{1, spec.fps};
    video.codec->framerate = AVRational{spec.fps, 1};
    video.codec->pix_fmt = AV_PIX_FMT_YUV420P;
    video.codec->gop_size = 12;
    video.codec->bit_rate = 400000;
    if (avcodec_open2(video.codec, vc, nullptr) < 0) fail("cannot open mpeg1video");
  }
  if (ok) {
    avcodec_parameters_from_context(video.stream->codecpar, video.codec);
    video.stream->time_base = video.codec->time_base;
  }
  const AVCodec* ac = spec.audio ? avcodec_find_encoder(AV_CODEC_ID_MP2) : nullptr;
  if (ok && spec.audio && !ac) fail("no mp2 encoder");
  if (ok && ac) {
    audio.stream = avformat_new_stream(out, nullptr);
    audio.codec = avcodec_alloc_context3(ac);
    audio.codec->sample_fmt = AV_SAMPLE_FMT_S16;
    audio.codec->sample_rate = spec.sampleRate;
    av_channel_layout_default(&audio.codec->ch_layout, 1);
    audio.codec->bit_rate = 64000;
    audio.codec->time_base = AVRational{1, spec.sampleRate};
    if (avcodec_open2(audio.codec, ac, nullptr) < 0) fail("cannot open mp2");
  }
  if (ok && ac) {
    avcodec_parameters_from_context(audio.stream->codecpar, audio.codec);
    audio.stream->time_base = audio.codec->time_base;
  }
  if (ok && avio_open(&out->pb, path.c_str(), AVIO_FLAG_WRITE) < 0) fail("cannot write " + path);
  if (ok && avformat_write_header(out, nullptr) < 0) fail("cannot write the header");
  const auto frames = static_cast<std::int64_t>(std::lround(spec.seconds * spec.fps));
  const auto samples = static_cast<std::int64_t>(std::lround(spec.seconds * spec.sampleRate));
  std::int64_t nextFrame = 0, nextSample = 0;
  if (ok) {
    video.frame = av_frame_alloc();
    video.frame->format = AV_PIX_FMT_YUV420P;
    video.frame->width = spec.width;
    video.frame->height = spec.height;
    if (av_frame_get_buffer(video.frame, 0) < 0) fail("out of memory");
  }
  if (ok && ac) {
    audio.frame = av_frame_alloc();
    audio.frame->format = AV_SAMPLE_FMT_S16;
    audio.frame->sample_rate = spec.sampleRate;
    av_channel_layout_default(&audio.frame->ch_layout, 1);
    audio.frame->nb_samples = audio.codec->frame_size;
    if (av_frame_get_buffer(audio.frame, 0) < 0) fail("out of memory");
  }
  double phase = 0.0;
  const double kPi = 3.14159265358979323846;
  // Frames in time order, each stream when its next frame starts earlier.
  while (ok && (nextFrame < frames || (ac && nextSample < samples))) {
    const double videoAt = static_cast<double>(nextFrame) / spec.fps;
    const double audioAt = ac ? static_cast<double>(nextSample) / spec.sampleRate : 1e300;
    if (nextFrame < frames && (videoAt <= audioAt || !(nextSample < samples))) {
      av_frame_make_writable(video.frame);
      const int grey = static_cast<int>(16 + (nextFrame * 200) / std::max<std::int64_t>(frames, 1));
      for (int plane = 0; plane < 3; ++plane) {
        const int h = plane == 0 ? spec.height : spec.height / 2;
        const int w = plane == 0 ? spec.width : spec.width / 2;
        for (int y = 0; y < h; ++y)
          for (int x = 0; x < w; ++x)
            video.frame->data[plane][y * video.frame->linesize[plane] + x] =
                static_cast<std::uint8_t>(plane == 0 ? grey : 128);
      }
      video.frame->pts = nextFrame++;
      if (!encode(out, video, video.frame)) fail("cannot encode video");
    } else {
      av_frame_make_writable(audio.frame);
      auto* pcm = reinterpret_cast<std::int16_t*>(audio.frame->data[0]);
      for (int i = 0; i < audio.frame->nb_samples; ++i, ++nextSample) {
        const double t = static_cast<double>(nextSample) / spec.sampleRate;
        const double hz = t < spec.seconds / 2 ? spec.toneHz : spec.secondToneHz;
        phase += 2.0 * kPi * hz / spec.sampleRate;
        pcm[i] = nextSample < samples ? static_cast<std::int16_t>(16383.0 * std::sin(phase)) : 0;
      }
      audio.frame->pts = nextSample - audio.frame->nb_samples;
      if (!encode(out, audio, audio.frame)) fail("cannot encode audio");
    }
  }
  if (ok && !encode(out, video, nullptr)) fail("cannot flush video");
  if (ok && ac && !encode(out, audio, nullptr)) fail("cannot flush audio");
  if (ok && av_write_trailer(out) < 0) fail("cannot finish " + path);
  if (out->pb) avio_closep(&out->pb);
  avformat_free_context(out);
  return ok;
}

}  // namespace gs::test
