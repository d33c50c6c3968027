// ClipLoads: AudioClip and MovieTexture sounds decoded on a worker thread (docs/media.md).
#include "clip_loads.hpp"

#include "base/file.hpp"
#include "formats/movie_audio.hpp"

#include <utility>

namespace gs::audio::detail {

ClipResult decodeClip(ClipJob job) {
  ClipResult result;
  result.clip = job.clip;
  result.movie = job.movie;
  std::string failures;
  const auto fail = [&](const std::string& why) {
    failures += (failures.empty() ? "" : "; ") + why;
  };
  for (ClipSource& s : job.sources) {
    std::string error = s.error;
    bool ok = error.empty() && s.fetched;
    std::string bytes = std::move(s.bytes);
    if (error.empty() && !s.path.empty()) ok = base::readFile(s.path, bytes, error);
    if (ok && job.movie) {
      formats::MovieAudio sound;
      const bool decoded = formats::readMovieAudio(bytes, s.url, sound, error);
      if (decoded) result.data = std::make_shared<formats::AudioData>(std::move(sound.audio));
      if (sound.duration >= 0.0) {  // a movie, with or without sound: the first readable one
        result.duration = sound.duration;
        if (!decoded) fail(error);
        break;
      }
    } else if (ok) {
      auto decoded = std::make_shared<formats::AudioData>();
      if (formats::readAudio(bytes, s.url, *decoded, error)) {
        result.duration = decoded->duration();
        result.data = std::move(decoded);
        break;
      }
    }
    fail(error.empty() ? s.url : error);
  }
  if (!result.data) result.failures = failures;
  return result;
}

ClipLoads::~ClipLoads() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (worker_.joinable()) worker_.join();
}

void ClipLoads::submit(ClipJob job) {
  {
    std::lock_guard lock(mutex_);
    jobs_.push_back(std::move(job));
    ++pending_;
    if (!worker_.joinable()) worker_ = std::thread([this] { run(); });
  }
  wake_.notify_one();
}

std::vector<ClipResult> ClipLoads::take() {
  std::lock_guard lock(mutex_);
  std::vector<ClipResult> out;
  out.swap(done_);
  pending_ -= out.size();
  return out;
}

void ClipLoads::waitIdle() {
  std::unique_lock lock(mutex_);
  idle_.wait(lock, [&] { return jobs_.empty() && !busy_; });
}

std::size_t ClipLoads::pending() const {
  std::lock_guard lock(mutex_);
  return pending_;
}

void ClipLoads::run() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [&] { return stop_ || !jobs_.empty(); });
    if (stop_) return;
    ClipJob job = std::move(jobs_.front());
    jobs_.pop_front();
    busy_ = true;
    lock.unlock();
    ClipResult result = decodeClip(std::move(job));
    lock.lock();
    done_.push_back(std::move(result));
    busy_ = false;
    if (jobs_.empty()) idle_.notify_all();
  }
}

}  // namespace gs::audio::detail
