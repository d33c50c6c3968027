// The slab gradient step (qnv/volume_slabs.hpp): the vectors of forEachVolumeVector are
// those encodeVolume computes (same gradients, positions, magnitudes and colours), for
// every slab thickness and thread count, over CThead-like small volumes.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "qnv/record.hpp"
#include "qnv/volume_slabs.hpp"

using namespace gs::qnv;
using Catch::Matchers::Contains;

namespace {

// A CT-like head: air (0) around a soft-tissue ellipsoid (~1000) inside a bone shell
// (~2000), with integer noise, as int16 samples; anisotropic spacing like CThead's.
Volume headLike(glm::uvec3 d, unsigned seed) {
  Volume v;
  v.dims = d;
  v.spacing = {1.0f, 1.0f, 2.0f};
  v.origin = {-3.0f, 0.5f, 10.0f};
  v.sourceType = ScalarType::int16;
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> noise(-20, 20);
  const glm::vec3 c = glm::vec3(d) * 0.5f;
  for (std::uint32_t z = 0; z < d.z; ++z)
    for (std::uint32_t y = 0; y < d.y; ++y)
      for (std::uint32_t x = 0; x < d.x; ++x) {
        glm::vec3 p = (glm::vec3(x, y, z) - c) / (c * 0.9f);
        if (d.z <= 2) p.z = 0.0f;  // thin volumes: a cylinder through every slice
        const float r = std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z);
        float value = r < 0.8f ? 1000.0f : r < 1.0f ? 2000.0f : 0.0f;
        if (value > 0.0f) value += static_cast<float>(noise(rng));
        v.samples.push_back(value);
      }
  return v;
}

// The vectors of forEachVolumeVector over the whole volume, checking the callback's
// order contract on the way.
std::vector<VolumeVector> slabVectors(const Volume& volume, VolumeVectorOptions options,
                                      VolumeVectorSummary* summary = nullptr) {
  MemoryVolumeSlabs reader(volume);
  std::vector<VolumeVector> all;
  const VolumeVectorSummary s =
      forEachVolumeVector(reader, 0, volume.dims.z, options, [&](std::span<const VolumeVector> v) {
        REQUIRE(!v.empty());
        if (!all.empty()) REQUIRE(v.front().index > all.back().index);
        all.insert(all.end(), v.begin(), v.end());
      });
  if (summary) *summary = s;
  return all;
}

// The records encodeVolume would make of `vectors`, given its header, sorted as numbers.
std::vector<std::uint64_t> quantized(const std::vector<VolumeVector>& vectors,
                                     const StreamHeader& h) {
  const MagnitudeQuantizer quantizeA(h.mapping, h.magnitudeMin, h.magnitudeMax);
  std::vector<std::uint64_t> records;
  for (const VolumeVector& v : vectors) {
    RecordFields f;
    f.x = quantizeCoordinate(v.position.x, h.boundsMin.x, h.boundsMax.x);
    f.y = quantizeCoordinate(v.position.y, h.boundsMin.y, h.boundsMax.y);
    f.z = quantizeCoordinate(v.position.z, h.boundsMin.z, h.boundsMax.z);
    quantizeDirection(v.gradient, f.theta, f.phi);
    f.a = quantizeA(v.magnitude);
    f.c = v.color;
    records.push_back(packRecord(f));
  }
  std::sort(records.begin(), records.end());
  return records;
}

bool sameVectors(const std::vector<VolumeVector>& a, const std::vector<VolumeVector>& b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (a[i].index != b[i].index || a[i].gradient != b[i].gradient ||
        a[i].magnitude != b[i].magnitude || a[i].position != b[i].position ||
        a[i].value != b[i].value || a[i].color != b[i].color)
      return false;
  return true;
}

}  // namespace

TEST_CASE("slab gradients equal encodeVolume's for every slab thickness", "[qnv][volume][slabs]") {
  for (const glm::uvec3 d : {glm::uvec3(23, 19, 17), glm::uvec3(16, 12, 2), glm::uvec3(9, 7, 1)}) {
    INFO("dims " << d.x << " " << d.y << " " << d.z);
    const Volume volume = headLike(d, d.x * 7 + d.z);
    VolumeEncodeOptions encodeOptions;
    const EncodedVectors encoded = encodeVolume(volume, encodeOptions);
    std::vector<std::uint64_t> expected = encoded.records;
    std::sort(expected.begin(), expected.end());

    VolumeVectorOptions options;
    options.slabSlices = d.z;
    options.threads = 1;
    VolumeVectorSummary summary;
    const std::vector<VolumeVector> reference = slabVectors(volume, options, &summary);
    REQUIRE(reference.size() == encoded.records.size());
    REQUIRE(!reference.empty());
    CHECK(summary.vectors == reference.size());
    CHECK(summary.voxels == volume.voxelCount());
    // The colour domain is the volume's range, as encodeVolume's.
    CHECK(summary.colorDomain.first == encoded.header.valueMin);
    CHECK(summary.colorDomain.second == encoded.header.valueMax);
    // Bit-identical magnitudes: the extremes are encodeVolume's header range.
    float lo = reference.front().magnitude, hi = lo;
    for (const VolumeVector& v : reference)
      lo = std::min(lo, v.magnitude), hi = std::max(hi, v.magnitude);
    CHECK(lo == encoded.header.magnitudeMin);
    CHECK(hi == encoded.header.magnitudeMax);
    CHECK(quantized(reference, encoded.header) == expected);

    for (std::uint32_t thickness : {1u, 2u, 3u, 5u, 16u, 100u})
      for (unsigned threads : {1u, 3u, 8u}) {
        INFO("thickness " << thickness << ", threads " << threads);
        options.slabSlices = thickness;
        options.threads = threads;
        CHECK(sameVectors(slabVectors(volume, options), reference));
      }
  }
}

TEST_CASE("slab gradients: the definition at one voxel, the window, ranges",
          "[qnv][volume][slabs]") {
  const Volume volume = headLike({12, 10, 8}, 3);
  // Interior voxel (5, 4, 3): central differences over twice the spacing.
  VolumeVectorOptions options;
  options.slabSlices = 2;
  options.threads = 2;
  const std::vector<VolumeVector> all = slabVectors(volume, options);
  auto at = [&](std::uint32_t x, std::uint32_t y, std::uint32_t z) {
    const std::uint64_t index = x + 12ull * (y + 10ull * z);
    const auto it = std::find_if(all.begin(), all.end(),
                                 [&](const VolumeVector& v) { return v.index == index; });
    REQUIRE(it != all.end());
    return *it;
  };
  const VolumeVector v = at(5, 1, 3);
  const glm::vec3 want((volume.at(6, 1, 3) - volume.at(4, 1, 3)) / 2.0f,
                       (volume.at(5, 2, 3) - volume.at(5, 0, 3)) / 2.0f,
                       (volume.at(5, 1, 4) - volume.at(5, 1, 2)) / 4.0f);
  CHECK(v.gradient == want);
  CHECK(v.position == volume.origin + glm::vec3(5, 1, 3) * volume.spacing);
  CHECK(v.value == volume.at(5, 1, 3));
  // Border voxel z = 7 (the last slice): one-sided, over one spacing.
  const VolumeVector b = at(6, 5, 7);
  CHECK(b.gradient.z == (volume.at(6, 5, 7) - volume.at(6, 5, 6)) / 2.0f);

  // A value window, as encodeVolume's.
  VolumeEncodeOptions encodeOptions;
  encodeOptions.valueWindow = std::pair{500.0f, 1500.0f};
  const EncodedVectors encoded = encodeVolume(volume, encodeOptions);
  options.valueWindow = encodeOptions.valueWindow;
  const std::vector<VolumeVector> windowed = slabVectors(volume, options);
  REQUIRE(windowed.size() == encoded.records.size());
  std::vector<std::uint64_t> expected = encoded.records;
  std::sort(expected.begin(), expected.end());
  CHECK(quantized(windowed, encoded.header) == expected);
  for (const VolumeVector& w : windowed) REQUIRE((w.value >= 500.0f && w.value <= 1500.0f));

  // A sub-range of slices gives exactly the vectors of those slices.
  MemoryVolumeSlabs reader(volume);
  std::vector<VolumeVector> part;
  options.valueWindow.reset();
  options.valueRange = volumeValueRange(reader, 3);
  forEachVolumeVector(reader, 2, 5, options, [&](std::span<const VolumeVector> s) {
    part.insert(part.end(), s.begin(), s.end());
  });
  std::vector<VolumeVector> expectedPart;
  for (const VolumeVector& w : all)
    if (w.index >= 2 * 120 && w.index < 5 * 120) expectedPart.push_back(w);
  CHECK(sameVectors(part, expectedPart));

  CHECK_THROWS_WITH(forEachVolumeVector(reader, 3, 3, options, [](auto) {}),
                    Contains("z0 < z1 <= 8"));
  options.valueWindow = std::pair{2.0f, 1.0f};
  CHECK_THROWS_WITH(forEachVolumeVector(reader, 0, 8, options, [](auto) {}),
                    Contains("value window is empty"));
}

TEST_CASE("slab thickness from a memory bound", "[qnv][volume][slabs]") {
  VolumeGridInfo info;
  info.dims = {2048, 2048, 2048};
  const std::uint64_t slice = 2048ull * 2048;
  const std::uint32_t slab = slabSlicesForMemory(info, std::uint64_t{2} << 30);
  CHECK(slab >= 1);
  const std::uint64_t used = 2 * slice * 4 + slab * slice * (12 + sizeof(VolumeVector));
  CHECK(used <= (std::uint64_t{2} << 30));
  CHECK(used + slice * (12 + sizeof(VolumeVector)) > (std::uint64_t{2} << 30));
  CHECK(slabSlicesForMemory(info, 1) == 1);
  info.dims = {4, 4, 3};
  CHECK(slabSlicesForMemory(info, std::uint64_t{1} << 30) == 3);
}

namespace {

// Fails when asked for slice `bad` (a short read in the middle of the data).
class FailingSlabs final : public VolumeSlabReader {
 public:
  FailingSlabs(const Volume& v, std::uint32_t bad) : inner_(v), bad_(bad) {}
  const VolumeGridInfo& info() const override { return inner_.info(); }
  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    if (z0 <= bad_ && bad_ < z1) throw InputError("failing.raw: short read at byte offset 42");
    inner_.readSlices(z0, z1, out);
  }

 private:
  MemoryVolumeSlabs inner_;
  std::uint32_t bad_;
};

}  // namespace

TEST_CASE("slab gradients: a read error of a slab read ahead reaches the caller",
          "[qnv][volume][slabs]") {
  const Volume volume = headLike({12, 10, 16}, 5);
  for (std::uint32_t bad : {0u, 7u, 15u})
    for (std::uint32_t thickness : {1u, 3u}) {
      FailingSlabs reader(volume, bad);
      VolumeVectorOptions options;
      options.valueRange = std::pair{0.0f, 2100.0f};
      options.slabSlices = thickness;
      options.threads = 2;
      std::uint64_t handed = 0;
      CHECK_THROWS_WITH(
          forEachVolumeVector(reader, 0, 16, options,
                              [&](std::span<const VolumeVector> v) { handed += v.size(); }),
          Contains("byte offset 42"));
    }
}
