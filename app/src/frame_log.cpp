#include "app/frame_log.hpp"

#include "app/window_state.hpp"

#include <unistd.h>

#include <cinttypes>
#include <fstream>

namespace gs::app {

const char* frameLogHeader() {
  return "seconds,frame_ms,work_ms,rss_kib,vectors0,vectors1,vectors2,vectors3,lod0,lod1,lod2,"
         "lod3";
}

std::string formatFrameLine(const FrameSample& s) {
  char line[320];
  std::snprintf(line, sizeof line,
                "%.3f,%.3f,%.3f,%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64
                ",%.4f,%.4f,%.4f,%.4f",
                s.seconds, s.frameMs, s.workMs, s.rssKib, s.vectors[0], s.vectors[1], s.vectors[2],
                s.vectors[3], s.lod[0], s.lod[1], s.lod[2], s.lod[3]);
  return line;
}

std::uint64_t residentKib() {
  // statm: size resident shared ... in pages.
  std::ifstream in("/proc/self/statm");
  std::uint64_t size = 0, resident = 0;
  if (!(in >> size >> resident)) return 0;
  const long page = ::sysconf(_SC_PAGESIZE);
  return resident * static_cast<std::uint64_t>(page > 0 ? page : 4096) / 1024;
}

FrameLog::FrameLog(const std::string& path) : file_(std::fopen(path.c_str(), "w")) {
  start_ = lastEnd_ = begin_ = Clock::now();
  if (file_) {
    std::fprintf(file_, "%s\n", frameLogHeader());
    std::fflush(file_);
  }
}

FrameLog::~FrameLog() {
  if (file_) std::fclose(file_);
}

void FrameLog::beginFrame() {
  begin_ = Clock::now();
}

void FrameLog::endFrame(const WindowState& state) {
  std::uint64_t vectors[4] = {0, 0, 0, 0};
  double lods[4] = {0.0, 0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < state.viewports.size() && i < 4; ++i) {
    const Viewport& v = state.viewports[i];
    if (!v.renderer()) continue;
    vectors[i] = v.renderer()->statistics().splats;
    lods[i] = v.options.lod;
  }
  endFrame(vectors, lods);
}

void FrameLog::endFrame(std::span<const std::uint64_t> vectors, std::span<const double> lods) {
  if (!file_) return;
  const auto now = Clock::now();
  auto ms = [](Clock::duration d) { return std::chrono::duration<double, std::milli>(d).count(); };
  FrameSample s;
  s.seconds = ms(now - start_) / 1000.0;
  s.frameMs = ms(now - lastEnd_);
  s.workMs = ms(now - begin_);
  s.rssKib = residentKib();
  for (std::size_t i = 0; i < vectors.size() && i < 4; ++i) s.vectors[i] = vectors[i];
  for (std::size_t i = 0; i < lods.size() && i < 4; ++i) s.lod[i] = lods[i];
  lastEnd_ = now;
  std::fprintf(file_, "%s\n", formatFrameLine(s).c_str());
  std::fflush(file_);
}

}  // namespace gs::app
