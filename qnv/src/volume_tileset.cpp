#include "qnv/volume_tileset.hpp"

#include "histogram_crossing.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "qnv/error.hpp"

namespace gs::qnv {

namespace {

constexpr std::size_t kBins = std::size_t{1} << 16;

// Passes the slices through and measures their finite value range on the way.
class RangeMeasuringReader final : public VolumeSlabReader {
 public:
  explicit RangeMeasuringReader(VolumeSlabReader& inner) : inner_(inner) {}
  const VolumeGridInfo& info() const override { return inner_.info(); }
  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override {
    inner_.readSlices(z0, z1, out);
    for (float v : out)
      if (std::isfinite(v)) lo_ = std::min(lo_, v), hi_ = std::max(hi_, v);
  }
  std::pair<float, float> range() const {
    return lo_ > hi_ ? std::make_pair(0.0f, 0.0f) : std::make_pair(lo_, hi_);
  }

 private:
  VolumeSlabReader& inner_;
  float lo_ = std::numeric_limits<float>::max();
  float hi_ = std::numeric_limits<float>::lowest();
};

}  // namespace

VolumeSelectionPlan planVolumeSelection(VolumeSlabReader& reader,
                                        const VolumeEncodeOptions& options,
                                        const VolumeVectorOptions& step, std::uint32_t startSlice) {
  const VolumeGridInfo info = reader.info();
  const glm::uvec3 d = info.dims;
  if (d.x == 0 || d.y == 0 || d.z == 0) throw InputError("volume has no voxels");
  VolumeVectorOptions pass = step;
  pass.valueRange.reset();
  pass.valueWindow = options.valueWindow;
  if (!pass.valueWindow)  // every finite value, as selectVolumeVectors's [min, max]
    pass.valueRange =
        std::make_pair(std::numeric_limits<float>::lowest(), std::numeric_limits<float>::max());
  if (options.valueWindow && !(options.valueWindow->first <= options.valueWindow->second))
    throw InputError("value window is empty");

  // Pass 1: candidates, extremes, value range, histogram of the upper 16 bits.
  RangeMeasuringReader measured(reader);
  std::vector<std::uint64_t> coarse(kBins, 0);
  std::uint64_t candidates = 0;
  float aMin = std::numeric_limits<float>::max(), aMax = 0.0f;
  forEachVolumeVector(measured, 0, d.z, pass, [&](std::span<const VolumeVector> vectors) {
    candidates += vectors.size();
    for (const VolumeVector& v : vectors) {
      ++coarse[std::bit_cast<std::uint32_t>(v.magnitude) >> 16];
      aMin = std::min(aMin, v.magnitude);
      aMax = std::max(aMax, v.magnitude);
    }
  });

  VolumeSelectionPlan plan;
  plan.startSlice = std::min(startSlice, d.z);
  plan.colorDomain = options.valueWindow ? *options.valueWindow : measured.range();
  const std::uint64_t voxels = info.voxelCount();
  const std::uint64_t kept = std::min(options.selection.keepOf(voxels), candidates);
  plan.summary = {voxels, candidates, kept};
  if (kept == 0 && candidates > 0) {  // keep none
    plan.keepAll = false;
    plan.threshold = std::numeric_limits<float>::infinity();
  } else if (kept < candidates) {
    // Pass 2: the lower 16 bits inside the crossing bin, in all and before startSlice.
    plan.keepAll = false;
    plan.passes = 2;
    const std::pair<std::size_t, std::uint64_t> coarseCut =
        detail::histogramCrossing(coarse, kept, "magnitude histogram holds fewer vectors");
    const std::size_t bin = coarseCut.first;
    const std::uint64_t above = coarseCut.second;
    std::vector<std::uint64_t> fine(kBins, 0), fineBefore(kBins, 0);
    const std::uint64_t startIndex = info.sliceVoxels() * plan.startSlice;
    forEachVolumeVector(reader, 0, d.z, pass, [&](std::span<const VolumeVector> vectors) {
      for (const VolumeVector& v : vectors) {
        const std::uint32_t bits = std::bit_cast<std::uint32_t>(v.magnitude);
        if ((bits >> 16) != bin) continue;
        ++fine[bits & 0xffffu];
        if (v.index < startIndex) ++fineBefore[bits & 0xffffu];
      }
    });
    const auto [low, aboveFine] =
        detail::histogramCrossing(fine, kept - above, "magnitude histogram holds fewer vectors");
    plan.threshold = std::bit_cast<float>(static_cast<std::uint32_t>((bin << 16) | low));
    plan.tiesKept = kept - above - aboveFine;
    plan.tiesBefore = fineBefore[low];
    aMin = plan.threshold;  // the smallest kept magnitude: at least one tie is kept
  }

  StreamHeader& h = plan.header;
  h.kind = StreamKind::volume;
  h.mapping = options.mapping;
  h.profile = options.profile;
  h.voxelSpacing = info.spacing;
  h.volumeDims = d;
  h.boundsMin = info.origin;
  h.boundsMax = info.origin + glm::vec3(d - glm::uvec3(1)) * info.spacing;
  h.valueMin = plan.colorDomain.first;
  h.valueMax = plan.colorDomain.second;
  h.palette = options.palette ? *options.palette : defaultTransferFunction();
  if (kept == 0) aMin = aMax = 1.0f;
  h.magnitudeMin = aMin;
  h.magnitudeMax = aMax;
  h.vectorCount = kept;
  return plan;
}

}  // namespace gs::qnv
