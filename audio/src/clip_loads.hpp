// Private to audio/: AudioClip and MovieTexture sounds decoded on a worker thread, so that
// no frame of the window waits for a whole clip to decode (docs/media.md, "Threading").
#pragma once

#include "formats/audio.hpp"

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

namespace gs::vrml {
class Node;
}

namespace gs::audio::detail {

/// One URL of a clip's url field, in order: a local file the worker reads, or bytes the
/// caller fetched already, or why it cannot be used.
struct ClipSource {
  std::string url;
  std::string path;   // a local file to read on the worker ("": see bytes)
  std::string bytes;  // the file's bytes when path is empty and fetched is true
  bool fetched = false;
  std::string error;  // why this URL is of no use (refused, not fetched), when not empty
};

/// A clip to decode: the first source that decodes wins (4.5.4).
struct ClipJob {
  const vrml::Node* clip = nullptr;
  bool movie = false;  // a MovieTexture: its audio stream (formats::readMovieAudio)
  std::vector<ClipSource> sources;
};

/// What decoding a clip gave.
struct ClipResult {
  const vrml::Node* clip = nullptr;
  bool movie = false;                              // as ClipJob::movie
  std::shared_ptr<const formats::AudioData> data;  // null: silent
  double duration = -1.0;                          // seconds; -1: unreadable
  std::string failures;                            // "url: why; ..." when data is null
};

/// Decodes the jobs one after another on its own thread (started at the first job).
class ClipLoads {
 public:
  ClipLoads() = default;
  ~ClipLoads();  // stops after the job under way and joins
  ClipLoads(const ClipLoads&) = delete;
  ClipLoads& operator=(const ClipLoads&) = delete;

  void submit(ClipJob job);
  /// The results finished since the last call, in the order submitted. Never waits.
  std::vector<ClipResult> take();
  /// Waits until every job submitted so far is finished (then take() has them all).
  void waitIdle();
  /// Jobs submitted whose results were not taken yet.
  std::size_t pending() const;

 private:
  void run();

  mutable std::mutex mutex_;
  std::condition_variable wake_, idle_;
  std::deque<ClipJob> jobs_;
  std::vector<ClipResult> done_;
  std::size_t pending_ = 0;  // submitted, not taken
  bool busy_ = false, stop_ = false;
  std::thread worker_;
};

/// Decodes `job` on the calling thread (what the worker runs).
ClipResult decodeClip(ClipJob job);

}  // namespace gs::audio::detail
