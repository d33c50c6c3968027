// Execution-model figures (docs/runtime.md, "Measured"): N TimeSensor ->
// PositionInterpolator -> Transform chains advanced frame by frame (events per second,
// milliseconds per cascade), and whether the chains redraw without re-tessellation.
//
//   bench_events [chains] [frames]      (default 10000 chains, 300 frames)
#include "encodings/parser.hpp"
#include "runtime/execution_model.hpp"
#include "scene/traversal.hpp"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

/// A world of `n` chains, each a TimeSensor driving a PositionInterpolator that moves a
/// Transform holding a Box (its own geometry node, so tessellations can be counted).
std::string chainsWorld(int n) {
  std::string w = "#VRML V2.0 utf8\n";
  w.reserve(static_cast<std::size_t>(n) * 400);
  for (int i = 0; i < n; ++i) {
    const std::string k = std::to_string(i);
    w +=
        "DEF T" + k + " TimeSensor { cycleInterval " + std::to_string(1 + i % 7) + " loop TRUE }\n";
    w += "DEF P" + k + " PositionInterpolator { key [0 0.5 1] keyValue [0 0 0, 1 " + k +
         " 0, 0 0 0] }\n";
    w += "DEF X" + k + " Transform { children Shape { geometry Box {} } }\n";
    w += "ROUTE T" + k + ".fraction_changed TO P" + k + ".set_fraction\n";
    w += "ROUTE P" + k + ".value_changed TO X" + k + ".set_translation\n";
  }
  return w;
}

}  // namespace

int main(int argc, char** argv) {
  const int chains = argc > 1 ? std::max(1, std::atoi(argv[1])) : 10000;
  const int frames = argc > 2 ? std::max(1, std::atoi(argv[2])) : 300;
  auto t0 = Clock::now();
  auto scene =
      std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(chainsWorld(chains), "chains.wrl"));
  const double parseSeconds = since(t0);
  t0 = Clock::now();
  gs::runtime::ExecutionModel model(scene, 1.7e9);
  const double loadSeconds = since(t0);

  gs::scene::SceneTraversal traversal(scene);
  gs::scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  for (const auto& s : frame.shapes) traversal.mesh(*s.geometry);
  const std::uint64_t tessellationsBefore = traversal.tessellationCount();

  const auto sentBefore = model.statistics().eventsSent;
  const auto deliveredBefore = model.statistics().eventsDelivered;
  double cascadeSeconds = 0.0, worst = 0.0, traversalSeconds = 0.0;
  for (int f = 1; f <= frames; ++f) {
    const auto c0 = Clock::now();
    model.advanceTo(1.7e9 + f / 60.0);
    const double s = since(c0);
    cascadeSeconds += s;
    worst = std::max(worst, s);
    const auto w0 = Clock::now();
    traversal.collect(traversal.boundViewpointCamera(), frame);
    for (const auto& sh : frame.shapes) traversal.mesh(*sh.geometry);
    traversalSeconds += since(w0);
  }
  const auto sent = model.statistics().eventsSent - sentBefore;
  const auto delivered = model.statistics().eventsDelivered - deliveredBefore;
  std::printf("bench_events: %d chains, %d frames at 60 Hz\n", chains, frames);
  std::printf("  parse %.3f s, load (routes, initial events) %.3f s\n", parseSeconds, loadSeconds);
  std::printf("  events sent %llu, delivered %llu: %.2f M events/s (sent + delivered)\n",
              static_cast<unsigned long long>(sent), static_cast<unsigned long long>(delivered),
              static_cast<double>(sent + delivered) / cascadeSeconds / 1e6);
  std::printf("  cascade per frame: mean %.3f ms, worst %.3f ms\n", cascadeSeconds / frames * 1e3,
              worst * 1e3);
  std::printf("  traversal per frame (collect the shapes, find their meshes): mean %.3f ms\n",
              traversalSeconds / frames * 1e3);
  std::printf("  tessellations while animating: %llu (shapes: %zu)\n",
              static_cast<unsigned long long>(traversal.tessellationCount() - tessellationsBefore),
              frame.shapes.size());
  return 0;
}
