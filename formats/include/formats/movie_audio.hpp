// The sound of a movie, for a Sound whose `source` is a MovieTexture (ISO/IEC 14772-1:1997
// 6.42: "source ... AudioClip or MovieTexture"; 6.28): the movie's audio stream decoded
// through FFmpeg (libavformat, libavcodec) and converted by libswresample to the AudioData
// that AudioClip uses (16-bit, mono or stereo, the stream's own rate), so the same outputs
// play it (docs/media.md). Safe for untrusted input: what FFmpeg cannot read is an error
// string, never a crash.
#pragma once

#include "formats/audio.hpp"

#include <string>

namespace gs::formats {

/// What readMovieAudio found.
struct MovieAudio {
  /// The movie's length in seconds as MovieDecoder counts it (its video's frames / frame
  /// rate, so the renderer and the sound report the same duration_changed); the audio's
  /// own length for a movie without video; -1 when the file is no movie FFmpeg reads.
  double duration = -1.0;
  /// The decoded sound; empty (no samples) when the movie has no audio FFmpeg decodes.
  AudioData audio;
};

/// Decodes the first audio stream of `bytes` (a whole movie file; `name`, its URL or path,
/// only names it in errors). More than two channels are mixed down to stereo. False with
/// `error` ("NAME: why") when no audio could be decoded: not a movie, no audio stream, a
/// damaged stream, or more than kMaxAudioSeconds; `out.duration` is still set when the
/// movie itself could be read.
bool readMovieAudio(const std::string& bytes, const std::string& name, MovieAudio& out,
                    std::string& error);

}  // namespace gs::formats
