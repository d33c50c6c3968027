// The frame-stats command of --script (app/window_script.hpp): the window's frame times
// and the MovieTexture frames each viewport showed, for docs/media.md's measurements.
#include "app/window_script.hpp"

#include <algorithm>
#include <fstream>

namespace gs::app {

void WindowScript::writeFrameStats(WindowState& state, const std::string& path) {
  std::vector<double> ms;
  for (std::size_t i = 1; i < frameStamps_.size(); ++i)
    ms.push_back((frameStamps_[i] - frameStamps_[i - 1]) * 1000.0);
  if (!frameStamps_.empty()) frameStamps_.erase(frameStamps_.begin(), frameStamps_.end() - 1);
  std::ofstream out(path);
  double mean = 0.0;
  for (double m : ms) mean += m;
  std::sort(ms.begin(), ms.end());
  auto at = [&ms](double q) {
    return ms.empty() ? 0.0 : ms[std::min(ms.size() - 1, static_cast<std::size_t>(q * ms.size()))];
  };
  out << "frames " << ms.size() << " mean_ms " << (ms.empty() ? 0.0 : mean / ms.size())
      << " median_ms " << at(0.5) << " p95_ms " << at(0.95) << " max_ms "
      << (ms.empty() ? 0.0 : ms.back()) << "\n";
  for (std::size_t i = 0; i < state.viewports.size(); ++i) {
    const Viewport& v = state.viewports[i];
    out << "viewport " << i << " movie_frames "
        << (v.renderer() ? v.renderer()->statistics().movieFrames : 0) << " movie_uploads "
        << (v.renderer() ? v.renderer()->statistics().movieUploads : 0) << "\n";
  }
  if (!out) state.log.push_back({true, "frame-stats: cannot write " + path});
}

}  // namespace gs::app
