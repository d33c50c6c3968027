// The merged levels of a QNV tileset (splats/merged_levels.hpp, docs/tilesets.md "Merged
// levels"): exact, order-free sums; merged Gaussians that keep their members' place,
// coverage and headlight shading; the part bytes refused when damaged.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"
#include "qnv/volume.hpp"
#include "splats/lod_tree.hpp"
#include "splats/merged_levels.hpp"

using namespace gs;

namespace {

/// A 24^3 ball whose value falls off from its centre: gradients everywhere, pointing in.
qnv::SelectedVectors ballVectors() {
  qnv::Volume v;
  v.dims = glm::uvec3(24);
  v.spacing = glm::vec3(1.0f, 1.0f, 2.0f);
  v.samples.resize(v.voxelCount());
  for (std::uint32_t z = 0; z < 24; ++z)
    for (std::uint32_t y = 0; y < 24; ++y)
      for (std::uint32_t x = 0; x < 24; ++x) {
        const double r = std::hypot(x - 11.5, y - 11.5, z - 11.5) / 12.0;
        v.samples[x + 24u * (y + 24u * z)] = static_cast<float>(std::max(0.0, 1.0 - r) * 200.0);
      }
  qnv::VolumeEncodeOptions options;
  options.profile.opacityScale = 0.01f;  // a faint haze: merged opacities stay below 1
  return qnv::selectVolumeVectors(v, options);
}

qnv::TilesetOptions cut() {
  qnv::TilesetOptions o;
  o.brickVoxels = 8;  // depth 2: 8-voxel leaves, a 16-voxel level 1, the root
  o.mergedCellsLog2 = 2;
  return o;
}

}  // namespace

TEST_CASE("merged levels: sums are exact, so any split of the vectors gives the same bytes",
          "[splats][merged]") {
  const qnv::SelectedVectors selected = ballVectors();
  REQUIRE(selected.vectors.size() > 5000);
  const qnv::TilesetLayout layout(selected.header, cut());
  REQUIRE(layout.depth() == 2);
  splats::MergedLevelBuilder whole(layout, 2), a(layout, 2), b(layout, 2), joined(layout, 2);
  for (const qnv::SourceVector& v : selected.vectors) whole.add(v);
  // Two shares taking every other vector, in reverse order, merged through their bytes.
  for (std::size_t i = selected.vectors.size(); i-- > 0;) (i % 2 ? a : b).add(selected.vectors[i]);
  std::string error;
  REQUIRE(joined.addSerialized(a.serialize(), "a", error));
  REQUIRE(joined.addSerialized(b.serialize(), "b", error));
  CHECK(joined.serialize() == whole.serialize());
  CHECK(whole.cellCount() > 8);

  // Damaged, foreign or short bytes are refused with a sentence naming the part.
  std::string bytes = whole.serialize();
  bytes[40] ^= 1;
  splats::MergedLevelBuilder other(layout, 2);
  CHECK_FALSE(other.addSerialized(bytes, "parts/0-of-1/merged.qnvm", error));
  CHECK(error.find("parts/0-of-1/merged.qnvm") != std::string::npos);
  CHECK(error.find("CRC") != std::string::npos);
  CHECK_FALSE(other.addSerialized(whole.serialize().substr(0, 30), "p", error));
  splats::MergedLevelBuilder coarser(layout, 3);
  CHECK_FALSE(coarser.addSerialized(whole.serialize(), "p", error));
  CHECK(error.find("cells per axis") != std::string::npos);
  CHECK_FALSE(other.addSerialized("not a part", "p", error));
}

TEST_CASE("merged levels: every interior node's Gaussians keep its vectors' place and coverage",
          "[splats][merged]") {
  const qnv::SelectedVectors selected = ballVectors();
  const qnv::TilesetLayout layout(selected.header, cut());
  splats::MergedLevelBuilder builder(layout, 2);
  double coverage = 0.0;
  const qnv::StreamHeader& h = layout.templateHeader();
  for (const qnv::SourceVector& v : selected.vectors) {
    builder.add(v);
    const auto p = splats::vectorProfile(h, v.magnitude, h.palette[v.color].a / 255.0f);
    if (p.peak >= splats::kVisiblePeak)
      coverage += (p.peak - splats::kVisiblePeak) *
                  splats::meanProjectedArea(glm::vec3(p.spread, p.spread, 0.0f));
  }
  const auto nodes = builder.build();
  // The root and the level-1 nodes (24 voxels: 2 x 2 x 2 of 16).
  REQUIRE(nodes.count(qnv::TilesetCell{0, glm::uvec3(0)}) == 1);
  std::size_t level1 = 0;
  for (const auto& [node, cloud] : nodes) {
    level1 += node.level == 1;
    CHECK(node.level < 2);
    REQUIRE(cloud.shDegree == 2);
    REQUIRE(!cloud.empty());
    CHECK(cloud.size() <= 4u * 4u * 4u);
    // Each level's merged splats carry the coverage of all the vectors (clamped opacity
    // aside: the ball's haze is faint, so nothing reaches 1 here).
    double merged = 0.0;
    for (const auto& [other, c] : nodes)
      if (other.level == node.level)
        for (std::size_t i = 0; i < c.size(); ++i)
          merged += splats::splatCoverage(c.scales[i], c.opacities[i]);
    CHECK(merged == Approx(coverage).epsilon(0.02));
    for (std::size_t i = 0; i < cloud.size(); ++i) {
      // Centres inside the volume's box of voxel centres (half a voxel of margin).
      CHECK(glm::all(glm::greaterThanEqual(cloud.positions[i], h.boundsMin - 0.5f)));
      CHECK(glm::all(glm::lessThanEqual(cloud.positions[i], h.boundsMax + 1.0f)));
      CHECK(cloud.opacities[i] > 0.0f);
      CHECK(cloud.opacities[i] < 1.0f);
    }
  }
  CHECK(level1 == 8);
}

TEST_CASE("merged levels: a flat wall's merged splat is lit as its vectors, brighter facing",
          "[splats][merged]") {
  // A step in z: gradients (along +z) only in the two layers z = 7, 8, a flat wall.
  qnv::Volume v;
  v.dims = glm::uvec3(16, 16, 16);
  v.samples.resize(v.voxelCount());
  for (std::uint32_t z = 0; z < 16; ++z)
    for (std::uint32_t i = 0; i < 256; ++i) v.samples[z * 256u + i] = z >= 8 ? 200.0f : 0.0f;
  const qnv::SelectedVectors selected = qnv::selectVolumeVectors(v, {});
  qnv::TilesetOptions o;
  o.brickVoxels = 8;
  const qnv::TilesetLayout layout(selected.header, o);
  splats::MergedLevelBuilder builder(layout, 1);
  for (const qnv::SourceVector& s : selected.vectors) builder.add(s);
  const auto nodes = builder.build();
  const splats::GaussianCloud& root = nodes.at(qnv::TilesetCell{0, glm::uvec3(0)});
  REQUIRE(root.size() == 4);  // the layer z = 8 in 2 x 2 cells (value 0 is transparent)
  // Vectors shade as ambient 0.2 + 0.8 |n . d| (render/splat_model.hpp): full colour
  // seen along the normal, the ambient share edge on. The SH of degree 2 follows |n . d|
  // by its Legendre series 1/2 + 5/8 P2: 1.125 facing, 0.1875 edge on.
  const glm::vec3 facing = splats::shColor(root, 0, glm::vec3(0.0f, 0.0f, -1.0f));
  const glm::vec3 edge = splats::shColor(root, 0, glm::vec3(1.0f, 0.0f, 0.0f));
  const float f = facing.r + facing.g + facing.b, e = edge.r + edge.g + edge.b;
  REQUIRE(e > 0.05f);
  CHECK(f / e == Approx((0.2 + 0.8 * 1.125) / (0.2 + 0.8 * 0.1875)).epsilon(0.05));
  // The wall's splats are flat across z: thinnest scale along the normal.
  for (std::size_t i = 0; i < root.size(); ++i) {
    const glm::mat3 sigma = splats::covariance(root.scales[i], root.rotations[i]);
    CHECK(sigma[2][2] < 0.25f * sigma[0][0]);
  }
}

TEST_CASE("merged levels: only the top levels are summed, so the sums stay bounded",
          "[splats][merged]") {
  // qnv::deepestMergedLevel: 8^L R^3 <= 2^18 cells, levels 0..2 for R = 16.
  CHECK(qnv::deepestMergedLevel(4) == 2);
  CHECK(qnv::deepestMergedLevel(5) == 1);
  CHECK(qnv::deepestMergedLevel(7) == 0);
  const qnv::SelectedVectors selected = ballVectors();
  qnv::TilesetOptions o;
  o.brickVoxels = 2;  // depth 4
  const qnv::TilesetLayout layout(selected.header, o);
  REQUIRE(layout.depth() == 4);
  splats::MergedLevelBuilder builder(layout, 4);
  for (const qnv::SourceVector& v : selected.vectors) builder.add(v);
  int deepest = -1;
  for (const auto& [node, cloud] : builder.build()) deepest = std::max(deepest, int{node.level});
  CHECK(deepest == 2);
}
