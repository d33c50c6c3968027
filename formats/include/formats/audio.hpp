// Sampled sound for AudioClip (ISO/IEC 14772-1:1997 6.3) through libsndfile: WAV (the
// format the standard requires) and the other formats libsndfile reads (AIFF, AU, FLAC,
// Ogg Vorbis, ...). Safe for untrusted input: damaged or oversized data are an error
// string, never a crash.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gs::formats {

/// Decoded sound: 16-bit signed samples, channels interleaved.
struct AudioData {
  int sampleRate = 0;                 // frames per second, > 0
  int channels = 0;                   // 1 (mono) or 2 (stereo)
  std::vector<std::int16_t> samples;  // frames * channels values
  /// Seconds: frames / sampleRate (the duration_changed of 6.3).
  double duration() const {
    return sampleRate > 0 && channels > 0
               ? static_cast<double>(samples.size()) / channels / sampleRate
               : 0.0;
  }
};

/// At most this many seconds of sound are decoded (a guard against hostile headers).
inline constexpr double kMaxAudioSeconds = 30.0 * 60.0;

/// Decodes `bytes` (a whole file; `name`, its URL or path, only names it in errors).
/// False with `error` ("NAME: why") when libsndfile cannot read it, it has no frames,
/// more than two channels, or more than kMaxAudioSeconds.
bool readAudio(const std::string& bytes, const std::string& name, AudioData& out,
               std::string& error);

}  // namespace gs::formats
