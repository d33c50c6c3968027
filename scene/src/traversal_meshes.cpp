// The traversal's world bounds, the viewpoints' cameras fitted to them, and its cache of
// tessellated geometry (SceneTraversal::mesh, meshBounds, dropMeshArrays; scene/traversal.hpp).
#include "scene/camera.hpp"
#include "scene/text_mesh.hpp"
#include "scene/traversal.hpp"

#include <algorithm>
#include <cmath>

namespace gs::scene {

namespace {

/// True when `m` maps each axis onto an axis (scale, mirror, axis swap): then the box of
/// a transformed box is exact.
bool axisAligned(const glm::mat3& m) {
  for (int c = 0; c < 3; ++c) {
    int nonZero = 0;
    const float big = std::max({std::abs(m[c].x), std::abs(m[c].y), std::abs(m[c].z)});
    for (int r = 0; r < 3; ++r)
      if (std::abs(m[c][r]) > big * 1e-6f) ++nonZero;
    if (nonZero > 1) return false;
  }
  return true;
}

}  // namespace

const vrml::Bounds& SceneTraversal::worldBounds() {
  if (haveWorldBounds_) return worldBounds_;
  haveWorldBounds_ = true;  // set first: meshBounds() below cannot recurse into here
  Camera viewer = viewpoints_.empty() ? Camera{} : viewpoints_.front().camera;
  collect(viewer, scratch_);
  vrml::Bounds bounds;
  for (const ShapeInstance& s : scratch_.shapes) {
    const vrml::Bounds& local = meshBounds(*s.geometry);
    if (local.empty()) continue;
    if (!axisAligned(glm::mat3(s.model))) {
      // Rotated: the box of the transformed points, not of the transformed box.
      auto it = meshes_.find(s.geometry);  // meshBounds() made the entry, revision current
      const bool wasDropped = it != meshes_.end() && it->second.arraysDropped;
      const bool kept = wasDropped && !it->second.boundsPositions.empty();
      CachedMesh& cached = kept ? it->second : cachedMesh(*s.geometry);  // may tessellate again
      cached.rotatedUse = true;
      const std::vector<glm::vec3>& points =
          cached.arraysDropped ? cached.boundsPositions : cached.mesh.positions;
      for (const glm::vec3& p : points) bounds.extend(glm::vec3(s.model * glm::vec4(p, 1.0f)));
      if (!kept && wasDropped) dropMeshArrays(*s.geometry);  // keep only the positions
      continue;
    }
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? local.max.x : local.min.x,
                        (corner & 2) ? local.max.y : local.min.y,
                        (corner & 4) ? local.max.z : local.min.z);
      bounds.extend(glm::vec3(s.model * glm::vec4(p, 1.0f)));
    }
  }
  worldBounds_ = bounds;
  scratch_ = TraversalFrame{};
  return worldBounds_;
}

Camera SceneTraversal::viewpointCamera(std::size_t index) {
  Camera camera = index < viewpoints_.size() ? viewpoints_[index].camera : Camera{};
  const vrml::Bounds& bounds = worldBounds();
  const float nearClip = navigation_.nearClip();
  camera.nearClip = nearClip;
  camera.farClip = std::max(nearClip * 2.0f, 1000.0f);
  fitClipPlanes(camera, bounds, nearClip);
  if (navigation_.visibilityLimit > 0.0f)
    camera.farClip = std::max(navigation_.visibilityLimit, camera.nearClip * 2.0f);
  return camera;
}

float NavigationSettings::nearClip() const {
  const float avatar = avatarSize.empty() ? 0.25f : avatarSize[0];
  return avatar > 0.0f ? avatar * 0.5f : 0.125f;
}

void SceneTraversal::noteNurbsSet(const vrml::Node& set) {
  for (const vrml::NodePtr& g : set.mfnode("geometry"))
    if (g && (g->typeId() == vrml::NodeTypeId::NurbsPatchSurface ||
              g->typeId() == vrml::NodeTypeId::NurbsTrimmedSurface))
      nurbsSets_[g.get()] = &set;
}

float SceneTraversal::nurbsScaleOf(const vrml::Node& geometry) const {
  if (nurbsSets_.empty()) return 1.0f;
  const auto it = nurbsSets_.find(&geometry);
  if (it == nurbsSets_.end()) return 1.0f;
  return std::max(0.0f, it->second->get<vrml::FieldType::SFFloat>("tessellationScale", 1.0f));
}

SceneTraversal::CachedMesh& SceneTraversal::cachedMesh(const vrml::Node& geometry) {
  auto [it, inserted] = meshes_.try_emplace(&geometry);
  const std::uint64_t revision = vrml::revisionWithFields(geometry);
  const float nurbsScale = nurbsScaleOf(geometry);
  if (inserted || it->second.arraysDropped || it->second.revision != revision ||
      it->second.nurbsScale != nurbsScale) {
    ++tessellations_;
    it->second.revision = revision;
    it->second.nurbsScale = nurbsScale;
    vrml::Diagnostics diag;
    it->second.mesh = options_.tessellator ? options_.tessellator(geometry, &diag)
                                           : tessellateGeometry(geometry, &diag, nurbsScale);
    it->second.arraysDropped = false;
    for (const vrml::Diagnostic& d : diag.items) report(d.severity, d.location, d.message);
  }
  return it->second;
}

const vrml::Mesh& SceneTraversal::mesh(const vrml::Node& geometry) {
  return cachedMesh(geometry).mesh;
}

const vrml::Bounds& SceneTraversal::meshBounds(const vrml::Node& geometry) {
  auto it = meshes_.find(&geometry);
  if (it != meshes_.end() && it->second.revision == vrml::revisionWithFields(geometry) &&
      it->second.nurbsScale == nurbsScaleOf(geometry))
    return it->second.mesh.bounds;
  return cachedMesh(geometry).mesh.bounds;
}

void SceneTraversal::dropMeshArrays(const vrml::Node& geometry) {
  auto it = meshes_.find(&geometry);
  if (it == meshes_.end()) return;
  vrml::Mesh& m = it->second.mesh;
  if (it->second.rotatedUse) it->second.boundsPositions = std::move(m.positions);
  m.positions = {};
  m.normals = {};
  m.colors = {};
  m.texCoords = {};
  m.attributes = {};  // X3D vertex attributes (vrml::Mesh::attributes)
  m.pointIndices = {};
  m.indices = {};
  it->second.arraysDropped = true;
}

}  // namespace gs::scene
