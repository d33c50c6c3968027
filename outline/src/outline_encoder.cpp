// Outline groups (paper section 1.1): weld, region growing over manifold edges, boundary
// loops, area order. See outline/outline_encoder.hpp for the contract.
#include "outline/outline_encoder.hpp"

#include "qnv/error.hpp"

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <numeric>
#include <string>
#include <utility>

namespace gs::outline {

namespace {

constexpr std::uint32_t kNone = std::numeric_limits<std::uint32_t>::max();

bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

void check(const PolygonSoup& soup) {
  if (soup.indices.size() % 3 != 0)
    throw InputError("outline encoder: " + std::to_string(soup.indices.size()) +
                     " indices is not a whole number of triangles");
  if (soup.positions.size() >= kNone)
    throw InputError("outline encoder: too many vertices (" +
                     std::to_string(soup.positions.size()) + ")");
  const std::size_t n = soup.positions.size();
  for (std::size_t i = 0; i < soup.indices.size(); ++i)
    if (soup.indices[i] >= n)
      throw InputError("outline encoder: index " + std::to_string(soup.indices[i]) + " (entry " +
                       std::to_string(i) + ") is outside the " + std::to_string(n) + " positions");
  if (!soup.material.empty() && soup.material.size() != soup.triangleCount())
    throw InputError("outline encoder: " + std::to_string(soup.material.size()) +
                     " material ids for " + std::to_string(soup.triangleCount()) + " triangles");
  if (!soup.normals.empty() && soup.normals.size() != n)
    throw InputError("outline encoder: " + std::to_string(soup.normals.size()) + " normals for " +
                     std::to_string(n) + " positions");
}

/// Welded id of every vertex: equal (finite) positions share an id; a non-finite
/// position gets an id of its own. `weldedPosition` receives one position per id.
std::vector<std::uint32_t> weld(const std::vector<glm::vec3>& p,
                                std::vector<glm::vec3>& weldedPosition) {
  std::vector<std::uint32_t> order;
  order.reserve(p.size());
  std::vector<std::uint32_t> id(p.size(), kNone);
  for (std::uint32_t i = 0; i < p.size(); ++i)
    if (finite(p[i])) order.push_back(i);
  std::sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) {
    const glm::vec3 &u = p[a], &v = p[b];
    if (u.x != v.x) return u.x < v.x;
    if (u.y != v.y) return u.y < v.y;
    if (u.z != v.z) return u.z < v.z;
    return a < b;
  });
  weldedPosition.clear();
  for (std::size_t k = 0; k < order.size(); ++k) {
    const std::uint32_t i = order[k];
    if (k == 0 || p[i] != p[order[k - 1]]) weldedPosition.push_back(p[i]);
    id[i] = static_cast<std::uint32_t>(weldedPosition.size() - 1);
  }
  for (std::uint32_t i = 0; i < p.size(); ++i) {
    if (id[i] != kNone) continue;
    id[i] = static_cast<std::uint32_t>(weldedPosition.size());
    weldedPosition.push_back(p[i]);
  }
  return id;
}

std::uint64_t edgeKey(std::uint32_t a, std::uint32_t b) {
  return a < b ? (std::uint64_t{a} << 32) | b : (std::uint64_t{b} << 32) | a;
}

struct Triangle {
  std::uint32_t w[3];  // welded vertex ids
  glm::dvec3 normal;   // unit
  double area = 0.0;
  bool valid = false;
};

/// Traces the boundary loops of one group from its triangles' welded corners.
void traceOutline(const std::vector<Triangle>& tris, const std::vector<std::uint32_t>& members,
                  const std::vector<glm::vec3>& weldedPosition, PolygonGroup& g) {
  struct Directed {
    std::uint64_t key;
    std::uint32_t from, to;
  };
  std::vector<Directed> edges;
  edges.reserve(3 * members.size());
  for (std::uint32_t t : members)
    for (int c = 0; c < 3; ++c) {
      const std::uint32_t a = tris[t].w[c], b = tris[t].w[(c + 1) % 3];
      edges.push_back({edgeKey(a, b), a, b});
    }
  std::sort(edges.begin(), edges.end(), [](const Directed& x, const Directed& y) {
    return x.key != y.key ? x.key < y.key : x.from < y.from;
  });
  std::vector<std::pair<std::uint32_t, std::uint32_t>> boundary;  // (from, to)
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 1) boundary.emplace_back(edges[i].from, edges[i].to);
    i = j;
  }
  std::sort(boundary.begin(), boundary.end());
  std::vector<unsigned char> used(boundary.size(), 0);
  std::vector<std::size_t> cursor(boundary.size());  // valid at the first edge of a run
  std::iota(cursor.begin(), cursor.end(), std::size_t{0});
  // The next unused boundary edge leaving `v`, or boundary.size(); amortised O(log n).
  auto nextFrom = [&](std::uint32_t v) {
    const auto lo = static_cast<std::size_t>(
        std::lower_bound(boundary.begin(), boundary.end(), std::make_pair(v, std::uint32_t{0})) -
        boundary.begin());
    if (lo == boundary.size() || boundary[lo].first != v) return boundary.size();
    std::size_t i = cursor[lo];
    while (i < boundary.size() && boundary[i].first == v && used[i]) ++i;
    cursor[lo] = i;
    return i < boundary.size() && boundary[i].first == v ? i : boundary.size();
  };

  struct Loop {
    std::size_t begin, size;
    double area;
  };
  std::vector<glm::vec3> points;
  std::vector<Loop> loops;
  const glm::dvec3 n(g.normal);
  for (std::size_t s = 0; s < boundary.size(); ++s) {
    if (used[s]) continue;
    const std::size_t begin = points.size();
    const std::uint32_t start = boundary[s].first;
    std::size_t e = s;
    while (e < boundary.size()) {
      used[e] = 1;
      points.push_back(weldedPosition[boundary[e].first]);
      const std::uint32_t to = boundary[e].second;
      if (to == start) break;
      e = nextFrom(to);
      if (e == boundary.size()) points.push_back(weldedPosition[to]);  // open chain
    }
    // Enclosed area projected on the group normal (Newell), positive counter-clockwise.
    glm::dvec3 newell(0.0);
    const std::size_t m = points.size() - begin;
    const glm::dvec3 o(points[begin]);
    for (std::size_t k = 0; k < m; ++k) {
      const glm::dvec3 a = glm::dvec3(points[begin + k]) - o;
      const glm::dvec3 b = glm::dvec3(points[begin + (k + 1) % m]) - o;
      newell += glm::cross(a, b);
    }
    loops.push_back({begin, m, 0.5 * glm::dot(newell, n)});
  }
  std::stable_sort(loops.begin(), loops.end(), [](const Loop& a, const Loop& b) {
    return std::abs(a.area) > std::abs(b.area);
  });
  g.outline.reserve(points.size());
  for (const Loop& l : loops) {
    g.outline.insert(g.outline.end(), points.begin() + static_cast<std::ptrdiff_t>(l.begin),
                     points.begin() + static_cast<std::ptrdiff_t>(l.begin + l.size));
    g.outlineLengths.push_back(static_cast<std::uint32_t>(l.size));
  }
}

}  // namespace

std::vector<PolygonGroup> encodeOutlineGroups(const PolygonSoup& soup,
                                              const OutlineOptions& options,
                                              OutlineSummary* summary) {
  check(soup);
  OutlineSummary sum;
  const std::size_t triCount = soup.triangleCount();
  sum.triangles = triCount;
  std::vector<glm::vec3> weldedPosition;
  const std::vector<std::uint32_t> welded = weld(soup.positions, weldedPosition);
  sum.weldedVertices = weldedPosition.size();

  // Triangles: welded corners, unit normal, area; zero-area and non-finite ones dropped.
  std::vector<Triangle> tris(triCount);
  for (std::size_t t = 0; t < triCount; ++t) {
    Triangle& tr = tris[t];
    for (int c = 0; c < 3; ++c) tr.w[c] = welded[soup.indices[3 * t + static_cast<std::size_t>(c)]];
    const glm::vec3 &p0 = weldedPosition[tr.w[0]], &p1 = weldedPosition[tr.w[1]],
                    &p2 = weldedPosition[tr.w[2]];
    if (tr.w[0] == tr.w[1] || tr.w[1] == tr.w[2] || tr.w[0] == tr.w[2] || !finite(p0) ||
        !finite(p1) || !finite(p2)) {
      ++sum.droppedTriangles;
      continue;
    }
    const glm::dvec3 cr =
        glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
    const double len = glm::length(cr);
    if (!(len > 0.0) || !std::isfinite(len)) {
      ++sum.droppedTriangles;
      continue;
    }
    tr.normal = cr / len;
    tr.area = 0.5 * len;
    tr.valid = true;
  }

  // Undirected edges, sorted: a run of equal keys is the set of triangles on one edge.
  struct EdgeUse {
    std::uint64_t key;
    std::uint32_t tri;
    std::uint32_t corner;
  };
  std::vector<EdgeUse> edges;
  edges.reserve(3 * triCount);
  for (std::uint32_t t = 0; t < triCount; ++t) {
    if (!tris[t].valid) continue;
    for (std::uint32_t c = 0; c < 3; ++c)
      edges.push_back({edgeKey(tris[t].w[c], tris[t].w[(c + 1) % 3]), t, c});
  }
  std::sort(edges.begin(), edges.end(), [](const EdgeUse& a, const EdgeUse& b) {
    return a.key != b.key ? a.key < b.key : a.tri < b.tri;
  });
  // neighbour[3t + c]: the triangle across corner c's edge when that edge is manifold.
  std::vector<std::uint32_t> neighbour(3 * triCount, kNone);
  for (std::size_t i = 0; i < edges.size();) {
    std::size_t j = i + 1;
    while (j < edges.size() && edges[j].key == edges[i].key) ++j;
    if (j - i == 2) {
      neighbour[3 * std::size_t{edges[i].tri} + edges[i].corner] = edges[i + 1].tri;
      neighbour[3 * std::size_t{edges[i + 1].tri} + edges[i + 1].corner] = edges[i].tri;
    } else if (j - i > 2) {
      ++sum.nonManifoldEdges;
    }
    i = j;
  }

  // Region growing, largest triangle first as seed.
  std::vector<std::uint32_t> seeds;
  seeds.reserve(triCount);
  for (std::uint32_t t = 0; t < triCount; ++t)
    if (tris[t].valid) seeds.push_back(t);
  std::stable_sort(seeds.begin(), seeds.end(),
                   [&](std::uint32_t a, std::uint32_t b) { return tris[a].area > tris[b].area; });
  const double maxAngle =
      std::isfinite(options.maxAngle) ? std::max(0.0, double{options.maxAngle}) : std::numbers::pi;
  const double minCos = maxAngle >= std::numbers::pi ? -2.0 : std::cos(maxAngle) - 1e-9;
  auto materialOf = [&](std::uint32_t t) {
    return soup.material.empty() ? std::uint32_t{0} : soup.material[t];
  };
  std::vector<std::uint32_t> groupOf(triCount, kNone);
  std::vector<std::uint32_t> seedOf;  // per group
  std::vector<std::uint32_t> queue;
  for (std::uint32_t s : seeds) {
    if (groupOf[s] != kNone) continue;
    const auto g = static_cast<std::uint32_t>(seedOf.size());
    seedOf.push_back(s);
    const glm::dvec3 seedNormal = tris[s].normal;
    const std::uint32_t mat = materialOf(s);
    groupOf[s] = g;
    queue.assign(1, s);
    for (std::size_t q = 0; q < queue.size(); ++q) {
      const std::uint32_t t = queue[q];
      for (std::size_t c = 0; c < 3; ++c) {
        const std::uint32_t u = neighbour[3 * std::size_t{t} + c];
        if (u == kNone || groupOf[u] != kNone || materialOf(u) != mat) continue;
        if (glm::dot(tris[u].normal, seedNormal) < minCos) continue;
        groupOf[u] = g;
        queue.push_back(u);
      }
    }
  }

  // Members of each group in input order (counting sort).
  const std::size_t groupCount = seedOf.size();
  std::vector<std::uint32_t> start(groupCount + 1, 0);
  for (std::uint32_t t = 0; t < triCount; ++t)
    if (groupOf[t] != kNone) ++start[groupOf[t] + 1];
  for (std::size_t g = 0; g < groupCount; ++g) start[g + 1] += start[g];
  std::vector<std::uint32_t> memberList(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t t = 0; t < triCount; ++t)
      if (groupOf[t] != kNone) memberList[fill[groupOf[t]]++] = t;
  }

  std::vector<PolygonGroup> groups(groupCount);
  std::vector<std::uint32_t> localOf(soup.positions.size(), kNone);
  std::vector<std::uint32_t> members;
  for (std::size_t g = 0; g < groupCount; ++g) {
    PolygonGroup& out = groups[g];
    const std::uint32_t seed = seedOf[g];
    out.material = materialOf(seed);
    out.normal = glm::vec3(tris[seed].normal);
    members.assign(memberList.begin() + start[g], memberList.begin() + start[g + 1]);
    out.indices.reserve(3 * members.size());
    out.sourceTriangles = members;
    for (std::uint32_t t : members) {
      out.area += tris[t].area;
      for (std::size_t c = 0; c < 3; ++c) {
        const std::uint32_t v = soup.indices[3 * std::size_t{t} + c];
        if (localOf[v] == kNone) {
          localOf[v] = static_cast<std::uint32_t>(out.positions.size());
          out.positions.push_back(soup.positions[v]);
          if (!soup.normals.empty()) out.normals.push_back(soup.normals[v]);
        }
        out.indices.push_back(localOf[v]);
      }
    }
    for (std::uint32_t t : members)
      for (std::size_t c = 0; c < 3; ++c) localOf[soup.indices[3 * std::size_t{t} + c]] = kNone;
    traceOutline(tris, members, weldedPosition, out);
    sum.outlineVertices += out.outline.size();
  }
  // Groups were made in seed order (largest seed first); order them by total area.
  std::stable_sort(groups.begin(), groups.end(),
                   [](const PolygonGroup& a, const PolygonGroup& b) { return a.area > b.area; });
  if (summary) *summary = sum;
  return groups;
}

}  // namespace gs::outline
