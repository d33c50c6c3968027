#include <catch2/catch.hpp>

#include <algorithm>
#include <set>

#include "session/tileset_selection.hpp"
#include "tileset_fixture.hpp"

using namespace gs;
using session::BrickChoice;

namespace {

session::TilesetView wholeView() {
  session::TilesetView v;
  v.position = {0.5f, 0.5f, 3.0f};
  v.verticalFov = 0.785398f;
  v.heightPixels = 512;
  return v;
}

// Looks straight down -Z at the corner cell x, y in [0, 0.25] of the unit cube.
session::TilesetView cornerView() {
  session::TilesetView v;
  v.position = {0.125f, 0.125f, 1.15f};
  v.verticalFov = 0.174533f;  // 10 degrees
  v.heightPixels = 512;
  return v;
}

bool ancestorsFirst(const qnv::TilesetIndex& index, const std::vector<BrickChoice>& choices) {
  std::set<std::tuple<int, std::uint32_t, std::uint32_t, std::uint32_t>> taken;
  for (const BrickChoice& c : choices) {
    const auto& b = index.bricks[c.brick];
    if (b.level > 0 && !taken.count({b.level - 1, b.x / 2, b.y / 2, b.z / 2})) return false;
    taken.insert({b.level, b.x, b.y, b.z});
  }
  return true;
}

}  // namespace

TEST_CASE("tileset selection: the whole view refines every brick of a close tileset",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  const auto choices = session::selectBricks(index, wholeView(), {});
  REQUIRE(choices.size() == index.bricks.size());  // 1 + 8 + 64
  CHECK(index.bricks[choices.front().brick].level == 0);
  CHECK(ancestorsFirst(index, choices));
  for (const BrickChoice& c : choices) {
    CHECK(c.records == 4096);
    CHECK(c.bytes == index.bricks[c.brick].fileBytes);
  }
}

TEST_CASE("tileset selection: a zoom into one corner picks that corner's deep bricks only",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  const auto whole = session::selectBricks(index, wholeView(), {});
  const auto zoom = session::selectBricks(index, cornerView(), {});
  REQUIRE(!zoom.empty());
  CHECK(ancestorsFirst(index, zoom));
  int deep = 0;
  for (const BrickChoice& c : zoom) {
    const auto& b = index.bricks[c.brick];
    CHECK(b.x == 0);
    CHECK(b.y == 0);
    deep += b.level == 2;
  }
  CHECK(deep == 4);         // the column of leaf cells under the corner, every depth
  CHECK(zoom.size() == 7);  // root, 2 level-1 cells, 4 leaves
  CHECK(session::totalBytes(zoom) * 8 < session::totalBytes(whole));
}

TEST_CASE("tileset selection: a far view takes a whole-packet prefix of the root",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  auto v = wholeView();
  v.position.z = 60.0f;  // the cube spans about 21 pixels: ~450 pixels of area
  const auto choices = session::selectBricks(index, v, {});
  REQUIRE(choices.size() == 1);
  CHECK(index.bricks[choices[0].brick].level == 0);
  const std::uint64_t per = index.header.recordsPerPacket();
  CHECK(choices[0].records < 4096);
  CHECK(choices[0].records % per == 0);
  CHECK(choices[0].bytes ==
        qnv::brickPrefixBytes(index.bricks[choices[0].brick], index.header, choices[0].records));
  CHECK(choices[0].bytes < index.bricks[choices[0].brick].fileBytes);
}

TEST_CASE("tileset selection: the vector budget and the memory budget cap the records",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  const std::uint64_t per = index.header.recordsPerPacket();
  for (const bool memory : {false, true}) {
    session::TilesetBudget budget;
    (memory ? budget.memoryVectors : budget.vectors) = 10000;
    const auto choices = session::selectBricks(index, wholeView(), budget);
    std::uint64_t records = 0;
    for (const BrickChoice& c : choices) records += c.records;
    CHECK(records >= 9000);
    CHECK(records < 10000 + per);
    // An even density: a prefix of the root and of every level-1 brick, no leaves (a walk
    // that stopped at the budget would take the root, one level-1 brick and a part).
    CHECK(choices.size() == 9);
    for (const BrickChoice& c : choices) CHECK(index.bricks[c.brick].level <= 1);
    CHECK(ancestorsFirst(index, choices));
  }
}

TEST_CASE("tileset selection: bricks behind the eye or outside the frustum are culled",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  auto v = wholeView();
  v.forward = {0.0f, 0.0f, 1.0f};  // looking away
  CHECK(session::selectBricks(index, v, {}).empty());
  v = wholeView();
  v.model = glm::mat4(1.0f);
  v.model[3] = glm::vec4(40.0f, 0.0f, 0.0f, 1.0f);  // moved far to the right
  CHECK(session::selectBricks(index, v, {}).empty());
}

TEST_CASE("tileset selection: views merge to the largest prefix per brick, ancestors first",
          "[tileset][selection]") {
  const auto index = test::syntheticTileset(2, 4096);
  auto far = wholeView();
  far.position.z = 60.0f;
  const auto a = session::selectBricks(index, far, {});
  const auto b = session::selectBricks(index, cornerView(), {});
  const auto merged = session::mergeChoices({a, b});
  REQUIRE(merged.size() == b.size());
  CHECK(ancestorsFirst(index, merged));
  for (const BrickChoice& c : merged) CHECK(c.records == 4096);
}

namespace {

/// syntheticTileset as a volume of 1/32-unit voxels whose vectors all lie in the weakest
/// band of magnitudes from `weakest` to 1, quantized by `mapping` (linear from 0.5: the
/// haze of many weak gradients; logarithmic from 1e-15: vectors too faint to see).
qnv::TilesetIndex volumeTileset(float weakest, qnv::MagnitudeMapping mapping) {
  auto index = test::syntheticTileset(2, 4096);
  index.header.kind = qnv::StreamKind::volume;
  index.header.voxelSpacing = glm::vec3(1.0f / 32.0f);
  index.header.mapping = mapping;
  index.header.magnitudeMin = weakest;
  index.header.magnitudeMax = 1.0f;
  for (auto& b : index.bricks) {
    b.histogram = {};
    b.histogram[0] = static_cast<std::uint32_t>(b.vectorCount);
  }
  return index;
}

std::uint64_t chosenRecords(const qnv::TilesetIndex& index, const session::TilesetView& view,
                            double maxLost) {
  session::TilesetBudget budget;
  budget.maxLostOpticalDepth = maxLost;
  std::uint64_t n = 0;
  for (const BrickChoice& c : session::selectBricks(index, view, budget)) n += c.records;
  return n;
}

}  // namespace

TEST_CASE("tileset selection: a far volume keeps the weak vectors that make its haze",
          "[tileset][selection]") {
  const auto hazy = volumeTileset(0.5f, qnv::MagnitudeMapping::linear);  // peaks of 0.7+
  auto far = wholeView();
  far.position.z = 60.0f;  // the cube spans about 21 pixels
  // The screen-space rule alone keeps about one vector per pixel of the root.
  const std::uint64_t screenOnly = chosenRecords(hazy, far, 0.0);
  CHECK(screenOnly < 4096);
  // The opacity-aware rule: dropping any of them would take more than 0.02 of optical
  // depth from the pixels, so every brick is drawn whole, as the single stream draws it.
  CHECK(chosenRecords(hazy, far, 0.02) == hazy.header.vectorCount);
  // Within a vector budget the global magnitude threshold still decides.
  session::TilesetBudget budget;
  budget.vectors = 10000;
  std::uint64_t n = 0;
  for (const BrickChoice& c : session::selectBricks(hazy, far, budget)) n += c.records;
  CHECK(n < 10000 + hazy.header.recordsPerPacket());
}

TEST_CASE("tileset selection: vectors too faint to see are still left to the screen-space rule",
          "[tileset][selection]") {
  // Band 0 spans magnitudes 1e-15 to 3e-15: peaks of 6e-8 at most.
  const auto faint = volumeTileset(1e-15f, qnv::MagnitudeMapping::logarithmic);
  auto far = wholeView();
  far.position.z = 60.0f;
  CHECK(chosenRecords(faint, far, 0.02) == chosenRecords(faint, far, 0.0));
  // Surface tilesets have no haze: the rule does not apply to them.
  const auto surface = test::syntheticTileset(2, 4096);
  CHECK(chosenRecords(surface, far, 0.02) == chosenRecords(surface, far, 0.0));
}

TEST_CASE("tileset selection: far interior nodes are drawn by their merged bricks",
          "[tileset][selection][merged]") {
  // docs/tilesets.md, "Merged levels": a node whose projected size over its cells per axis
  // is at most kMergedPixels is merged, and nothing below it is chosen.
  auto index = test::syntheticTileset(2, 4096);
  CHECK(session::chooseMerged(index, {wholeView()}).merged.empty());  // no merged levels
  index.mergedCellsLog2 = 4;
  session::TilesetView far = wholeView();
  far.position = {0.5f, 0.5f, 300.0f};  // the cube about 3 pixels across
  const session::MergedChoice m = session::chooseMerged(index, {far});
  REQUIRE(m.merged.size() == 1);
  CHECK(index.bricks[m.merged[0]].level == 0);
  REQUIRE(m.skip.size() == index.bricks.size());
  CHECK(std::count(m.skip.begin(), m.skip.end(), 1) == static_cast<long>(index.bricks.size()));
  CHECK(session::selectBricks(index, far, {}, m.skip).empty());
  // Close: every brick is refined, nothing merged.
  const session::MergedChoice close = session::chooseMerged(index, {wholeView()});
  CHECK(close.merged.empty());
  CHECK(close.skip.empty());
}

TEST_CASE("tileset selection: a middle distance merges level-1 nodes under a refined root",
          "[tileset][selection][merged]") {
  auto index = test::syntheticTileset(2, 4096);
  index.mergedCellsLog2 = 4;
  session::TilesetView mid = wholeView();
  // The root's bounding sphere (diameter sqrt 3) about 48 pixels, a level-1 node's 24:
  // root 3 px a cell (refined), level 1 1.5 px a cell (merged).
  mid.position = {0.5f, 0.5f, 0.5f + 0.866f + 1.732f * 512.0f / (2.0f * 0.41421f * 48.0f)};
  const session::MergedChoice m = session::chooseMerged(index, {mid});
  REQUIRE(m.merged.size() == 8);
  for (std::size_t i : m.merged) CHECK(index.bricks[i].level == 1);
  // The root's own vectors lie in its children's regions, all merged: nothing to fetch.
  CHECK(m.skip[0] == 1);
  CHECK(session::selectBricks(index, mid, {}, m.skip).empty());
  // Half the cube out of view (the eye moved along x): the visible children are merged,
  // the others culled, so the root still has nothing to draw.
  session::TilesetView side = mid;
  side.position.x = 0.55f + 0.41421f * side.position.z;  // the left half wholly outside
  const session::MergedChoice s = session::chooseMerged(index, {side});
  CHECK(!s.merged.empty());
  CHECK(s.merged.size() < 8);
  CHECK(session::selectBricks(index, side, {}, s.skip).empty());
  // A second, close view refines every node: then nothing is merged for either.
  const session::MergedChoice both = session::chooseMerged(index, {mid, wholeView()});
  CHECK(both.merged.empty());
}
