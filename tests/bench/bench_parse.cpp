// VRML parse throughput: reads every .wrl under a folder into memory, then parses each
// file N times on one thread and prints MB, seconds and MB/s.
//
//   bench_parse [folder] [repetitions] [x3d]
//
// The folder defaults to ../shared/corpus/vrml/kicad (relative to the working
// directory, i.e. run it from the project root); repetitions default to 5.
//
// Then the same content in X3D's encodings (issue 20): each world is written by
// vrml::writeScene (what `ghostspace convert` does) as Classic VRML (.x3dv) and XML
// (.x3d), each text is parsed N times, and expat alone (handlers that do nothing) reads
// the XML bytes N times: the XML reader's figure is quoted as a share of expat's. A third
// argument `x3d` measures only these. The three readers take turns pass by pass, and each
// figure is the best pass, in wall-clock time and in the thread's CPU time. With XMLONLY=1
// in the environment as well, only the XML reader runs (for a profiler) and nothing is
// printed.
#include "encodings/parser.hpp"
#include "encodings/writer.hpp"

#include <expat.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
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

struct Text {
  std::string name;
  std::string bytes;
};

/// Seconds of wall-clock and of this thread's CPU time.
struct Times {
  double wall = 1e300;
  double cpu = 1e300;
};

double threadCpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

/// One pass of `work` over every text; `best` keeps the smallest wall and CPU times seen.
template <typename Work>
void timePass(const std::vector<Text>& texts, Times& best, Work&& work) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  const double c0 = threadCpuSeconds();
  for (const Text& t : texts) work(t);
  best.cpu = std::min(best.cpu, threadCpuSeconds() - c0);
  best.wall = std::min(best.wall, std::chrono::duration<double>(Clock::now() - t0).count());
}

/// expat over `bytes` with start and end handlers that do nothing; false on an XML error.
bool expatBare(const std::string& bytes) {
  XML_Parser p = XML_ParserCreate(nullptr);
  XML_SetElementHandler(
      p, [](void*, const XML_Char*, const XML_Char**) {}, [](void*, const XML_Char*) {});
  const bool ok = XML_Parse(p, bytes.data(), static_cast<int>(bytes.size()), 1) != XML_STATUS_ERROR;
  XML_ParserFree(p);
  return ok;
}

/// Parses each input, writes it as Classic VRML and XML, and prints the three figures.
void benchX3dEncodings(const std::vector<Text>& inputs, int reps) {
  std::vector<Text> classic, xml;
  for (const Text& in : inputs) {
    const gs::vrml::Scene s = gs::vrml::parseVrml(in.bytes, in.name);
    gs::vrml::WriteOptions o;
    o.encoding = gs::vrml::Encoding::classic;
    classic.push_back({in.name + ".x3dv", gs::vrml::writeScene(s, o).text});
    o.encoding = gs::vrml::Encoding::xml;
    xml.push_back({in.name + ".x3d", gs::vrml::writeScene(s, o).text});
  }
  const auto total = [](const std::vector<Text>& v) {
    std::size_t n = 0;
    for (const Text& t : v) n += t.bytes.size();
    return static_cast<double>(n) / 1e6;
  };
  std::size_t errors = 0;
  const auto parse = [&errors](const Text& t) {
    const gs::vrml::Scene s = gs::vrml::parseVrml(t.bytes, t.name);
    errors += s.diagnostics.errorCount();
  };
  parse(classic.front());  // warm
  if (std::getenv("XMLONLY") != nullptr) {
    Times t;
    for (int r = 0; r < reps; ++r) timePass(xml, t, parse);
    return;
  }
  // The three readers take turns, pass by pass, so that a machine whose load changes
  // during the run slows each of them alike; the best pass of each is kept.
  Times classicT, xmlT, expatT;
  std::size_t expatErrors = 0;
  for (int r = 0; r < reps; ++r) {
    timePass(classic, classicT, parse);
    timePass(xml, xmlT, parse);
    timePass(xml, expatT, [&expatErrors](const Text& t) { expatErrors += !expatBare(t.bytes); });
  }
  const double classicMB = total(classic) / classicT.wall, xmlMB = total(xml) / xmlT.wall,
               expatMB = total(xml) / expatT.wall;
  const double xmlCpuMB = total(xml) / xmlT.cpu, expatCpuMB = total(xml) / expatT.cpu;
  std::printf(
      "X3D Classic (.x3dv, %.2f MB): %.1f MB/s best pass (with scene destruction)\n"
      "X3D XML (.x3d, %.2f MB): %.1f MB/s best pass; expat alone on the same bytes: %.1f "
      "MB/s; the XML reader reads at %.0f%% of expat's throughput\n"
      "  in thread CPU time: XML %.1f MB/s, expat %.1f MB/s: %.0f%%\n"
      "%zu parse errors, %zu expat errors\n",
      total(classic), classicMB, total(xml), xmlMB, expatMB, 100.0 * xmlMB / expatMB, xmlCpuMB,
      expatCpuMB, 100.0 * xmlCpuMB / expatCpuMB, errors / static_cast<std::size_t>(reps),
      expatErrors / static_cast<std::size_t>(reps));
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
  if (argc > 3 && std::string(argv[3]) == "x3d") {
    std::vector<Text> texts;
    for (const Input& in : inputs) texts.push_back({in.name, in.bytes});
    benchX3dEncodings(texts, reps);
    return 0;
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
  std::vector<Text> texts;
  for (const Input& in : inputs) texts.push_back({in.name, in.bytes});
  benchX3dEncodings(texts, reps);
  return 0;
}
