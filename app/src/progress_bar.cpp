#include "app/progress_bar.hpp"

#include <algorithm>

#include <unistd.h>

namespace gs::app {

ProgressBar::ProgressBar(std::string label, std::FILE* stream, bool enabled)
    : label_(std::move(label)), stream_(stream), active_(enabled && isatty(fileno(stream)) == 1) {}

ProgressBar::~ProgressBar() {
  finish();
}

void ProgressBar::update(double fraction) {
  if (!active_ || finished_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - lastDraw_ < std::chrono::milliseconds(50)) return;
  lastDraw_ = now;
  draw(fraction);
}

void ProgressBar::finish() {
  if (!active_ || finished_) return;
  draw(1.0);
  std::fputc('\n', stream_);
  finished_ = true;
}

void ProgressBar::draw(double fraction) {
  constexpr int kWidth = 30;
  fraction = std::clamp(fraction, 0.0, 1.0);
  const int filled = static_cast<int>(fraction * kWidth + 0.5);
  std::string bar(static_cast<std::size_t>(filled), '#');
  bar.append(static_cast<std::size_t>(kWidth - filled), '.');
  std::fprintf(stream_, "\r%s [%s] %3d%%", label_.c_str(), bar.c_str(),
               static_cast<int>(fraction * 100.0 + 0.5));
  std::fflush(stream_);
}

}  // namespace gs::app
