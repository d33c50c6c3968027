// readMovieAudio: a movie's audio stream through libavformat, libavcodec and libswresample
// (docs/media.md, "A MovieTexture as a Sound's source").
#include "formats/movie_audio.hpp"

#include "ffmpeg_input.hpp"
#include "formats/movie.hpp"

extern "C" {
#include <libavcodec/avcodec.h>
#include <libavutil/channel_layout.h>
#include <libavutil/samplefmt.h>
#include <libswresample/swresample.h>
}

#include <memory>

namespace gs::formats {

namespace {

/// Everything FFmpeg allocated for one decode, freed in reverse order.
struct AudioDecode {
  MemoryInput input;
  AVIOContext* io = nullptr;
  AVFormatContext* format = nullptr;
  AVCodecContext* codec = nullptr;
  SwrContext* swr = nullptr;
  AVFrame* frame = nullptr;
  AVPacket* packet = nullptr;

  ~AudioDecode() {
    av_packet_free(&packet);
    av_frame_free(&frame);
    swr_free(&swr);
    avcodec_free_context(&codec);
    avformat_close_input(&format);
    if (io != nullptr) av_freep(&io->buffer);
    avio_context_free(&io);
  }
};

constexpr int kMaxSampleRate = 384000;

/// Converts `frame` (null: flushes the resampler) and appends to `out`. False when the
/// sound grows over kMaxAudioSeconds or the resampler fails.
bool convert(AudioDecode& d, const AVFrame* frame, AudioData& out, std::string& error,
             const std::string& name) {
  const int inSamples = frame != nullptr ? frame->nb_samples : 0;
  const int room = swr_get_out_samples(d.swr, inSamples);
  if (room < 0) {
    error = name + ": cannot convert the audio";
    return false;
  }
  if (room == 0) return true;
  const std::size_t at = out.samples.size();
  out.samples.resize(at + static_cast<std::size_t>(room) * static_cast<std::size_t>(out.channels));
  auto* target = reinterpret_cast<std::uint8_t*>(out.samples.data() + at);
  const int n = swr_convert(
      d.swr, &target, room,
      frame != nullptr ? const_cast<const std::uint8_t**>(frame->extended_data) : nullptr,
      inSamples);
  if (n < 0) {
    out.samples.resize(at);
    error = name + ": cannot convert the audio (" + averror(n) + ")";
    return false;
  }
  out.samples.resize(at + static_cast<std::size_t>(n) * static_cast<std::size_t>(out.channels));
  if (out.duration() > kMaxAudioSeconds) {
    error = name + ": the sound is longer than the limit";
    return false;
  }
  return true;
}

}  // namespace

bool readMovieAudio(const std::string& bytes, const std::string& name, MovieAudio& out,
                    std::string& error) {
  out = MovieAudio{};
  // The movie's length as the renderer's MovieDecoder counts it (same duration_changed).
  {
    std::string ignored;
    if (auto video = MovieDecoder::open(bytes, name, ignored)) out.duration = video->duration();
  }
  AudioDecode d;
  d.input.bytes = bytes;
  av_log_set_level(AV_LOG_QUIET);
  constexpr int kBuffer = 64 * 1024;
  auto* buffer = static_cast<std::uint8_t*>(av_malloc(kBuffer));
  d.io = avio_alloc_context(buffer, kBuffer, 0, &d.input, &MemoryInput::read, nullptr,
                            &MemoryInput::seek);
  if (d.io == nullptr) {
    av_free(buffer);
    error = name + ": out of memory";
    return false;
  }
  d.format = avformat_alloc_context();
  d.format->pb = d.io;
  d.format->flags |= AVFMT_FLAG_CUSTOM_IO;
  if (const int r = avformat_open_input(&d.format, name.c_str(), nullptr, nullptr); r < 0) {
    error = name + ": not a movie FFmpeg reads (" + averror(r) + ")";
    return false;
  }
  if (const int r = avformat_find_stream_info(d.format, nullptr); r < 0) {
    error = name + ": cannot read the movie's streams (" + averror(r) + ")";
    return false;
  }
  const AVCodec* codec = nullptr;
  const int stream = av_find_best_stream(d.format, AVMEDIA_TYPE_AUDIO, -1, -1, &codec, 0);
  if (stream < 0 || codec == nullptr) {
    error = name + ": no audio stream FFmpeg can decode";
    return false;
  }
  const AVCodecParameters* par = d.format->streams[stream]->codecpar;
  if (par->sample_rate <= 0 || par->sample_rate > kMaxSampleRate ||
      par->ch_layout.nb_channels <= 0) {
    error = name + ": an audio stream of " + std::to_string(par->sample_rate) + " Hz and " +
            std::to_string(par->ch_layout.nb_channels) + " channels";
    return false;
  }
  d.codec = avcodec_alloc_context3(codec);
  avcodec_parameters_to_context(d.codec, par);
  d.codec->thread_count = 1;
  if (const int r = avcodec_open2(d.codec, codec, nullptr); r < 0) {
    error = name + ": cannot open the " + codec->name + " decoder (" + averror(r) + ")";
    return false;
  }
  AudioData& a = out.audio;
  a.sampleRate = d.codec->sample_rate > 0 ? d.codec->sample_rate : par->sample_rate;
  a.channels = d.codec->ch_layout.nb_channels >= 2 ? 2 : 1;
  AVChannelLayout outLayout;
  av_channel_layout_default(&outLayout, a.channels);
  if (swr_alloc_set_opts2(&d.swr, &outLayout, AV_SAMPLE_FMT_S16, a.sampleRate, &d.codec->ch_layout,
                          d.codec->sample_fmt, d.codec->sample_rate, 0, nullptr) < 0 ||
      swr_init(d.swr) < 0) {
    error = name + ": cannot convert its audio to 16-bit samples";
    a = AudioData{};
    return false;
  }
  d.frame = av_frame_alloc();
  d.packet = av_packet_alloc();
  bool ended = false, ok = true;
  while (ok) {
    const int r = avcodec_receive_frame(d.codec, d.frame);
    if (r == 0) {
      ok = convert(d, d.frame, a, error, name);
      av_frame_unref(d.frame);
      continue;
    }
    if (r == AVERROR_EOF) break;
    if (r != AVERROR(EAGAIN)) break;  // a damaged stream: keep what was decoded
    if (ended) break;
    for (;;) {
      if (av_read_frame(d.format, d.packet) < 0) {
        ended = true;
        avcodec_send_packet(d.codec, nullptr);
        break;
      }
      if (d.packet->stream_index != stream) {
        av_packet_unref(d.packet);
        continue;
      }
      avcodec_send_packet(d.codec, d.packet);  // a damaged packet is skipped
      av_packet_unref(d.packet);
      break;
    }
  }
  if (ok) ok = convert(d, nullptr, a, error, name);
  if (!ok || a.samples.empty()) {
    if (ok) error = name + ": its audio stream has no samples";
    a = AudioData{};
    return false;
  }
  if (out.duration < 0.0) out.duration = a.duration();
  return true;
}

}  // namespace gs::formats
