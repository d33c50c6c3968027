#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/geometric.hpp>

#include "ordering.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"

namespace gs::qnv {

namespace {

Rgba8 triangleColor(const TriangleMesh& mesh, std::size_t t) {
  if (!mesh.faceColors.empty()) return mesh.faceColors[t];
  if (!mesh.vertexColors.empty()) {
    unsigned sum[4] = {0, 0, 0, 0};
    for (int k = 0; k < 3; ++k) {
      const Rgba8& c = mesh.vertexColors[mesh.indices[3 * t + k]];
      for (int ch = 0; ch < 4; ++ch) sum[ch] += c[ch];
    }
    return Rgba8((sum[0] + 1) / 3, (sum[1] + 1) / 3, (sum[2] + 1) / 3, (sum[3] + 1) / 3);
  }
  return mesh.baseColor;
}

void report(const ProgressCallback& progress, double done) {
  if (progress) progress(done);
}

}  // namespace

bool triangleVector(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, std::uint64_t index,
                    SourceVector& out) {
  const glm::vec3 normal = glm::cross(b - a, c - a);
  const float area = 0.5f * glm::length(normal);
  if (!(area > 0.0f && std::isfinite(area) &&
        std::isfinite(a.x + a.y + a.z + b.x + b.y + b.z + c.x + c.y + c.z)))
    return false;
  out.position = (a + b + c) / 3.0f;
  out.normal = normal;
  out.magnitude = area;
  out.source = index;
  return true;
}

SelectedVectors selectSurfaceVectors(const TriangleMesh& mesh, const SurfaceEncodeOptions& options,
                                     EncodeSummary* summary) {
  const std::size_t triangles = mesh.triangleCount();
  if (triangles > std::numeric_limits<std::uint32_t>::max())
    throw InputError("too many triangles to encode (" + std::to_string(triangles) + ")");
  for (std::uint32_t index : mesh.indices)
    if (index >= mesh.positions.size())
      throw InputError("triangle index " + std::to_string(index) + " is beyond the " +
                       std::to_string(mesh.positions.size()) + " vertices");

  std::vector<detail::Candidate> candidates;
  candidates.reserve(triangles);
  for (std::size_t t = 0; t < triangles; ++t) {
    SourceVector v;
    if (triangleVector(mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
                       mesh.positions[mesh.indices[3 * t + 2]], t, v))
      candidates.push_back({v.magnitude, static_cast<std::uint32_t>(t)});
  }
  report(options.progress, 0.3);
  const std::uint64_t candidateCount = candidates.size();
  detail::keepLargest(candidates, options.selection.keepOf(triangles));
  // Source order inside the kept set keeps the encoder's output deterministic.
  std::sort(
      candidates.begin(), candidates.end(),
      [](const detail::Candidate& x, const detail::Candidate& y) { return x.index < y.index; });

  SelectedVectors out;
  StreamHeader& h = out.header;
  h.kind = StreamKind::surface;
  h.mapping = options.mapping;
  h.profile = options.profile;
  out.vectors.resize(candidates.size());
  std::vector<Rgba8> colors(candidates.size());
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(std::numeric_limits<float>::lowest());
  float aMin = std::numeric_limits<float>::max(), aMax = 0.0f;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    const std::size_t t = candidates[i].index;
    SourceVector& v = out.vectors[i];
    triangleVector(mesh.positions[mesh.indices[3 * t]], mesh.positions[mesh.indices[3 * t + 1]],
                   mesh.positions[mesh.indices[3 * t + 2]], t, v);
    lo = glm::min(lo, v.position);
    hi = glm::max(hi, v.position);
    aMin = std::min(aMin, v.magnitude);
    aMax = std::max(aMax, v.magnitude);
    colors[i] = triangleColor(mesh, t);
  }
  if (candidates.empty()) lo = hi = glm::vec3(0.0f), aMin = aMax = 1.0f;
  h.boundsMin = lo;
  h.boundsMax = hi;
  h.magnitudeMin = aMin;
  h.magnitudeMax = aMax;
  std::vector<std::uint8_t> colorIndex;
  h.palette = buildPalette(colors, colorIndex);
  for (std::size_t i = 0; i < out.vectors.size(); ++i) out.vectors[i].color = colorIndex[i];
  h.vectorCount = out.vectors.size();
  if (summary) *summary = {triangles, candidateCount, out.vectors.size()};
  report(options.progress, 0.6);
  return out;
}

EncodedVectors encodeSurface(const TriangleMesh& mesh, const SurfaceEncodeOptions& options,
                             EncodeSummary* summary) {
  SelectedVectors selected = selectSurfaceVectors(mesh, options, summary);
  EncodedVectors out = detail::quantizeLargestFirst(selected);
  report(options.progress, 1.0);
  return out;
}

}  // namespace gs::qnv
