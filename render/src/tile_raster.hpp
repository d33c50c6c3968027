// Private to render/: the pieces of the tiled CPU rasterizer (gaussian_cpu.cpp): a tile's
// accumulation buffers, the scene's depth under it, writing a finished tile into the RGBA8
// image, and the threads that run the per-thread work.
#pragma once

#include <algorithm>
#include <array>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <functional>
#include <mutex>
#include <span>
#include <system_error>
#include <thread>
#include <vector>

#include "simd4.hpp"

namespace gs::render::detail {

/// One tile's accumulation buffers, kSide x kSide pixels row by row: premultiplied colour,
/// transmittance, depth limit.
template <int kSide>
struct TileBuffers {
  alignas(16) std::array<float, kSide * kSide> r, g, b, t, limit;
};

/// The scene's depth under a rectangle of the view: width x height window depths (0..1)
/// for the pixels from (x0, y0), rows bottom to top; none (no limit) outside it or when
/// `depths` is empty.
struct DepthWindow {
  std::span<const float> depths;
  int x0 = 0, y0 = 0, width = 0, height = 0;
};

/// Starts the tw x th pixels at pixel (tx0, ty0) of the view (a tile, or a band of its
/// rows), held in the first th rows of `tile`: colour 0 and transmittance 1 there,
/// transmittance 0 past them (saturated, never drawn). Each pixel's depth limit (eye
/// distance) is `farClip`, or nearer where `depth` holds geometry: depthB / (2 d - 1 +
/// depthA), depthA and depthB the projection's [2][2] and [3][2].
template <int kSide>
void startTile(TileBuffers<kSide>& tile, int tx0, int ty0, int tw, int th, float farClip,
               const DepthWindow& depth, float depthA, float depthB) {
  const std::size_t used = static_cast<std::size_t>(th) * kSide;
  std::fill_n(tile.r.begin(), used, 0.0f);
  std::fill_n(tile.g.begin(), used, 0.0f);
  std::fill_n(tile.b.begin(), used, 0.0f);
  std::fill_n(tile.t.begin(), used, 0.0f);
  std::fill_n(tile.limit.begin(), used, 0.0f);
  const bool hasDepth = depth.depths.size() >= static_cast<std::size_t>(depth.width) *
                                                   static_cast<std::size_t>(depth.height);
  for (int j = 0; j < th; ++j) {
    const int y = ty0 + j - depth.y0;
    for (int i = 0; i < tw; ++i) {
      const auto at = static_cast<std::size_t>(j * kSide + i);
      tile.t[at] = 1.0f;
      float limit = farClip;
      const int x = tx0 + i - depth.x0;
      if (hasDepth && x >= 0 && x < depth.width && y >= 0 && y < depth.height) {
        const float d = depth.depths[static_cast<std::size_t>(y) * depth.width + x];
        if (d < 1.0f) limit = std::min(limit, depthB / (2.0f * d - 1.0f + depthA));
      }
      tile.limit[at] = limit;
    }
  }
}

/// Writes the tw x th corner of `tile` (a tile, or a band of its rows) as RGBA8 (alpha = 1 -
/// transmittance) at pixel (tx0, ty0) of `out`, an image `width` pixels wide, rows from the bottom.
template <int kSide>
void writeTile(const TileBuffers<kSide>& tile, std::uint8_t* out, int width, int tx0, int ty0,
               int tw, int th) {
  for (int j = 0; j < th; ++j) {
    std::uint8_t* row = &out[(static_cast<std::size_t>(ty0 + j) * width + tx0) * 4];
    for (int i = 0; i < tw; ++i) {
      const auto at = static_cast<std::size_t>(j * kSide + i);
      row[4 * i + 0] = level8(tile.r[at]);
      row[4 * i + 1] = level8(tile.g[at]);
      row[4 * i + 2] = level8(tile.b[at]);
      row[4 * i + 3] = level8(1.0f - tile.t[at]);
    }
  }
}

/// Writes the tw x th pixels at (tx0, ty0) of `out` (RGBA8, `width` pixels wide) as
/// transparent black: what writeTile writes for a tile no splat reached.
inline void clearTile(std::uint8_t* out, int width, int tx0, int ty0, int tw, int th) {
  for (int j = 0; j < th; ++j)
    std::memset(&out[(static_cast<std::size_t>(ty0 + j) * width + tx0) * 4], 0,
                static_cast<std::size_t>(tw) * 4);
}

/// Whether some chunk binned a splat into tile `t` (`bins[chunk][t]`).
template <typename Bins>
bool binned(const Bins& bins, int chunks, int t) {
  for (int c = 0; c < chunks; ++c)
    if (!bins[static_cast<std::size_t>(c)][static_cast<std::size_t>(t)].empty()) return true;
  return false;
}

/// Threads kept for a rasterizer's frames: run(work) runs work(0) .. work(threads - 1) at
/// once, work(0) on the calling thread, and returns when all have returned. The workers
/// start on the first run and wait between frames, so that a frame of a few splats (a far
/// level-of-detail cut) does not pay for starting threads. `work` must not throw.
class WorkerPool {
 public:
  explicit WorkerPool(int threads) : threads_(std::max(threads, 1)) {}
  ~WorkerPool() {
    {
      std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_all();
    for (std::thread& t : workers_) t.join();
  }
  WorkerPool(const WorkerPool&) = delete;
  WorkerPool& operator=(const WorkerPool&) = delete;

  /// Starts the workers (once): afterwards threads() is how many run() uses, fewer than
  /// asked when the system refused to start some.
  void start() {
    if (started_) return;
    started_ = true;
    try {
      workers_.reserve(static_cast<std::size_t>(threads_ - 1));
      for (int c = 1; c < threads_; ++c) workers_.emplace_back([this, c] { serve(c); });
    } catch (...) {  // std::system_error, std::bad_alloc: run with the workers there are
      threads_ = 1 + static_cast<int>(workers_.size());
    }
  }
  int threads() const { return threads_; }

  template <typename Work>
  void run(const Work& work) {
    const std::function<void(int)> job = [&work](int c) { work(c); };
    start();
    {
      std::lock_guard lock(mutex_);
      job_ = &job;
      running_ = threads_ - 1;
      ++generation_;
    }
    wake_.notify_all();
    job(0);
    std::unique_lock lock(mutex_);
    done_.wait(lock, [this] { return running_ == 0; });
    job_ = nullptr;
  }

 private:
  void serve(int c) {
    std::uint64_t seen = 0;
    for (;;) {
      const std::function<void(int)>* job = nullptr;
      {
        std::unique_lock lock(mutex_);
        wake_.wait(lock, [&] { return stopping_ || generation_ != seen; });
        if (stopping_) return;
        seen = generation_;
        job = job_;
      }
      (*job)(c);
      std::lock_guard lock(mutex_);
      if (--running_ == 0) done_.notify_one();
    }
  }

  int threads_;
  bool started_ = false;
  std::vector<std::thread> workers_;
  std::mutex mutex_;
  std::condition_variable wake_, done_;
  const std::function<void(int)>* job_ = nullptr;
  std::uint64_t generation_ = 0;
  int running_ = 0;
  bool stopping_ = false;
};

}  // namespace gs::render::detail
