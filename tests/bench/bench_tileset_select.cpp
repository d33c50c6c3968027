// The tileset selection rule at several distances (docs/tilesets.md, "Choosing bricks"):
// reads a tileset's index.qnvt and prints, for a view along -Z at 1.5 to 48 times the
// box's diagonal (400 pixels high, 45 degrees), how many vectors the screen-space rule
// alone chooses and how many the opacity-aware rule (volume tilesets) chooses, against
// the tileset's count; with merged levels (docs/tilesets.md, "Merged levels"), the nodes
// drawn merged, their splats (read from the merged bricks' headers) and the vectors still
// chosen beside them, and the bytes a viewer fetches for it all (the chosen prefixes and
// the merged bricks whole). A Gaussian tileset's counts are splats, not records. Pure
// computation: no fetching, no drawing.
//
//   bench_tileset_select INDEX.qnvt
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "qnv/stream.hpp"
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
  const bool gaussian = index->header.kind == gs::qnv::StreamKind::gaussian;
  const std::uint64_t per = gaussian ? std::max(1u, index->header.recordsPerElement()) : 1;
  const char* unit = gaussian ? "splats" : "vectors";
  std::printf("%s: %zu bricks, %llu %s, %s\n", argv[1], index->bricks.size(),
              static_cast<unsigned long long>(index->header.vectorCount / per), unit,
              gaussian                                            ? "Gaussian"
              : index->header.kind == gs::qnv::StreamKind::volume ? "volume"
                                                                  : "surface");
  // Splats and bytes of each interior brick's merged brick (0 where there is none).
  std::vector<std::uint64_t> mergedSplats(index->bricks.size(), 0);
  std::vector<std::uint64_t> mergedBytes(index->bricks.size(), 0);
  std::uint64_t tilesetBytes = 0;
  for (const gs::qnv::TilesetBrick& b : index->bricks) tilesetBytes += b.fileBytes;
  const std::filesystem::path folder = std::filesystem::path(argv[1]).parent_path();
  for (std::size_t i = 0; i < index->bricks.size() && index->mergedCellsLog2 > 0; ++i) {
    if (!index->hasMerged(index->bricks[i].level)) continue;
    std::ifstream m(folder / index->bricks[i].mergedPath(), std::ios::binary);
    std::string head(gs::qnv::kHeaderBytes, '\0');
    m.read(head.data(), static_cast<std::streamsize>(head.size()));
    if (const auto h = gs::qnv::parseHeader(head, "merged", error); h)
      mergedSplats[i] = h->vectorCount / std::max(1u, h->recordsPerElement());
    std::error_code ec;
    const auto size = std::filesystem::file_size(folder / index->bricks[i].mergedPath(), ec);
    mergedBytes[i] = ec ? 0 : size;
    tilesetBytes += mergedBytes[i];
  }
  std::printf("%llu bytes of bricks and merged bricks\n",
              static_cast<unsigned long long>(tilesetBytes));
  std::printf(
      "| distance / diagonal | screen-space rule | opacity-aware rule | selection time | "
      "merged nodes | merged splats | %s beside them | drawn in all | bytes fetched |\n",
      unit);
  std::printf("|---|---|---|---|---|---|---|---|---|\n");
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
        counts[rule] += c.records / per;
      seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    }
    const gs::session::MergedChoice merged = gs::session::chooseMerged(*index, {view});
    std::uint64_t splats = 0, beside = 0, fetched = 0;
    for (std::size_t i : merged.merged) {
      splats += mergedSplats[i];
      fetched += mergedBytes[i];
    }
    for (const auto& c : gs::session::selectBricks(*index, view, {}, merged.skip)) {
      beside += c.records / per;
      fetched += gs::qnv::brickPrefixBytes(index->bricks[c.brick], index->header, c.records);
    }
    std::printf(
        "| %.1f | %llu | %llu | %.2f ms | %zu | %llu | %llu | %llu (%.2f%%) | %llu (%.1f%%) |\n",
        factor, static_cast<unsigned long long>(counts[0]),
        static_cast<unsigned long long>(counts[1]), seconds * 1e3, merged.merged.size(),
        static_cast<unsigned long long>(splats), static_cast<unsigned long long>(beside),
        static_cast<unsigned long long>(splats + beside),
        100.0 * static_cast<double>(splats + beside) /
            static_cast<double>(std::max<std::uint64_t>(index->header.vectorCount / per, 1)),
        static_cast<unsigned long long>(fetched),
        100.0 * static_cast<double>(fetched) /
            static_cast<double>(std::max<std::uint64_t>(tilesetBytes, 1)));
  }
  return 0;
}
