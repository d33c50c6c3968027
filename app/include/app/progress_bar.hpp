// A one-line progress bar on a terminal: "encoding  [##########..........]  50%".
#pragma once

#include <chrono>
#include <cstdio>
#include <string>

namespace gs::app {

class ProgressBar {
 public:
  /// Draws to `stream` only when it is a terminal (isatty) and `enabled`; otherwise every
  /// call does nothing, so scripts and tests see clean output.
  ProgressBar(std::string label, std::FILE* stream = stderr, bool enabled = true);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// Shows `fraction` (clamped to 0..1) done; redraws at most 20 times a second.
  void update(double fraction);
  /// Draws 100% and ends the line (also done by the destructor).
  void finish();
  bool active() const { return active_; }

 private:
  void draw(double fraction);
  std::string label_;
  std::FILE* stream_;
  bool active_;
  bool finished_ = false;
  std::chrono::steady_clock::time_point lastDraw_{};
};

}  // namespace gs::app
