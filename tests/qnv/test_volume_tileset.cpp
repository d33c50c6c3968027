// The selection passes of the out-of-core tileset encode (qnv/volume_tileset.hpp): the
// plan's header and the vectors its filter keeps are selectVolumeVectors's exactly, for
// every selection (all, a fraction with ties at the threshold, a count, none, a window),
// every slab thickness, and a filter starting at any slice (one share of a split run).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <set>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"
#include "qnv/volume_tileset.hpp"

using namespace gs::qnv;

namespace {

// Small integer samples: many gradient magnitudes tie exactly.
Volume blocky(glm::uvec3 d, unsigned seed) {
  Volume v;
  v.dims = d;
  v.spacing = {1.0f, 0.5f, 2.0f};
  v.origin = {1.0f, -2.0f, 0.25f};
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> value(0, 3);
  for (std::size_t i = 0; i < std::size_t{d.x} * d.y * d.z; ++i)
    v.samples.push_back(static_cast<float>(value(rng)));
  return v;
}

std::string headerBytes(StreamHeader h) {
  return serializeHeader(h);
}

}  // namespace

TEST_CASE("out-of-core selection keeps selectVolumeVectors's vectors", "[qnv][volume][ooc]") {
  const Volume volume = blocky({9, 7, 11}, 3);
  struct Case {
    Selection selection;
    std::optional<std::pair<float, float>> window;
  };
  std::vector<Case> cases;
  for (double f : {1.0, 0.5, 0.13, 0.001}) cases.push_back({{f, 0}, std::nullopt});
  cases.push_back({{1.0, 100}, std::nullopt});
  cases.push_back({{1.0, 0}, std::make_pair(1.0f, 2.0f)});
  cases.push_back({{0.2, 0}, std::make_pair(1.0f, 2.0f)});
  cases.push_back({{1e-9, 0}, std::nullopt});  // keeps none
  for (const Case& c : cases) {
    VolumeEncodeOptions options;
    options.selection = c.selection;
    options.valueWindow = c.window;
    EncodeSummary summary;
    const SelectedVectors expected = selectVolumeVectors(volume, options, &summary);
    std::set<std::uint64_t> expectedSources;
    for (const SourceVector& v : expected.vectors) expectedSources.insert(v.source);
    for (std::uint32_t slab : {1u, 4u, 11u}) {
      for (std::uint32_t start : {0u, 3u, 10u}) {
        INFO("fraction " << c.selection.fraction << " count " << c.selection.count << " slab "
                         << slab << " start " << start);
        MemoryVolumeSlabs reader(volume);
        VolumeVectorOptions step;
        step.slabSlices = slab;
        step.threads = 2;
        const VolumeSelectionPlan plan = planVolumeSelection(reader, options, step, start);
        CHECK(headerBytes(plan.header) == headerBytes(expected.header));
        CHECK(plan.summary.candidates == summary.candidates);
        CHECK(plan.summary.kept == summary.kept);
        CHECK(plan.passes == (summary.kept > 0 && summary.kept < summary.candidates ? 2u : 1u));
        // The filter from `start` keeps exactly the expected vectors of those slices.
        VolumeKeepFilter filter(plan);
        VolumeVectorOptions pass = step;
        pass.valueWindow = c.window;
        if (!c.window) pass.valueRange = plan.colorDomain;
        std::set<std::uint64_t> kept;
        forEachVolumeVector(reader, start, volume.dims.z, pass, [&](auto vectors) {
          for (const VolumeVector& v : vectors)
            if (filter.keep(v)) {
              kept.insert(v.index);
              const auto same =
                  std::find_if(expected.vectors.begin(), expected.vectors.end(),
                               [&](const SourceVector& e) { return e.source == v.index; });
              REQUIRE(same != expected.vectors.end());
              const SourceVector s = toSourceVector(v);
              CHECK(s.position == same->position);
              CHECK(s.normal == same->normal);
              CHECK(s.magnitude == same->magnitude);
              CHECK(s.color == same->color);
            }
        });
        std::set<std::uint64_t> want;
        const std::uint64_t from = std::uint64_t{start} * volume.dims.x * volume.dims.y;
        for (std::uint64_t s : expectedSources)
          if (s >= from) want.insert(s);
        CHECK(kept == want);
      }
    }
  }
}

TEST_CASE("interior parts scanned piece by piece equal the parsed ones", "[qnv][tileset][ooc]") {
  InteriorParts parts;
  parts[TilesetCell{0, {0, 0, 0}}] = {{2.5f, 7, 0x1234}, {1.0f, 3, 99}};
  parts[TilesetCell{1, {1, 0, 1}}] = {{0.25f, 11, 5}};
  TilesetOptions cut;
  cut.brickVoxels = 5;
  cut.brickVectors = 77;
  const std::string bytes = serializeInteriorParts(parts, cut);
  const PartReader read = [&](std::uint64_t offset, std::size_t n, char* out) {
    REQUIRE(offset + n <= bytes.size());
    std::copy_n(bytes.data() + offset, n, out);
  };
  std::string error;
  TilesetOptions scanned;
  const auto spans = scanInteriorParts(bytes.size(), read, "p", scanned, error);
  REQUIRE(spans);
  CHECK(scanned.brickVoxels == 5);
  CHECK(scanned.brickVectors == 77);
  REQUIRE(spans->size() == 2);
  std::size_t i = 0;
  for (const auto& [node, entries] : parts) {
    const InteriorPartSpan& span = (*spans)[i++];
    CHECK(span.node == node);
    const std::vector<InteriorEntry> loaded = loadInteriorEntries(span, read);
    REQUIRE(loaded.size() == entries.size());
    for (std::size_t k = 0; k < loaded.size(); ++k) {
      CHECK(loaded[k].magnitude == entries[k].magnitude);
      CHECK(loaded[k].source == entries[k].source);
      CHECK(loaded[k].record == entries[k].record);
    }
  }
  // Every damage parseInteriorParts refuses, scanInteriorParts refuses with its sentence.
  for (std::size_t cutAt : {bytes.size() - 1, std::size_t{30}, std::size_t{27}}) {
    const std::string part = bytes.substr(0, cutAt);
    const PartReader readPart = [&](std::uint64_t offset, std::size_t n, char* out) {
      REQUIRE(offset + n <= part.size());
      std::copy_n(part.data() + offset, n, out);
    };
    std::string parseError, scanError;
    TilesetOptions c1, c2;
    CHECK_FALSE(parseInteriorParts(part, "p", c1, parseError));
    CHECK_FALSE(scanInteriorParts(part.size(), readPart, "p", c2, scanError));
    CHECK(scanError.rfind("p: ", 0) == 0);
  }
  std::string flipped = bytes;
  flipped[40] ^= 1;
  const PartReader readFlipped = [&](std::uint64_t offset, std::size_t n, char* out) {
    std::copy_n(flipped.data() + offset, n, out);
  };
  TilesetOptions c3;
  CHECK_FALSE(scanInteriorParts(flipped.size(), readFlipped, "p", c3, error));
  CHECK(error == "p: damaged or truncated (CRC mismatch)");
}
