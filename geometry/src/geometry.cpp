// tessellate(): dispatch on the geometry node's type, plus the shared helpers of
// geometry_internal.hpp (problem log, field helpers, mesh builder).
#include "geometry/geometry.hpp"

#include "geometry_internal.hpp"
#include "vrml/geo_nodes.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>

namespace gs::vrml {

namespace geometry_detail {

bool finite(const glm::vec2& v) {
  return std::isfinite(v.x) && std::isfinite(v.y);
}
bool finite(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

glm::vec4 rgba(const glm::vec3& c) {
  auto clamp01 = [](float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; };  // NaN -> 0
  return {clamp01(c.r), clamp01(c.g), clamp01(c.b), 1.0f};
}

glm::vec4 rgba(const glm::vec4& c) {
  auto clamp01 = [](float x) { return x > 0.0f ? (x < 1.0f ? x : 1.0f) : 0.0f; };  // NaN -> 0
  return {clamp01(c.r), clamp01(c.g), clamp01(c.b), clamp01(c.a)};
}

ColorSource::ColorSource(const Node& geometry, std::string_view field) {
  static const std::vector<glm::vec3> kNone;
  rgb_ = &kNone;
  const NodePtr child = geometry.sfnode(field);
  if (child == nullptr) return;
  present_ = true;
  const FieldValue* f = child->field("color");
  if (f == nullptr) return;
  if (f->type() == FieldType::MFColor) {
    rgb_ = &f->get<FieldType::MFColor>();
  } else if (f->type() == FieldType::MFColorRGBA) {
    rgb_ = nullptr;
    rgba_ = &f->get<FieldType::MFColorRGBA>();
  }
}

const std::vector<glm::vec2>& texCoordPoints(const Node& geometry, TexSource& kind) {
  static const std::vector<glm::vec2> kNone;
  NodePtr tc = geometry.sfnode("texCoord");
  kind = TexSource::none;
  if (tc == nullptr) return kNone;
  if (tc->typeId() == NodeTypeId::MultiTextureCoordinate) {  // its first coordinate set
    const std::vector<NodePtr>& sets = tc->mfnode("texCoord");
    tc = sets.empty() ? nullptr : sets.front();
  }
  const FieldValue* f = tc != nullptr ? tc->field("point") : nullptr;
  if (f == nullptr || f->type() != FieldType::MFVec2f) {
    kind = TexSource::generated;
    return kNone;
  }
  kind = TexSource::points;
  return f->get<FieldType::MFVec2f>();
}

const std::vector<glm::vec2>* secondTexCoordPoints(const Node& geometry) {
  const NodePtr& tc = geometry.sfnode("texCoord");
  if (tc == nullptr || tc->typeId() != NodeTypeId::MultiTextureCoordinate) return nullptr;
  const std::vector<NodePtr>& sets = tc->mfnode("texCoord");
  if (sets.size() < 2 || sets[1] == nullptr) return nullptr;
  const FieldValue* f = sets[1]->field("point");
  if (f == nullptr || f->type() != FieldType::MFVec2f) return nullptr;
  return &f->get<FieldType::MFVec2f>();
}

StrqPoints strqTexCoordPoints(const Node& geometry) {
  StrqPoints out;
  NodePtr tc = geometry.sfnode("texCoord");
  if (tc != nullptr && tc->typeId() == NodeTypeId::MultiTextureCoordinate) {
    const std::vector<NodePtr>& sets = tc->mfnode("texCoord");
    tc = sets.empty() ? nullptr : sets.front();
  }
  if (tc == nullptr || tc->unresolved) return out;
  const FieldValue* f = tc->field("point");
  if (f == nullptr) return out;
  auto add = [&out](const glm::vec4& p) {
    const bool ok = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z) &&
                    std::isfinite(p.w) && p.w != 0.0f;
    const glm::vec4 v = ok ? p : glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
    const glm::vec2 st(v.x / v.w, v.y / v.w);
    out.strq.push_back(v);
    out.st.push_back(finite(st) ? st : glm::vec2(0.0f));
  };
  if (tc->typeId() == NodeTypeId::TextureCoordinate3D && f->type() == FieldType::MFVec3f) {
    const std::vector<glm::vec3>& points = f->get<FieldType::MFVec3f>();
    out.strq.reserve(points.size());
    out.st.reserve(points.size());
    for (const glm::vec3& p : points) add(glm::vec4(p, 1.0f));
  } else if (tc->typeId() == NodeTypeId::TextureCoordinate4D && f->type() == FieldType::MFVec4f) {
    const std::vector<glm::vec4>& points = f->get<FieldType::MFVec4f>();
    out.strq.reserve(points.size());
    out.st.reserve(points.size());
    for (const glm::vec4& p : points) add(p);
  } else {
    return out;
  }
  out.present = true;
  return out;
}

std::span<const glm::vec3> coordPoints(const Node& geometry, std::vector<glm::vec3>& scratch) {
  const NodePtr coord = geometry.sfnode("coord");
  if (coord == nullptr) return {};
  const FieldValue* f = coord->field("point");
  if (f == nullptr) return {};
  if (f->type() == FieldType::MFVec3f) return f->get<FieldType::MFVec3f>();
  if (f->type() != FieldType::MFVec3d) return {};
  const auto& d = f->get<FieldType::MFVec3d>();
  if (coord->typeId() == NodeTypeId::GeoCoordinate) {
    // X3D 4.0 clause 25.4.2: geo coordinates of its geoSystem, made local (its geoOrigin).
    const geospatial::GeoSystem system = geoSystemOf(*coord);
    const geospatial::LocalFrame frame = geoFrameOf(*coord);
    scratch.resize(d.size());
    for (std::size_t i = 0; i < d.size(); ++i)
      scratch[i] = glm::vec3(geospatial::toLocal(frame, geospatial::toGeocentric(system, d[i])));
    return scratch;
  }
  scratch.assign(d.begin(), d.end());  // glm converts dvec3 -> vec3 explicitly per element
  return scratch;
}

void ProblemLog::add(const std::string& message) {
  if (count_++ == 0) first_ = message;
}

void ProblemLog::flush() {
  if (flushed_ || count_ == 0 || diag_ == nullptr) return;
  flushed_ = true;
  std::string msg = node_.typeName() + ": " + first_;
  if (count_ > 1) msg += " (and " + std::to_string(count_ - 1) + " more problems in this node)";
  diag_->warning(node_.location, std::move(msg));
}

MeshBuilder::MeshBuilder(Primitive primitive, bool normals, bool colors, bool texCoords)
    : normals_(normals), colors_(colors), texCoords_(texCoords) {
  mesh_.primitive = primitive;
}

namespace {

std::uint64_t mix(std::uint64_t h, const void* data, std::size_t bytes) {
  std::uint32_t w[4];
  std::memcpy(w, data, bytes);
  for (std::size_t i = 0; i < bytes / 4; ++i) {
    h = (h ^ w[i]) * 0x9E3779B97F4A7C15ull;
    h ^= h >> 32;
  }
  return h;
}

std::uint64_t finalMix(std::uint64_t h) {
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdull;
  h ^= h >> 33;
  return h;
}

}  // namespace

std::uint64_t MeshBuilder::hashOf(const Vertex& v) const {
  std::uint64_t h = mix(0x1234567ull, &v.position, sizeof v.position);
  if (normals_) h = mix(h, &v.normal, sizeof v.normal);
  if (colors_) h = mix(h, &v.color, sizeof v.color);
  if (texCoords_) h = mix(h, &v.texCoord, sizeof v.texCoord);
  if (texCoords1_) h = mix(h, &v.texCoord1, sizeof v.texCoord1);
  if (texCoordsStrq_) h = mix(h, &v.texCoordStrq, sizeof v.texCoordStrq);
  if (points_) h = mix(h, &v.point, sizeof v.point);
  return finalMix(h);
}

std::uint64_t MeshBuilder::hashOfStored(std::uint32_t i) const {
  std::uint64_t h = mix(0x1234567ull, &mesh_.positions[i], sizeof(glm::vec3));
  if (normals_) h = mix(h, &mesh_.normals[i], sizeof(glm::vec3));
  if (colors_) h = mix(h, &mesh_.colors[i], sizeof(glm::vec4));
  if (texCoords_) h = mix(h, &mesh_.texCoords[i], sizeof(glm::vec2));
  if (texCoords1_) h = mix(h, &mesh_.texCoords1[i], sizeof(glm::vec2));
  if (texCoordsStrq_) h = mix(h, &mesh_.texCoordsStrq[i], sizeof(glm::vec4));
  if (points_) h = mix(h, &mesh_.pointIndices[i], sizeof(std::uint32_t));
  return finalMix(h);
}

bool MeshBuilder::sameAsStored(std::uint32_t i, const Vertex& v) const {
  return std::memcmp(&mesh_.positions[i], &v.position, sizeof v.position) == 0 &&
         (!normals_ || std::memcmp(&mesh_.normals[i], &v.normal, sizeof v.normal) == 0) &&
         (!colors_ || std::memcmp(&mesh_.colors[i], &v.color, sizeof v.color) == 0) &&
         (!texCoords_ || std::memcmp(&mesh_.texCoords[i], &v.texCoord, sizeof v.texCoord) == 0) &&
         (!texCoords1_ ||
          std::memcmp(&mesh_.texCoords1[i], &v.texCoord1, sizeof v.texCoord1) == 0) &&
         (!texCoordsStrq_ ||
          std::memcmp(&mesh_.texCoordsStrq[i], &v.texCoordStrq, sizeof v.texCoordStrq) == 0) &&
         (!points_ || mesh_.pointIndices[i] == v.point);
}

void MeshBuilder::grow(std::size_t minSlots) {
  std::size_t size = 64;
  while (size < minSlots) size *= 2;
  if (size <= slots_.size()) return;
  slots_.assign(size, 0);
  const std::size_t mask = size - 1;
  const auto n = static_cast<std::uint32_t>(mesh_.positions.size());
  for (std::uint32_t i = 0; i < n; ++i) {
    const std::uint64_t h = hashOfStored(i);
    std::size_t at = static_cast<std::size_t>(h) & mask;
    while (slots_[at] != 0) at = (at + 1) & mask;
    slots_[at] = (h & 0xffffffff00000000ull) | (std::uint64_t{i} + 1);
  }
}

std::uint32_t MeshBuilder::push(const Vertex& v) {
  const auto i = static_cast<std::uint32_t>(mesh_.positions.size());
  mesh_.positions.push_back(v.position);
  if (normals_) mesh_.normals.push_back(v.normal);
  if (colors_) mesh_.colors.push_back(v.color);
  if (texCoords_) mesh_.texCoords.push_back(v.texCoord);
  if (texCoords1_) mesh_.texCoords1.push_back(v.texCoord1);
  if (texCoordsStrq_) mesh_.texCoordsStrq.push_back(v.texCoordStrq);
  if (points_) mesh_.pointIndices.push_back(v.point);
  return i;
}

std::uint32_t MeshBuilder::add(const Vertex& v) {
  if (2 * (mesh_.positions.size() + 1) > slots_.size()) grow(4 * (mesh_.positions.size() + 1));
  const std::uint64_t h = hashOf(v);
  const std::size_t mask = slots_.size() - 1;
  for (std::size_t at = static_cast<std::size_t>(h) & mask;; at = (at + 1) & mask) {
    const std::uint64_t slot = slots_[at];
    if (slot == 0) {
      const std::uint32_t i = push(v);
      slots_[at] = (h & 0xffffffff00000000ull) | (std::uint64_t{i} + 1);
      return i;
    }
    const auto i = static_cast<std::uint32_t>((slot & 0xffffffffull) - 1);
    if ((slot >> 32) == (h >> 32) && sameAsStored(i, v)) return i;
  }
}

void MeshBuilder::reserve(std::size_t vertices, std::size_t indices) {
  mesh_.positions.reserve(vertices);
  if (normals_) mesh_.normals.reserve(vertices);
  if (colors_) mesh_.colors.reserve(vertices);
  if (texCoords_) mesh_.texCoords.reserve(vertices);
  if (texCoords1_) mesh_.texCoords1.reserve(vertices);
  if (texCoordsStrq_) mesh_.texCoordsStrq.reserve(vertices);
  if (points_) mesh_.pointIndices.reserve(vertices);
  mesh_.indices.reserve(indices);
  grow(2 * vertices + 2);
}

Mesh MeshBuilder::finish(bool solid) {
  Mesh m = std::move(mesh_);
  mesh_ = Mesh{};
  mesh_.primitive = m.primitive;
  slots_.clear();
  m.solid = solid;
  for (const glm::vec3& p : m.positions) m.bounds.extend(p);
  return m;
}

// X3D 4.0 clause 24.4.2: a FogCoordinate's depth i belongs to coordinate point i (an
// ElevationGrid's grid point i). Each vertex takes the depth of the first point at its
// exact position (the tessellators copy positions from the points; a vertex they made,
// such as a NURBS sample, takes 0).
void assignFogDepths(const Node& geometry, Mesh& m) {
  const NodePtr& fog = geometry.sfnode("fogCoord");
  if (!fog || fog->unresolved || fog->typeId() != NodeTypeId::FogCoordinate || m.positions.empty())
    return;
  const std::vector<float>& depth = fieldOr<FieldType::MFFloat>(*fog, "depth");
  if (depth.empty()) return;
  const NodePtr& coord = geometry.sfnode("coord");
  std::vector<glm::vec3> points;
  if (geometry.typeId() == NodeTypeId::ElevationGrid) {
    points = elevationGridPoints(geometry, depth.size());
  } else if (!coord || coord->unresolved) {
    return;
  } else if (coord->typeId() == NodeTypeId::CoordinateDouble) {
    const std::vector<glm::dvec3>& d = fieldOr<FieldType::MFVec3d>(*coord, "point");
    points.assign(d.begin(), d.end());
  } else {
    points = fieldOr<FieldType::MFVec3f>(*coord, "point");
  }
  struct Hash {
    std::size_t operator()(const glm::vec3& p) const {
      return std::hash<float>{}(p.x) * 73856093u ^ std::hash<float>{}(p.y) * 19349663u ^
             std::hash<float>{}(p.z) * 83492791u;
    }
  };
  std::unordered_map<glm::vec3, std::size_t, Hash> first;
  first.reserve(points.size());
  for (std::size_t i = 0; i < points.size() && i < depth.size(); ++i)
    first.try_emplace(points[i], i);
  m.fogDepths.resize(m.positions.size());
  for (std::size_t v = 0; v < m.positions.size(); ++v) {
    const auto it = first.find(m.positions[v]);
    m.fogDepths[v] = it != first.end() ? std::max(depth[it->second], 0.0f) : 0.0f;
  }
}

}  // namespace geometry_detail

Mesh tessellate(const Node& geometry, Diagnostics* diag, float nurbsTessellationScale) {
  using namespace geometry_detail;
  if (geometry.unresolved) return {};
  ProblemLog log(geometry, diag);
  Mesh m;
  switch (geometry.typeId()) {
    case NodeTypeId::Box:
      m = tessellateBox(geometry, log);
      break;
    case NodeTypeId::Cone:
      m = tessellateCone(geometry, log);
      break;
    case NodeTypeId::Cylinder:
      m = tessellateCylinder(geometry, log);
      break;
    case NodeTypeId::Sphere:
      m = tessellateSphere(geometry, log);
      break;
    case NodeTypeId::IndexedFaceSet:
      m = tessellateIndexedFaceSet(geometry, log);
      break;
    case NodeTypeId::IndexedLineSet:
      m = tessellateIndexedLineSet(geometry, log);
      break;
    case NodeTypeId::PointSet:
      m = tessellatePointSet(geometry, log);
      break;
    case NodeTypeId::ElevationGrid:
    case NodeTypeId::GeoElevationGrid:
      m = tessellateElevationGrid(geometry, log);
      break;
    case NodeTypeId::Extrusion:
      m = tessellateExtrusion(geometry, log);
      break;
    case NodeTypeId::IndexedTriangleSet:  // X3D 4.0 clause 11 (geometry_x3d.cpp)
      m = tessellateIndexedTriangleSet(geometry, log);
      break;
    case NodeTypeId::IndexedTriangleFanSet:
      m = tessellateIndexedTriangleFanSet(geometry, log);
      break;
    case NodeTypeId::IndexedTriangleStripSet:
      m = tessellateIndexedTriangleStripSet(geometry, log);
      break;
    case NodeTypeId::TriangleSet:
      m = tessellateTriangleSet(geometry, log);
      break;
    case NodeTypeId::TriangleFanSet:
      m = tessellateTriangleFanSet(geometry, log);
      break;
    case NodeTypeId::TriangleStripSet:
      m = tessellateTriangleStripSet(geometry, log);
      break;
    case NodeTypeId::LineSet:
      m = tessellateLineSet(geometry, log);
      break;
    case NodeTypeId::IndexedQuadSet:  // X3D 4.0 clause 32, CADGeometry
      m = tessellateIndexedQuadSet(geometry, log);
      break;
    case NodeTypeId::QuadSet:
      m = tessellateQuadSet(geometry, log);
      break;
    case NodeTypeId::NurbsCurve:  // X3D 4.0 clause 27, NURBS (geometry_nurbs.cpp)
      m = tessellateNurbsCurve(geometry, log);
      break;
    case NodeTypeId::NurbsSweptSurface:  // geometry_nurbs_swept.cpp
      m = tessellateNurbsSweptSurface(geometry, log);
      break;
    case NodeTypeId::NurbsSwungSurface:
      m = tessellateNurbsSwungSurface(geometry, log);
      break;
    case NodeTypeId::NurbsPatchSurface:
    case NodeTypeId::NurbsTrimmedSurface:
      m = tessellateNurbsSurface(geometry, log, nurbsTessellationScale);
      break;
    case NodeTypeId::Arc2D:  // X3D 4.0 clause 14, Geometry2D (geometry_2d.cpp)
      m = tessellateArc2D(geometry, log);
      break;
    case NodeTypeId::ArcClose2D:
      m = tessellateArcClose2D(geometry, log);
      break;
    case NodeTypeId::Circle2D:
      m = tessellateCircle2D(geometry, log);
      break;
    case NodeTypeId::Disk2D:
      m = tessellateDisk2D(geometry, log);
      break;
    case NodeTypeId::Polyline2D:
      m = tessellatePolyline2D(geometry, log);
      break;
    case NodeTypeId::Polypoint2D:
      m = tessellatePolypoint2D(geometry, log);
      break;
    case NodeTypeId::Rectangle2D:
      m = tessellateRectangle2D(geometry, log);
      break;
    case NodeTypeId::TriangleSet2D:
      m = tessellateTriangleSet2D(geometry, log);
      break;
    case NodeTypeId::OutlineGroup:  // GhostSpace extension: its outline (outline_geometry.cpp)
      m = triangulateOutline(fieldOr<FieldType::MFVec3f>(geometry, "outline"),
                             fieldOr<FieldType::MFInt32>(geometry, "outlineLengths"), diag,
                             geometry.location);
      break;
    default:  // Text (6.47) and every non-geometry node: an empty mesh.
      break;
  }
  assignFogDepths(geometry, m);
  // An X3D geoSystem word not understood (X3D 4.0 clause 25.2.2) is left out: said once.
  const Node* geo = geometry.typeId() == NodeTypeId::GeoElevationGrid ? &geometry : nullptr;
  if (const NodePtr& coord = geometry.sfnode("coord");
      coord && coord->typeId() == NodeTypeId::GeoCoordinate)
    geo = coord.get();
  if (geo != nullptr) {
    std::string problem;
    geoSystemOf(*geo, &problem);
    if (!problem.empty()) log.add(problem + "; read without it");
  }
  assignVertexAttributes(geometry, m, log);
  log.flush();
  return m;
}

}  // namespace gs::vrml
