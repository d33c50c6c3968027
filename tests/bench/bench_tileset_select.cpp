// The tileset selection rule at several distances (docs/tilesets.md, "Choosing bricks"):
// reads a tileset's index.qnvt and prints, for a view along -Z at 1.5 to 48 times the
// box's diagonal (400 pixels high, 45 degrees), how many vectors the screen-space rule
// alone chooses and how many the opacity-aware rule (volume tilesets) chooses, against
// the tileset's count. Pure computation: no fetching, no drawing.
//
//   bench_tileset_select INDEX.qnvt
#include <chrono>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>

#include "qnv/tileset.hpp"
#include "session/tileset_selection.hpp"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s INDEX.qnvt\n", argv[0]);
    return 2;
  }
  std::ifstream in(argv[1], std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  std::string error;
  const auto index = gs::qnv::parseTilesetIndex(bytes.str(), argv[1], error);
  if (!index) {
    std::fprintf(stderr, "%s\n", error.c_str());
    return 1;
  }
  const glm::vec3 lo = index->header.boundsMin, hi = index->header.boundsMax;
  const glm::vec3 centre = (lo + hi) * 0.5f;
  const float diagonal = glm::length(hi - lo);
  std::printf("%s: %zu bricks, %llu vectors, %s\n", argv[1], index->bricks.size(),
              static_cast<unsigned long long>(index->header.vectorCount),
              index->header.kind == gs::qnv::StreamKind::volume ? "volume" : "surface");
  std::printf(
      "| distance / diagonal | screen-space rule | opacity-aware rule | selection time |\n");
  std::printf("|---|---|---|---|\n");
  for (const double factor : {1.5, 3.0, 6.0, 12.0, 24.0, 48.0}) {
    gs::session::TilesetView view;
    view.position = centre + glm::vec3(0.0f, 0.0f, static_cast<float>(factor) * diagonal);
    view.heightPixels = 400;
    std::uint64_t counts[2] = {0, 0};
    double seconds = 0.0;
    for (int rule = 0; rule < 2; ++rule) {
      gs::session::TilesetBudget budget;
      if (rule == 0) budget.maxLostOpticalDepth = 0.0;
      const auto t0 = std::chrono::steady_clock::now();
      for (const auto& c : gs::session::selectBricks(*index, view, budget))
        counts[rule] += c.records;
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    std::printf("| %.1f | %llu | %llu | %.2f ms |\n", factor,
                static_cast<unsigned long long>(counts[0]),
                static_cast<unsigned long long>(counts[1]), seconds * 1e3);
  }
  return 0;
}
