// MoviePlayer: a MovieDecoder on a worker thread with a small queue of decoded frames
// (docs/media.md, "Threading").
#include "formats/movie.hpp"

#include <algorithm>
#include <cmath>

namespace gs::formats {

namespace {

std::int64_t indexAt(double t, double frameDuration, std::int64_t frameCount) {
  if (!(t > 0.0) || frameDuration <= 0.0) return 0;
  const double k = std::floor(t / frameDuration + 1e-6);
  return std::clamp(static_cast<std::int64_t>(std::min(k, 9e15)), std::int64_t{0},
                    std::max<std::int64_t>(frameCount - 1, 0));
}

}  // namespace

MoviePlayer::MoviePlayer(Opener open, std::size_t queueFrames)
    : queueFrames_(std::max<std::size_t>(queueFrames, 1)) {
  worker_ = std::thread([this, open = std::move(open)]() mutable { run(std::move(open)); });
}

MoviePlayer::~MoviePlayer() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  worker_.join();
}

MoviePlayer::Status MoviePlayer::status() const {
  std::lock_guard lock(mutex_);
  return status_;
}

MoviePlayer::Status MoviePlayer::waitOpened() {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, [&] { return status_ != Status::opening; });
  return status_;
}

std::string MoviePlayer::error() const {
  std::lock_guard lock(mutex_);
  return error_;
}

double MoviePlayer::duration() const {
  std::lock_guard lock(mutex_);
  return duration_;
}

std::uint64_t MoviePlayer::framesDecoded() const {
  std::lock_guard lock(mutex_);
  return framesDecoded_;
}

void MoviePlayer::run(Opener open) {
  std::string error;
  std::unique_ptr<MovieDecoder> decoder = open(error);
  {
    std::lock_guard lock(mutex_);
    if (!decoder) {
      status_ = Status::failed;
      error_ = error.empty() ? "cannot open the movie" : error;
    } else {
      status_ = Status::ready;
      duration_ = decoder->duration();
      frameDuration_ = decoder->frameDuration();
      frameCount_ = decoder->frameCount();
    }
  }
  ready_.notify_all();
  if (!decoder) return;
  std::unique_lock lock(mutex_);
  for (;;) {
    // What to decode next: the wanted frame when it is not queued, else the frame after
    // the run of queued frames that follows it, while the queue has room.
    std::int64_t next = -1;
    wake_.wait(lock, [&] {
      if (stop_) return true;
      const auto has = [&](std::int64_t i) {
        return std::any_of(queue_.begin(), queue_.end(),
                           [i](const auto& f) { return f->index == i; });
      };
      if (!has(wanted_)) {
        next = wanted_;
        return true;
      }
      std::int64_t i = wanted_;
      while (has(i + 1)) ++i;
      if (i + 1 < frameCount_ && queue_.size() < queueFrames_) {
        next = i + 1;
        return true;
      }
      return false;
    });
    if (stop_) return;
    if (next == wanted_) {
      // A jump: frames outside [wanted, wanted + queue) are of no use now.
      std::erase_if(queue_, [&](const auto& f) {
        return f->index < wanted_ || f->index >= wanted_ + static_cast<std::int64_t>(queueFrames_);
      });
    }
    lock.unlock();
    auto frame = std::make_shared<VideoFrame>();
    const bool ok = decoder->decodeFrame(next, *frame, error);
    lock.lock();
    framesDecoded_ = decoder->framesDecoded();
    if (!ok) {
      status_ = Status::failed;
      error_ = error;
      ready_.notify_all();
      return;
    }
    if (queue_.size() >= queueFrames_) queue_.pop_front();
    const auto at = std::find_if(queue_.begin(), queue_.end(),
                                 [&](const auto& f) { return f->index > frame->index; });
    queue_.insert(at, std::move(frame));
    ready_.notify_all();
  }
}

std::shared_ptr<const VideoFrame> MoviePlayer::pickLocked(std::int64_t index) {
  std::shared_ptr<const VideoFrame> best;
  for (const auto& f : queue_)
    if (f->index <= index && (!best || f->index > best->index)) best = f;
  if (best) {
    // Frames before the one shown are done with.
    std::erase_if(queue_, [&](const auto& f) { return f->index < best->index; });
    last_ = best;
  }
  return last_;
}

std::shared_ptr<const VideoFrame> MoviePlayer::frameFor(double t) {
  std::unique_lock lock(mutex_);
  if (status_ != Status::ready) return last_;
  const std::int64_t index = indexAt(t, frameDuration_, frameCount_);
  if (index != wanted_) {
    wanted_ = index;
    wake_.notify_one();
  }
  return pickLocked(index);
}

std::shared_ptr<const VideoFrame> MoviePlayer::waitFrameFor(double t) {
  std::unique_lock lock(mutex_);
  ready_.wait(lock, [&] { return status_ != Status::opening; });
  if (status_ != Status::ready) return nullptr;
  const std::int64_t index = indexAt(t, frameDuration_, frameCount_);
  wanted_ = index;
  wake_.notify_one();
  std::shared_ptr<const VideoFrame> found;
  ready_.wait(lock, [&] {
    if (status_ != Status::ready) return true;
    for (const auto& f : queue_)
      if (f->index == index) found = f;
    return found != nullptr;
  });
  if (!found) return nullptr;
  pickLocked(index);
  return found;
}

}  // namespace gs::formats
