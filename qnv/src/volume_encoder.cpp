#include <algorithm>
#include <cmath>
#include <limits>

#include "ordering.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"

namespace gs::qnv {

namespace {

void report(const ProgressCallback& progress, double done) {
  if (progress) progress(done);
}

// Central difference along one axis at index i of n samples `stride` apart, divided by
// the distance between the samples used (one-sided at the border).
float difference(const float* s, std::size_t stride, std::uint32_t i, std::uint32_t n,
                 float spacing) {
  if (n < 2) return 0.0f;
  if (i == 0) return (s[stride] - s[0]) / spacing;
  if (i + 1 == n) return (s[0] - s[-static_cast<std::ptrdiff_t>(stride)]) / spacing;
  return (s[stride] - s[-static_cast<std::ptrdiff_t>(stride)]) / (2.0f * spacing);
}

}  // namespace

SelectedVectors selectVolumeVectors(const Volume& volume, const VolumeEncodeOptions& options,
                                    EncodeSummary* summary) {
  const glm::uvec3 d = volume.dims;
  const std::size_t voxels = volume.voxelCount();
  if (voxels > kMaxVoxels)
    throw InputError("volume of " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                     std::to_string(d.z) + " voxels is more than the limit of " +
                     std::to_string(kMaxVoxels) + " voxels (qnv::kMaxVoxels)");
  if (d.x == 0 || d.y == 0 || d.z == 0 || volume.samples.size() != voxels)
    throw InputError("volume of " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                     std::to_string(d.z) + " voxels holds " +
                     std::to_string(volume.samples.size()) + " samples");
  const glm::vec3 spacing = volume.spacing;
  if (!(spacing.x > 0.0f && spacing.y > 0.0f && spacing.z > 0.0f))
    throw InputError("voxel spacing must be positive");

  float vMin = std::numeric_limits<float>::max(), vMax = std::numeric_limits<float>::lowest();
  for (float v : volume.samples)
    if (std::isfinite(v)) vMin = std::min(vMin, v), vMax = std::max(vMax, v);
  if (vMin > vMax) vMin = vMax = 0.0f;
  float windowLo = vMin, windowHi = vMax;
  if (options.valueWindow) {
    windowLo = options.valueWindow->first;
    windowHi = options.valueWindow->second;
    if (!(windowLo <= windowHi)) throw InputError("value window is empty");
  }

  // Gradient magnitudes of every voxel in the window (section 3.2).
  std::vector<detail::Candidate> candidates;
  candidates.reserve(voxels / 4);
  const std::size_t sliceStride = std::size_t{d.x} * d.y;
  for (std::uint32_t z = 0; z < d.z; ++z) {
    for (std::uint32_t y = 0; y < d.y; ++y) {
      const std::size_t row = std::size_t{d.x} * (y + std::size_t{d.y} * z);
      const float* s = volume.samples.data() + row;
      for (std::uint32_t x = 0; x < d.x; ++x) {
        const float v = s[x];
        if (!(v >= windowLo && v <= windowHi)) continue;
        const float gx = difference(s + x, 1, x, d.x, spacing.x);
        const float gy = difference(s + x, d.x, y, d.y, spacing.y);
        const float gz = difference(s + x, sliceStride, z, d.z, spacing.z);
        const float m = std::sqrt(gx * gx + gy * gy + gz * gz);
        if (m > 0.0f && std::isfinite(m))
          candidates.push_back({m, static_cast<std::uint32_t>(row + x)});
      }
    }
    if (z % 16 == 0) report(options.progress, 0.5 * z / d.z);
  }
  const std::uint64_t candidateCount = candidates.size();
  detail::keepLargest(candidates, options.selection.keepOf(voxels));
  report(options.progress, 0.6);

  SelectedVectors out;
  StreamHeader& h = out.header;
  h.kind = StreamKind::volume;
  h.mapping = options.mapping;
  h.profile = options.profile;
  h.voxelSpacing = spacing;
  h.volumeDims = d;
  h.boundsMin = volume.origin;
  h.boundsMax = volume.origin + glm::vec3(d - glm::uvec3(1)) * spacing;
  h.valueMin = windowLo;
  h.valueMax = windowHi;
  h.palette = options.palette ? *options.palette : defaultTransferFunction();
  float aMin = std::numeric_limits<float>::max(), aMax = 0.0f;
  for (const detail::Candidate& c : candidates)
    aMin = std::min(aMin, c.magnitude), aMax = std::max(aMax, c.magnitude);
  if (candidates.empty()) aMin = aMax = 1.0f;
  h.magnitudeMin = aMin;
  h.magnitudeMax = aMax;

  const float valueScale = windowHi > windowLo ? kPaletteSize / (windowHi - windowLo) : 0.0f;
  out.vectors.resize(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const std::size_t index = candidates[i].index;
    const std::uint32_t x = static_cast<std::uint32_t>(index % d.x);
    const std::uint32_t y = static_cast<std::uint32_t>((index / d.x) % d.y);
    const std::uint32_t z = static_cast<std::uint32_t>(index / sliceStride);
    const float* s = volume.samples.data() + index;
    SourceVector& v = out.vectors[i];
    v.normal = glm::vec3(difference(s, 1, x, d.x, spacing.x), difference(s, d.x, y, d.y, spacing.y),
                         difference(s, sliceStride, z, d.z, spacing.z));
    v.position = volume.origin + glm::vec3(x, y, z) * spacing;
    v.magnitude = candidates[i].magnitude;
    v.source = index;
    const float slice = (*s - windowLo) * valueScale;
    v.color =
        static_cast<std::uint8_t>(std::clamp(slice, 0.0f, static_cast<float>(kPaletteSize - 1)));
  }
  h.vectorCount = out.vectors.size();
  if (summary) *summary = {voxels, candidateCount, out.vectors.size()};
  report(options.progress, 0.8);
  return out;
}

EncodedVectors encodeVolume(const Volume& volume, const VolumeEncodeOptions& options,
                            EncodeSummary* summary) {
  SelectedVectors selected = selectVolumeVectors(volume, options, summary);
  EncodedVectors out = detail::quantizeLargestFirst(selected);
  report(options.progress, 1.0);
  return out;
}

std::uint64_t quantizeVector(const SourceVector& v, const StreamHeader& h,
                             const MagnitudeQuantizer& quantizeA, const glm::uvec3* gridIndex) {
  RecordFields f;
  if (gridIndex) {
    std::uint16_t* code[3] = {&f.x, &f.y, &f.z};
    for (int a = 0; a < 3; ++a) {
      const std::uint64_t n = h.volumeDims[a];
      *code[a] =
          n < 2
              ? 0
              : static_cast<std::uint16_t>(std::min<std::uint64_t>(
                    kPositionSteps - 1, std::uint64_t{(*gridIndex)[a]} * kPositionSteps / (n - 1)));
    }
  } else {
    f.x = quantizeCoordinate(v.position.x, h.boundsMin.x, h.boundsMax.x);
    f.y = quantizeCoordinate(v.position.y, h.boundsMin.y, h.boundsMax.y);
    f.z = quantizeCoordinate(v.position.z, h.boundsMin.z, h.boundsMax.z);
  }
  quantizeDirection(v.normal, f.theta, f.phi);
  f.a = quantizeA(v.magnitude);
  f.c = v.color;
  return packRecord(f);
}

EncodedVectors detail::quantizeLargestFirst(const SelectedVectors& selected) {
  EncodedVectors out;
  out.header = selected.header;
  const StreamHeader& h = out.header;
  const MagnitudeQuantizer quantizeA(h.mapping, h.magnitudeMin, h.magnitudeMax);
  out.records.resize(selected.vectors.size());
  for (std::size_t i = 0; i < selected.vectors.size(); ++i)
    out.records[i] = quantizeVector(selected.vectors[i], h, quantizeA);
  detail::sortLargestFirst(out.records);
  return out;
}

}  // namespace gs::qnv
