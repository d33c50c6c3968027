// The selection passes of the out-of-core mesh tileset encode (qnv/surface_tileset.hpp):
// the plan's header and the vectors its filter keeps are selectSurfaceVectors's exactly,
// for every selection (all, fractions with ties at the threshold, counts, none), with face
// colours, vertex colours (more than 256: the median cut) and none; the colour bound.
#include <catch2/catch.hpp>

#include <map>
#include <random>

#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "qnv/surface_tileset.hpp"

using namespace gs::qnv;

namespace {

// Corners on a coarse integer grid: many areas tie exactly; some triangles degenerate.
TriangleMesh gridMesh(unsigned seed, int colors) {
  TriangleMesh m;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> coord(0, 3), channel(0, 255);
  for (int i = 0; i < 300; ++i) {
    m.positions.push_back(glm::vec3(coord(rng), coord(rng), coord(rng)) * 0.5f);
    if (colors == 1) m.vertexColors.push_back(Rgba8(channel(rng), channel(rng), channel(rng), 255));
  }
  std::uniform_int_distribution<std::uint32_t> index(0, 299);
  for (int t = 0; t < 500; ++t) {
    m.indices.insert(m.indices.end(), {index(rng), index(rng), index(rng)});
    if (colors == 2) m.faceColors.push_back(Rgba8(40 * (t % 4), 0, 255, 255));
  }
  return m;
}

// The mesh as a soup, in batches of 7 triangles.
class MeshSoup final : public TriangleSoupReader {
 public:
  explicit MeshSoup(const TriangleMesh& m) : m_(m) {}
  std::uint64_t triangleCount() const override { return m_.triangleCount(); }
  void forEachTriangle(const TriangleBatchCallback& callback) override {
    std::vector<SurfaceTriangle> batch;
    for (std::size_t t = 0; t < m_.triangleCount(); ++t) {
      SurfaceTriangle s;
      const std::uint32_t* i = &m_.indices[3 * t];
      s.a = m_.positions[i[0]];
      s.b = m_.positions[i[1]];
      s.c = m_.positions[i[2]];
      s.color = !m_.faceColors.empty() ? m_.faceColors[t]
                : !m_.vertexColors.empty()
                    ? triangleMeanColor(m_.vertexColors[i[0]], m_.vertexColors[i[1]],
                                        m_.vertexColors[i[2]])
                    : m_.baseColor;
      batch.push_back(s);
      if (batch.size() == 7 || t + 1 == m_.triangleCount()) {
        callback(t + 1 - batch.size(), batch);
        batch.clear();
      }
    }
  }

 private:
  const TriangleMesh& m_;
};

}  // namespace

TEST_CASE("out-of-core selection keeps selectSurfaceVectors's vectors", "[qnv][mesh][ooc]") {
  for (int colors : {0, 1, 2}) {
    const TriangleMesh mesh = gridMesh(7 + colors, colors);
    for (const Selection& selection :
         {Selection{1.0, 0}, Selection{0.3, 0}, Selection{0.05, 0}, Selection{1.0, 77},
          Selection{1.0, 1}, Selection{0.0, 0}, Selection{1.0, 100000}}) {
      INFO("colours " << colors << ", fraction " << selection.fraction << ", count "
                      << selection.count);
      SurfaceEncodeOptions options;
      options.selection = selection;
      EncodeSummary summary;
      const SelectedVectors whole = selectSurfaceVectors(mesh, options, &summary);
      MeshSoup soup(mesh);
      const SurfaceSelectionPlan plan = planSurfaceSelection(soup, options, 1000);
      CHECK(serializeHeader(plan.header) == serializeHeader(whole.header));
      CHECK(plan.summary.elements == summary.elements);
      CHECK(plan.summary.candidates == summary.candidates);
      CHECK(plan.summary.kept == summary.kept);
      // The filter over the soup keeps the same triangles, with the same colours.
      std::vector<SourceVector> kept;
      SurfaceKeepFilter filter(plan);
      soup.forEachTriangle([&](std::uint64_t first, std::span<const SurfaceTriangle> batch) {
        for (std::size_t i = 0; i < batch.size(); ++i) {
          SourceVector v;
          if (!triangleVector(batch[i].a, batch[i].b, batch[i].c, first + i, v)) continue;
          if (!filter.keep(v.magnitude)) continue;
          v.color = plan.palette.indexOf(batch[i].color);
          kept.push_back(v);
        }
      });
      REQUIRE(kept.size() == whole.vectors.size());
      for (std::size_t i = 0; i < kept.size(); ++i) {
        CHECK(kept[i].source == whole.vectors[i].source);
        CHECK(kept[i].color == whole.vectors[i].color);
        CHECK(kept[i].magnitude == whole.vectors[i].magnitude);
      }
    }
  }
}

TEST_CASE("out-of-core selection refuses more distinct colours than its bound",
          "[qnv][mesh][ooc]") {
  const TriangleMesh mesh = gridMesh(3, 1);
  MeshSoup soup(mesh);
  SurfaceEncodeOptions options;
  CHECK_THROWS_WITH(planSurfaceSelection(soup, options, 50),
                    Catch::Contains("more than 50 distinct colours"));
  // A fraction: only the kept triangles' colours count.
  options.selection.count = 20;
  CHECK_NOTHROW(planSurfaceSelection(soup, options, 50));
}

TEST_CASE("buildPaletteFromCounts is buildPalette", "[qnv][mesh][ooc]") {
  std::mt19937 rng(5);
  for (int distinct : {1, 200, 256, 257, 3000}) {
    std::uniform_int_distribution<int> pick(0, distinct - 1);
    std::vector<Rgba8> colors;
    for (int i = 0; i < 5000; ++i) {
      const int c = pick(rng);
      colors.push_back(Rgba8(c % 17 * 15, c / 17 % 16 * 16, c * 7 % 256, c % 3 == 0 ? 255 : 128));
    }
    std::vector<std::uint8_t> indices;
    const auto palette = buildPalette(colors, indices);
    std::map<std::uint32_t, std::uint64_t> counts;
    for (const Rgba8& c : colors) ++counts[paletteKey(c)];
    const CountedPalette counted = buildPaletteFromCounts({counts.rbegin(), counts.rend()});
    CHECK(counted.palette == palette);
    for (std::size_t i = 0; i < colors.size(); ++i) CHECK(counted.indexOf(colors[i]) == indices[i]);
  }
}
