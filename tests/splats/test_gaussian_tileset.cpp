// A Gaussian splatting scene as a QNV tileset (splats/gaussian_tileset.hpp; docs/tilesets.md
// "Gaussian tilesets"): every kept splat in exactly one brick, each brick importance
// first, ancestors holding each leaf's most important splats, an index the reader takes,
// and merged bricks that keep the region's place and coverage.
#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>

#include "qnv/decoder.hpp"
#include "qnv/error.hpp"
#include "qnv/record.hpp"
#include "qnv/tileset.hpp"
#include "splats/gaussian_tileset.hpp"
#include "splats/lod_tree.hpp"
#include "splats/merged_levels.hpp"
#include "splats/qnv_gaussians.hpp"

using namespace gs;

namespace {

/// 4,000 random splats in a 2 x 1 x 1 box, SH degree 1, a few of them invisible.
splats::GaussianCloud randomGaussians() {
  std::mt19937 random(7);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  splats::GaussianCloud c;
  c.setShDegree(1);
  for (int i = 0; i < 4000; ++i) {
    c.positions.push_back({2.0f * unit(random), unit(random), unit(random)});
    c.scales.push_back(glm::vec3(0.002f + 0.02f * unit(random), 0.002f + 0.02f * unit(random),
                                 0.001f + 0.004f * unit(random)));
    c.rotations.push_back(glm::normalize(
        glm::quat(unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f, 0.3f)));
    c.opacities.push_back(i % 100 == 0 ? 0.0f : 0.05f + 0.9f * unit(random));
    c.shDc.push_back({unit(random) - 0.5f, unit(random) - 0.5f, unit(random) - 0.5f});
    for (int k = 0; k < 3; ++k) c.shRest.push_back(glm::vec3(0.1f * (unit(random) - 0.5f)));
  }
  return c;
}

qnv::TilesetOptions gaussianCut() {
  qnv::TilesetOptions o;
  o.brickVectors = 128;  // 3,960 splats: depth 2 (8^2 x 128 >= 3,960)
  o.mergedCellsLog2 = 2;
  return o;
}

}  // namespace

TEST_CASE("a Gaussian tileset puts every kept splat in one brick, importance first",
          "[splats][tileset]") {
  const splats::GaussianCloud cloud = randomGaussians();
  const splats::GaussianTilesetFiles files = splats::buildGaussianTileset(cloud, gaussianCut());
  const qnv::TilesetIndex& index = files.index;
  CHECK(files.splats == 3960);  // the 40 of opacity 0 are left out
  CHECK(index.depth == 2);
  CHECK(index.header.kind == qnv::StreamKind::gaussian);
  const std::uint32_t words = index.header.recordsPerElement();
  CHECK(index.header.vectorCount == files.splats * words);

  // The reader takes the index as written.
  std::string error;
  const auto parsed = qnv::parseTilesetIndex(qnv::serializeTilesetIndex(index), "t", error);
  REQUIRE(parsed);
  CHECK(parsed->bricks.size() == files.bricks.size());

  // Every brick decodes as a Gaussian stream of its records, A codes never increasing,
  // centres inside its box; all together hold each kept splat once.
  std::size_t total = 0;
  std::vector<float> opacities;
  std::uint64_t rootTopCode = 0;
  for (std::size_t b = 0; b < files.bricks.size(); ++b) {
    const qnv::BrickFile& f = files.bricks[b];
    CHECK(f.brick.vectorCount % words == 0);
    const splats::GaussianCloud part = splats::readQnvGaussians(f.bytes, f.brick.path());
    REQUIRE(part.size() == f.brick.vectorCount / words);
    total += part.size();
    std::uint64_t histogram = 0;
    for (const std::uint32_t n : f.brick.histogram) histogram += n;
    CHECK(histogram == f.brick.vectorCount);
    for (std::size_t i = 0; i < part.size(); ++i) {
      const glm::vec3 p = part.positions[i];
      CHECK(glm::all(glm::greaterThanEqual(p, f.brick.boundsMin - glm::vec3(1e-5f))));
      CHECK(glm::all(glm::lessThanEqual(p, f.brick.boundsMax + glm::vec3(1e-5f))));
      opacities.push_back(part.opacities[i]);
    }
    // The records in brick order: A (bits 8..22 of the first word) never increases.
    qnv::StreamDecoder decoder("brick");
    std::vector<std::uint64_t> firsts;
    decoder.setRecordSink([&](std::uint64_t first, std::span<const std::uint64_t> records) {
      (void)first;
      for (std::size_t r = 0; r < records.size(); r += words) firsts.push_back(records[r]);
    });
    REQUIRE(decoder.feed(f.bytes, {}));
    // Compact packets give a packet's splats in spatial order: compare packet maxima.
    const std::uint32_t perPacket = index.header.recordsPerPacket() / words;
    std::uint32_t previous = 0xffffu;
    for (std::size_t first = 0; first < firsts.size(); first += perPacket) {
      std::uint32_t top = 0, bottom = 0xffffu;
      for (std::size_t k = first; k < std::min<std::size_t>(firsts.size(), first + perPacket);
           ++k) {
        top = std::max(top, qnv::magnitudeCode(firsts[k]));
        bottom = std::min(bottom, qnv::magnitudeCode(firsts[k]));
      }
      CHECK(top <= previous);
      previous = bottom;
    }
    if (f.brick.level == 0) rootTopCode = firsts.empty() ? 0 : qnv::magnitudeCode(firsts[0]);
  }
  CHECK(total == files.splats);
  CHECK(std::count(opacities.begin(), opacities.end(), 0.0f) == 0);
  // The root holds each leaf's most important splats: the scene's largest A code too.
  std::uint32_t top = 0;
  for (const qnv::BrickFile& f : files.bricks)
    for (std::size_t band = qnv::kTilesetBands; band-- > 0;)
      if (f.brick.histogram[band] > 0) {
        top = std::max<std::uint32_t>(top, static_cast<std::uint32_t>(band));
        break;
      }
  CHECK(qnv::tilesetBand(static_cast<std::uint32_t>(rootTopCode)) == top);
}

TEST_CASE("a Gaussian tileset's merged bricks keep their region's place and coverage",
          "[splats][tileset][merged]") {
  const splats::GaussianCloud cloud = randomGaussians();
  const splats::GaussianTilesetFiles files = splats::buildGaussianTileset(cloud, gaussianCut());
  // Interior levels 0 and 1 of depth 2 have merged bricks: the root and its 8 children.
  REQUIRE(files.merged.size() == 9);
  CHECK(files.index.mergedCellsLog2 == 2);
  // Summed coverage and coverage-weighted centre.
  const auto moments = [](const splats::GaussianCloud& c, double& coverage, glm::dvec3& centre) {
    coverage = 0.0;
    centre = glm::dvec3(0.0);
    for (std::size_t i = 0; i < c.size(); ++i) {
      const double w = splats::splatCoverage(c.scales[i], c.opacities[i]);
      coverage += w;
      centre += w * glm::dvec3(c.positions[i]);
    }
    centre /= coverage;
  };
  double sourceCoverage = 0.0, coverage = 0.0;
  glm::dvec3 sourceCentre, centre;
  moments(cloud, sourceCoverage, sourceCentre);
  const auto& [node, bytes] = files.merged.front();
  CHECK(node.level == 0);
  const splats::GaussianCloud root = splats::readQnvGaussians(bytes, "merged root");
  CHECK(root.size() > 0);
  CHECK(root.size() <= 64);  // 4^3 cells at most
  moments(root, coverage, centre);
  // Quantized to 8-bit opacities and log scales: within a few per cent.
  CHECK(coverage == Approx(sourceCoverage).epsilon(0.1));
  CHECK(glm::length(centre - sourceCentre) < 0.05);
}

TEST_CASE("a Gaussian tileset has merged bricks at every interior level, summed node by node",
          "[splats][tileset][merged]") {
  const splats::GaussianCloud cloud = randomGaussians();
  qnv::TilesetOptions cut = gaussianCut();
  cut.brickVectors = 8;     // 3,960 splats: depth 3
  cut.mergedCellsLog2 = 5;  // 32^3 cells a node: qnv::deepestMergedLevel is 1
  const splats::GaussianTilesetFiles files = splats::buildGaussianTileset(cloud, cut);
  const qnv::TilesetIndex& index = files.index;
  REQUIRE(index.depth == 3);
  CHECK(index.mergedEveryLevel);
  std::size_t interior = 0;
  for (const qnv::TilesetBrick& b : index.bricks) interior += b.level < 3 ? 1 : 0;
  REQUIRE(files.merged.size() == interior);
  // Every node's merged brick is the merge of all the splats of its region: the same as
  // one builder of levels 0 to 2 fed the whole scene in scene order gives (the fixed-point
  // sums do not depend on the order; the SH sums, doubles, to rounding).
  const splats::GaussianFrame frame = splats::gaussianFrame(cloud);
  const qnv::TilesetLayout layout =
      splats::gaussianLayoutForSplats(frame.header, frame.kept.size(), cut);
  splats::MergedLevelBuilder whole(layout, 5, 0, 2);
  for (const std::uint32_t i : frame.kept) whole.addGaussian(cloud, i);
  const auto expected = whole.build();
  std::size_t deep = 0;
  for (const auto& [node, bytes] : files.merged) {
    INFO("node " << int(node.level) << " " << node.cell.x << " " << node.cell.y << " "
                 << node.cell.z);
    const splats::GaussianCloud merged = splats::readQnvGaussians(bytes, "merged");
    const auto it = expected.find(node);
    REQUIRE(it != expected.end());
    CHECK(merged.size() == it->second.size());
    const splats::GaussianCloud exact =
        splats::readQnvGaussians(splats::encodeMergedBrick(it->second), "expected");
    REQUIRE(exact.size() == merged.size());
    for (std::size_t i = 0; i < merged.size(); ++i) {
      CHECK(merged.positions[i] == exact.positions[i]);
      CHECK(merged.opacities[i] == exact.opacities[i]);
    }
    deep += node.level == 2 ? 1 : 0;
  }
  CHECK(deep > 8);  // level 2's nodes, below deepestMergedLevel(5)
  // Leaves out of Morton order are refused; what is held is one node a level.
  splats::GaussianMergedLevels levels(layout, 5,
                                      [](const qnv::TilesetCell&, splats::GaussianCloud&&) {});
  const std::uint32_t first[] = {frame.kept[0]};
  levels.addLeaf(glm::uvec3(1, 1, 0), cloud, first);
  CHECK_THROWS_AS(levels.addLeaf(glm::uvec3(0, 1, 0), cloud, first), std::logic_error);
  CHECK(levels.peakCells() == 3);  // the splat's cell at levels 0, 1 and 2
  // Morton codes: bit 3 i of x, 3 i + 1 of y, 3 i + 2 of z, and back.
  std::mt19937 random(11);
  for (int n = 0; n < 1000; ++n) {
    const glm::uvec3 cell(random() & 0x1fffffu, random() & 0x1fffffu, random() & 0x1fffffu);
    std::uint64_t naive = 0;
    for (unsigned bit = 0; bit < 21; ++bit)
      for (int a = 0; a < 3; ++a)
        naive |= std::uint64_t{(cell[a] >> bit) & 1u} << (3 * bit + static_cast<unsigned>(a));
    CHECK(splats::mortonOfCell(cell) == naive);
    CHECK(splats::cellOfMorton(naive) == cell);
  }
}

TEST_CASE("a Gaussian tileset of nothing, or with bricks of 0 splats, is refused",
          "[splats][tileset]") {
  splats::GaussianCloud empty;
  CHECK_THROWS_AS(splats::buildGaussianTileset(empty, gaussianCut()), qnv::InputError);
  qnv::TilesetOptions zero = gaussianCut();
  zero.brickVectors = 0;
  CHECK_THROWS_AS(splats::buildGaussianTileset(randomGaussians(), zero), qnv::InputError);
}

TEST_CASE("a Gaussian tileset's merged cells, not given, are 32 only where they are few",
          "[splats][tileset][merged]") {
  // 3,960 splats spread over a 2 x 1 x 1 box: the root's 32^3 grid has nearly one cell per
  // splat, so 16^3 stays.
  splats::GaussianCloud cloud = randomGaussians();
  CHECK(splats::defaultGaussianMergedCellsLog2(cloud) == 4);
  // The same splats moved onto 128 points of the box (eight along x, four along y and z):
  // at most 128 cells of 32^3 hold them, one per 31 splats: 32^3.
  for (glm::vec3& p : cloud.positions) p = glm::floor(p * 4.0f) / 4.0f;
  CHECK(splats::defaultGaussianMergedCellsLog2(cloud) == 5);
  // No splat kept: the default.
  CHECK(splats::defaultGaussianMergedCellsLog2(splats::GaussianCloud{}) == 4);
}

TEST_CASE("a Gaussian tileset's K, not given, makes a mid-sized scene's octree 2 deep",
          "[splats][tileset][merged]") {
  // 16,384 splats or fewer, and more than 131,072: the default K.
  CHECK(splats::defaultGaussianBrickVectors(0) == 16384);
  CHECK(splats::defaultGaussianBrickVectors(3000) == 16384);
  CHECK(splats::defaultGaussianBrickVectors(16384) == 16384);
  CHECK(splats::defaultGaussianBrickVectors(131073) == 16384);
  CHECK(splats::defaultGaussianBrickVectors(6000000) == 16384);
  // Between: the largest power of two K with 8 K < splats, so 8 K < splats <= 64 K.
  CHECK(splats::defaultGaussianBrickVectors(16385) == 2048);
  CHECK(splats::defaultGaussianBrickVectors(122000) == 8192);  // CThead's capture
  CHECK(splats::defaultGaussianBrickVectors(131072) == 8192);
  for (std::uint64_t kept : {16385u, 40000u, 65536u, 65537u, 100000u, 131072u}) {
    INFO(kept);
    const std::uint64_t k = splats::defaultGaussianBrickVectors(kept);
    CHECK(8 * k < kept);
    CHECK(kept <= 64 * k);
  }
}

TEST_CASE(
    "a Gaussian tileset's bricks and merged bricks are the same bytes on any number of threads",
    "[splats][tileset]") {
  const splats::GaussianCloud cloud = randomGaussians();
  const splats::GaussianTilesetFiles one = splats::buildGaussianTileset(cloud, gaussianCut());
  REQUIRE(one.bricks.size() > 8);  // a tree with interior and leaf bricks
  for (const unsigned threads : {2u, 5u}) {
    INFO(threads);
    const splats::GaussianTilesetFiles many =
        splats::buildGaussianTileset(cloud, gaussianCut(), {}, 0, 1, threads);
    REQUIRE(many.bricks.size() == one.bricks.size());
    for (std::size_t i = 0; i < one.bricks.size(); ++i) {
      CHECK(many.bricks[i].bytes == one.bricks[i].bytes);
      CHECK(many.bricks[i].brick.path() == one.bricks[i].brick.path());
    }
    CHECK(qnv::serializeTilesetIndex(many.index) == qnv::serializeTilesetIndex(one.index));
    // The merged levels, summed on a thread of their own beside the bricks': the same.
    REQUIRE(many.merged.size() == one.merged.size());
    CHECK(many.merged == one.merged);
  }
}
