// VRML parse throughput: reads every .wrl under a folder into memory, then parses each
// file N times on one thread and prints MB, seconds and MB/s.
//
//   bench_parse [folder] [repetitions]
//
// The folder defaults to ../shared/corpus/vrml/kicad (relative to the working
// directory, i.e. run it from the project root); repetitions default to 5.
#include "vrml/parser.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace {

bool readAll(const std::filesystem::path& p, std::string& out) {
  std::FILE* f = std::fopen(p.string().c_str(), "rb");
  if (f == nullptr) return false;
  char buf[1 << 16];
  std::size_t n = 0;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  std::fclose(f);
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const std::filesystem::path dir = argc > 1 ? argv[1] : "../shared/corpus/vrml/kicad";
  const int reps = argc > 2 ? std::max(1, std::atoi(argv[2])) : 5;
  if (!std::filesystem::is_directory(dir)) {
    std::fprintf(stderr, "bench_parse: no folder %s\n", dir.string().c_str());
    return 1;
  }
  struct Input {
    std::string name;
    std::string bytes;
  };
  std::vector<Input> inputs;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() || e.path().extension() != ".wrl") continue;
    Input in{e.path().string(), {}};
    if (readAll(e.path(), in.bytes)) inputs.push_back(std::move(in));
  }
  std::sort(inputs.begin(), inputs.end(),
            [](const Input& a, const Input& b) { return a.name < b.name; });
  std::size_t bytes = 0;
  for (const Input& in : inputs) bytes += in.bytes.size();
  if (inputs.empty()) {
    std::fprintf(stderr, "bench_parse: no .wrl files under %s\n", dir.string().c_str());
    return 1;
  }
  std::size_t nodes = 0, errors = 0;
  // One untimed pass: builds the node table and warms the caches.
  for (const Input& in : inputs) {
    const gs::vrml::Scene s = gs::vrml::parseVrml(in.bytes, in.name);
    nodes += s.rootNodes.size();
    errors += s.diagnostics.errorCount();
  }
  // Each pass parses every file once and destroys its scene before the next file, as a
  // viewer loading one world after another would. Parsing and destruction are timed apart
  // (the parse figure is what a viewer waits for); the best pass is reported too because
  // other processes on the machine add noise.
  using Clock = std::chrono::steady_clock;
  double parseSec = 0, freeSec = 0, best = 1e300, bestWithFree = 1e300;
  for (int r = 0; r < reps; ++r) {
    double p = 0, f = 0;
    for (const Input& in : inputs) {
      const auto t0 = Clock::now();
      auto scene = std::make_unique<gs::vrml::Scene>(gs::vrml::parseVrml(in.bytes, in.name));
      const auto t1 = Clock::now();
      if (scene->rootNodes.empty()) ++errors;
      scene.reset();
      const auto t2 = Clock::now();
      p += std::chrono::duration<double>(t1 - t0).count();
      f += std::chrono::duration<double>(t2 - t1).count();
    }
    parseSec += p;
    freeSec += f;
    best = std::min(best, p);
    bestWithFree = std::min(bestWithFree, p + f);
  }
  const double mb1 = static_cast<double>(bytes) / 1e6;
  const double mb = mb1 * reps;
  std::printf(
      "%zu files, %.2f MB x %d = %.1f MB parsed in %.3f s: %.1f MB/s (best pass %.1f MB/s); "
      "with scene destruction (%.3f s): %.1f MB/s (best pass %.1f MB/s); %zu root nodes, %zu "
      "errors\n",
      inputs.size(), mb1, reps, mb, parseSec, mb / parseSec, mb1 / best, freeSec,
      mb / (parseSec + freeSec), mb1 / bestWithFree, nodes, errors);
  return 0;
}
