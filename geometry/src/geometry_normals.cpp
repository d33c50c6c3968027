// Default normals (clause 6.23 "creaseAngle"; also 6.18 and 6.19): a corner's normal
// averages the normals of the faces around its point that meet its own face at an angle
// of at most creaseAngle, weighted by each face's angle at the point.
#include "geometry_internal.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>

namespace gs::vrml::geometry_detail {

namespace {

/// Points shared by more corners than this are smoothed through normal clusters instead of
/// all pairs, so that a point at the centre of a huge fan stays linear in time.
constexpr std::size_t kPairwiseLimit = 32;
constexpr std::size_t kMaxClusters = 64;

glm::vec3 normalizedOr(const glm::dvec3& v, const glm::vec3& fallback) {
  const double len = glm::length(v);
  if (!(len > 1e-30) || !std::isfinite(len)) return fallback;
  return glm::vec3(v / len);
}

}  // namespace

std::vector<glm::vec3> creaseNormals(const CornerSet& cs, float creaseAngle) {
  const std::size_t n = cs.point.size();
  std::vector<glm::vec3> out(n);
  auto faceNormal = [&](std::size_t k) { return cs.faceNormal[cs.face[k]]; };
  if (!(creaseAngle > 0.0f)) {  // faceted (also for NaN)
    for (std::size_t k = 0; k < n; ++k) out[k] = faceNormal(k);
    return out;
  }
  const double cosCrease =
      creaseAngle >= static_cast<float>(std::numbers::pi) ? -2.0 : std::cos(double{creaseAngle});
  const double tolerance = 1e-6;
  const float cosJoin = static_cast<float>(std::cos(std::min(double{creaseAngle}, 1.0) * 0.25));

  // Corners grouped by point.
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return cs.point[a] < cs.point[b]; });

  struct Cluster {
    glm::vec3 representative;
    glm::dvec3 sum;
  };
  std::vector<Cluster> clusters;
  clusters.reserve(kMaxClusters);
  for (std::size_t begin = 0; begin < n;) {
    std::size_t end = begin + 1;
    while (end < n && cs.point[order[end]] == cs.point[order[begin]]) ++end;
    const std::span<const std::uint32_t> group(order.data() + begin, end - begin);
    begin = end;

    if (cosCrease < -1.0) {  // creaseAngle >= pi: every face around the point counts
      glm::dvec3 sum(0.0);
      for (std::uint32_t k : group) sum += glm::dvec3(faceNormal(k)) * double{cs.weight[k]};
      for (std::uint32_t k : group) out[k] = normalizedOr(sum, faceNormal(k));
      continue;
    }
    if (group.size() <= kPairwiseLimit) {
      for (std::uint32_t k : group) {
        const glm::vec3 own = faceNormal(k);
        glm::dvec3 sum(0.0);
        for (std::uint32_t j : group) {
          const glm::vec3 other = faceNormal(j);
          if (glm::dot(own, other) >= cosCrease - tolerance)
            sum += glm::dvec3(other) * double{cs.weight[j]};
        }
        out[k] = normalizedOr(sum, own);
      }
      continue;
    }
    // Many faces around one point: gather them into clusters of close normals first (a
    // face joins the first cluster within a quarter of the crease angle, or the nearest
    // one once kMaxClusters exist), then compare each corner with the clusters only.
    clusters.clear();
    for (std::uint32_t k : group) {
      const glm::vec3 fn = faceNormal(k);
      Cluster* target = nullptr;
      float bestDot = -2.0f;
      for (Cluster& c : clusters) {
        const float d = glm::dot(c.representative, fn);
        if (d >= cosJoin) {
          target = &c;
          break;
        }
        if (d > bestDot) bestDot = d, target = &c;
      }
      if ((target == nullptr || glm::dot(target->representative, fn) < cosJoin) &&
          clusters.size() < kMaxClusters) {
        clusters.push_back({fn, glm::dvec3(0.0)});
        target = &clusters.back();
      }
      target->sum += glm::dvec3(fn) * double{cs.weight[k]};
    }
    for (std::uint32_t k : group) {
      const glm::vec3 own = faceNormal(k);
      glm::dvec3 sum(0.0);
      for (const Cluster& c : clusters)
        if (glm::dot(own, c.representative) >= cosCrease - tolerance) sum += c.sum;
      out[k] = normalizedOr(sum, own);
    }
  }
  return out;
}

}  // namespace gs::vrml::geometry_detail
