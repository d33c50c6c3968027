// The selection passes of the out-of-core tileset encode (qnv/volume_tileset.hpp): the
// plan's header and the vectors its filter keeps are selectVolumeVectors's exactly, for
// every selection (all, a fraction with ties at the threshold, a count, none, a window),
// every slab thickness, and a filter starting at any slice (one share of a split run).
#include <catch2/catch.hpp>

#include <algorithm>
#include <random>
#include <set>

#include "qnv/encoder.hpp"
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
