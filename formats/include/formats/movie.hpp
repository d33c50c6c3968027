// Movies for MovieTexture (ISO/IEC 14772-1:1997 6.28) through FFmpeg's libavformat,
// libavcodec and libswscale: MPEG-1 (the standard's format) and whatever else the
// installed FFmpeg decodes. MovieDecoder decodes on the calling thread; MoviePlayer runs
// one on a worker thread with a small frame queue so the drawing thread never waits
// (docs/media.md). Safe for untrusted input: a file FFmpeg cannot read, or larger than
// MovieLimits, is an error string, never a crash.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gs::formats {

/// One decoded picture.
struct VideoFrame {
  int width = 0, height = 0;       // pixels
  std::int64_t index = 0;          // frame number from 0
  double time = 0.0;               // seconds from the clip's start: index * frameDuration
  std::vector<std::uint8_t> rgba;  // width * height * 4 bytes, rows in this order:
  bool bottomRowFirst = false;     // false: top row first; true: bottom row first (OpenGL's)
  /// Whether some pixel's alpha is below 255: a stream whose pixel format has alpha (an
  /// animated GIF's transparent colour, VP8/VP9 or PNG with alpha) and uses it; alpha
  /// is 255 everywhere otherwise.
  bool translucent = false;
};

/// What a movie may be.
struct MovieLimits {
  int maxSide = 8192;                      // pixels, each of width and height
  std::int64_t maxPixels = 4096LL * 4096;  // width * height
};

/// Decodes one movie's video stream. Frames are timed by counting at the stream's frame
/// rate from its first frame (MPEG-1 is constant-rate; the container's time stamps, often
/// missing in MPEG program streams, are not used), so frame k covers media time
/// [k / rate, (k + 1) / rate).
class MovieDecoder {
 public:
  /// A decoder over `bytes` (the whole file); `name` (URL or path) names it in errors.
  /// Null with `error` set when FFmpeg cannot open it, it has no video stream, no decoder,
  /// or a size over `limits`. Reads the stream's packets once to count its frames.
  static std::unique_ptr<MovieDecoder> open(std::string bytes, const std::string& name,
                                            std::string& error, const MovieLimits& limits = {});
  ~MovieDecoder();
  MovieDecoder(const MovieDecoder&) = delete;
  MovieDecoder& operator=(const MovieDecoder&) = delete;

  int width() const;
  int height() const;
  /// Seconds per frame (1 / frame rate), > 0.
  double frameDuration() const;
  /// Frames in the stream (from the packet count), >= 1.
  std::int64_t frameCount() const;
  /// Seconds: frameCount() * frameDuration() (the duration_changed of 6.28).
  double duration() const;
  /// The frame index shown at media time `t` (seconds), clamped to the clip.
  std::int64_t frameIndexAt(double t) const;
  /// Decodes frame `index` (clamped to the clip) into `out`. Decoding moves forward;
  /// an earlier frame rewinds to the start. False with `error` when decoding fails before
  /// any frame; a stream that ends early gives its last decoded frame.
  bool decodeFrame(std::int64_t index, VideoFrame& out, std::string& error);
  /// Frames from here on come bottom row first (VideoFrame::bottomRowFirst), as
  /// glTexImage2D takes them, flipped on the decoding thread; false (the default): top first.
  void setBottomRowFirst(bool bottomFirst);
  /// Pictures the codec has produced since open (each frame decoded once; a rewind decodes
  /// the frames before the one asked for again): how tests see that a movie is decoded once.
  std::uint64_t framesDecoded() const;

 private:
  struct Impl;
  explicit MovieDecoder(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// A MovieDecoder on its own thread with a queue of a few decoded frames: the frame asked
/// for and the next ones (forward play needs no wait). The drawing thread asks with
/// frameFor() and takes whatever is ready. All members are thread-safe.
class MoviePlayer {
 public:
  /// Opens the movie on the worker thread with `open` (which returns null and sets the
  /// error on failure).
  using Opener = std::function<std::unique_ptr<MovieDecoder>(std::string& error)>;
  explicit MoviePlayer(Opener open, std::size_t queueFrames = 4);
  ~MoviePlayer();  // stops and joins the worker
  MoviePlayer(const MoviePlayer&) = delete;
  MoviePlayer& operator=(const MoviePlayer&) = delete;

  enum class Status { opening, ready, failed };
  Status status() const;
  /// Waits until the movie is open (ready) or failed, and says which.
  Status waitOpened();
  /// Why opening or decoding failed (status failed).
  std::string error() const;
  /// Seconds, once ready (0 before).
  double duration() const;
  /// MovieDecoder::framesDecoded of the worker's decoder (0 before it opened).
  std::uint64_t framesDecoded() const;

  /// Asks for the frame at media time `t` (seconds) and returns the best frame ready
  /// now: that frame when decoded, else the nearest earlier one queued, else the last
  /// frame returned (null before the first). Never waits for decoding.
  std::shared_ptr<const VideoFrame> frameFor(double t);
  /// As frameFor(t) but waits until the frame for `t` is decoded (or the movie failed):
  /// how --snapshot gets the same pixels every run. Null when the movie failed.
  std::shared_ptr<const VideoFrame> waitFrameFor(double t);

 private:
  void run(Opener open);
  std::shared_ptr<const VideoFrame> pickLocked(std::int64_t index);

  mutable std::mutex mutex_;
  std::condition_variable wake_, ready_;
  Status status_ = Status::opening;
  std::string error_;
  double duration_ = 0.0, frameDuration_ = 0.0;
  std::int64_t frameCount_ = 0;
  std::uint64_t framesDecoded_ = 0;
  std::int64_t wanted_ = 0;
  std::size_t queueFrames_;
  std::deque<std::shared_ptr<const VideoFrame>> queue_;  // by index, ascending
  std::shared_ptr<const VideoFrame> last_;
  bool stop_ = false;
  std::thread worker_;
};

}  // namespace gs::formats
