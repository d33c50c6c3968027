// `--frame-log FILE`: one line per frame of the window, for the soak test
// (tests/soak/soak.sh, docs/soak.md) and anyone measuring the window. CSV, one header line:
//
//   seconds,frame_ms,work_ms,rss_kib,vectors0,vectors1,vectors2,vectors3,lod0,lod1,lod2,lod3
//
// seconds: since the log was opened (steady clock), at the end of the frame; frame_ms: from
// the end of the previous frame to the end of this one (what a user sees, the wait for
// events included); work_ms: from the end of that wait to the end of the frame (input,
// streaming, drawing, swap); rss_kib: resident memory of the process (/proc/self/statm,
// KiB); vectorsI: QNV vectors drawn in viewport I this frame (0 for an empty or absent
// viewport); lodI: its level of detail (fraction 0..1; 0 when absent). Each line is written
// and flushed at the end of its frame, so a killed window leaves whole lines.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <span>
#include <string>

namespace gs::app {

struct WindowState;

/// What one line of the log says (see the file comment for the units).
struct FrameSample {
  double seconds = 0.0;
  double frameMs = 0.0;
  double workMs = 0.0;
  std::uint64_t rssKib = 0;
  std::uint64_t vectors[4] = {0, 0, 0, 0};
  double lod[4] = {0.0, 0.0, 0.0, 0.0};
};

/// The header line (no newline).
const char* frameLogHeader();
/// One line for `sample` (no newline): times with 3 decimals (ms: 0.001 ms), lods with 4.
std::string formatFrameLine(const FrameSample& sample);
/// Resident memory of this process in KiB (/proc/self/statm); 0 when unreadable.
std::uint64_t residentKib();

class FrameLog {
 public:
  /// Opens (truncates) `path` and writes the header; ok() says whether it could.
  explicit FrameLog(const std::string& path);
  ~FrameLog();
  FrameLog(const FrameLog&) = delete;
  FrameLog& operator=(const FrameLog&) = delete;

  bool ok() const { return file_ != nullptr; }
  /// The wait for events has ended: the frame's work starts.
  void beginFrame();
  /// The frame was swapped: writes its line (vectors and lods from `state`'s viewports).
  void endFrame(const WindowState& state);
  /// The frame was drawn: writes its line with the splats drawn and the level of detail of
  /// each viewport (at most 4 of each are written; missing ones are 0). The window's
  /// endFrame(state) and `--snapshot --frame-log` both write through it.
  void endFrame(std::span<const std::uint64_t> vectors, std::span<const double> lods);

 private:
  using Clock = std::chrono::steady_clock;
  std::FILE* file_ = nullptr;
  Clock::time_point start_, lastEnd_, begin_;
};

}  // namespace gs::app
