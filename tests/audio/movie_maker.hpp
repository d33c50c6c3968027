// Test clips made at test time with FFmpeg's own encoders (no shipped binaries): an MPEG-1
// program stream (.mpg) with MPEG-1 video and, optionally, an MP2 audio stream.
#pragma once

#include <string>

namespace gs::test {

struct MovieSpec {
  int width = 32, height = 32;  // pixels, even
  int fps = 25;                 // frames per second
  double seconds = 1.0;         // length of both streams
  bool audio = true;            // with an MP2 stream (mono, `sampleRate` Hz)
  int sampleRate = 44100;       // one MP2 allows: 32000, 44100, 48000 (and half those)
  /// The tone: `toneHz` for the first half of the clip, `secondToneHz` for the rest
  /// (amplitude 0.5 of full scale), so the order of the samples can be checked.
  double toneHz = 440.0, secondToneHz = 880.0;
};

/// Writes the clip to `path`. False with `error` when FFmpeg lacks an encoder or the
/// file cannot be written.
bool writeMovie(const std::string& path, const MovieSpec& spec, std::string& error);

}  // namespace gs::test
