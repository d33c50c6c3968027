// X3D Picking (ISO/IEC 19775-1:2023, X3D 4.0 clause 38): PointPickSensor, LinePickSensor,
// PrimitivePickSensor and VolumePickSensor test their pickingGeometry, in their own
// coordinate system, against the shapes under their pickTarget nodes each time the clock
// moves (after the time-dependent nodes, so a target an interpolator moved is seen where
// it now is); PickableGroup's `pickable` FALSE hides its shapes from every sensor.
// intersectionType BOUNDS tests the targets' world bounding boxes, GEOMETRY their
// triangles: a point is picked inside a closed target (ray parity), a line where it
// crosses a triangle, a primitive or volume when one of its points lies inside a target,
// a target's point lies inside it, or one of its edges crosses a target's triangle.
// sortOrder CLOSEST and ANY keep one target (the nearest to the sensor's origin for
// CLOSEST), ALL and ALL_SORTED every one (nearest first for ALL_SORTED). Events:
// isActive when some target is picked or none any more, pickedGeometry (the pickTarget
// members picked) and pickedPoint (Point and Line sensors, the sensor's coordinates) when
// they change; LinePickSensor also pickedNormal and pickedTextureCoordinate (0 0 0).
// objectType and matchCriterion choose the PickableGroups a sensor may pick in (38.3.1,
// 38.4.2). A ParticleSystem among the targets' shapes is picked by its particles as they
// are drawn at that step (clause 40.4.7: X3DShapeNode).
#include "execution_state.hpp"

#include "geometry/geometry.hpp"
#include "geometry/intersect.hpp"
#include "particles/particle_mesh.hpp"
#include "vrml/transform.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

/// Whether `node`'s objectType (MFString, "ALL" when it has none) lists `type`.
bool hasObjectType(const vrml::Node& node, std::string_view type) {
  const vrml::FieldValue* f = node.field("objectType");
  if (f == nullptr || f->type() != FieldType::MFString) return type == "ALL";
  const auto& types = f->get<FieldType::MFString>();
  return std::find(types.begin(), types.end(), type) != types.end();
}

/// Whether pick sensor `sensor` may pick what lies under PickableGroup `group` (X3D 4.0
/// clauses 38.3.1, 38.4.2): not when the group's objectType holds "NONE"; always when
/// either holds "ALL"; otherwise by the sensor's matchCriterion over the types both list:
/// MATCH_ANY (the default, and for a value not understood) at least one, MATCH_ONLY_ONE
/// exactly one, MATCH_EVERY all of each's.
bool objectTypesMatch(const vrml::Node& sensor, const vrml::Node& group) {
  if (hasObjectType(group, "NONE")) return false;
  if (hasObjectType(group, "ALL") || hasObjectType(sensor, "ALL")) return true;
  const auto listOf = [](const vrml::Node& n) {
    const vrml::FieldValue* f = n.field("objectType");
    std::vector<std::string> types;
    if (f != nullptr && f->type() == FieldType::MFString) types = f->get<FieldType::MFString>();
    std::sort(types.begin(), types.end());
    types.erase(std::unique(types.begin(), types.end()), types.end());
    return types;
  };
  const std::vector<std::string> mine = listOf(sensor), theirs = listOf(group);
  std::vector<std::string> both;
  std::set_intersection(mine.begin(), mine.end(), theirs.begin(), theirs.end(),
                        std::back_inserter(both));
  const std::string criterion =
      sensor.get<FieldType::SFString>("matchCriterion", std::string("MATCH_ANY"));
  if (criterion == "MATCH_EVERY") return both.size() == mine.size() && both.size() == theirs.size();
  if (criterion == "MATCH_ONLY_ONE") return both.size() == 1;
  return !both.empty();
}

/// Triangles kept per target, and triangle tests made per sensor and step, at most: a
/// hostile world cannot stall a frame (past the budget a sensor picks nothing more).
constexpr std::size_t kMaxTriangles = 2'000'000;
constexpr std::size_t kMaxTests = 50'000'000;

/// A piece of a WorldMesh that is closed by itself (one shape's mesh, one particle's
/// geometry): its triangles end before `end` (an index into WorldMesh::triangles).
struct ClosedPart {
  std::size_t end = 0;
  vrml::Bounds bounds;
};

struct WorldMesh {
  std::vector<glm::vec3> triangles;  // 3 per triangle, world coordinates
  std::vector<glm::vec3> points;     // every vertex (points, lines' ends, triangles' corners)
  std::vector<glm::vec3> segments;   // 2 per line segment
  std::vector<ClosedPart> parts;     // the triangles of each addMesh() call, in order
  vrml::Bounds bounds;
};

void addMesh(const vrml::Mesh& mesh, const glm::mat4& m, WorldMesh& out) {
  std::vector<glm::vec3> world(mesh.positions.size());
  ClosedPart part;
  for (std::size_t i = 0; i < world.size(); ++i) {
    world[i] = glm::vec3(m * glm::vec4(mesh.positions[i], 1.0f));
    out.bounds.extend(world[i]);
  }
  out.points.insert(out.points.end(), world.begin(), world.end());
  auto& list = mesh.primitive == vrml::Primitive::triangles ? out.triangles : out.segments;
  if (mesh.primitive == vrml::Primitive::points) return;
  for (std::uint32_t i : mesh.indices)
    if (i < world.size() && list.size() < kMaxTriangles * 3) {
      list.push_back(world[i]);
      part.bounds.extend(world[i]);
    }
  if (&list != &out.triangles || part.bounds.empty()) return;
  part.end = out.triangles.size();
  out.parts.push_back(part);
}

/// Segment p + t (q - p), t in [0, 1], against triangle a b c (both faces): t, or -1.
float segmentHitsTriangle(const glm::vec3& p, const glm::vec3& q, const glm::vec3& a,
                          const glm::vec3& b, const glm::vec3& c) {
  float t = 0.0f, u = 0.0f, v = 0.0f;
  return vrml::lineTriangle(p, q - p, a, b, c, t, u, v) && t >= 0.0f && t <= 1.0f ? t : -1.0f;
}

bool insideBox(const glm::vec3& p, const vrml::Bounds& b) {
  return !b.empty() && glm::all(glm::greaterThanEqual(p, b.min)) &&
         glm::all(glm::lessThanEqual(p, b.max));
}

/// Whether `p` is inside one of the closed parts of `mesh`: crossings of a ray along a
/// fixed, skew direction with that part's triangles are odd. (Parts are tested one by one:
/// two overlapping closed shapes, or coincident particles, would cancel in one count.)
bool insideMesh(const glm::vec3& p, const WorldMesh& mesh, std::size_t& budget) {
  if (!insideBox(p, mesh.bounds)) return false;
  const glm::vec3 far =
      p + glm::vec3(0.5773f, 0.5774f, 0.5775f) * (glm::length(mesh.bounds.size()) * 4.0f + 1.0f);
  std::size_t begin = 0;
  for (const ClosedPart& part : mesh.parts) {
    const std::size_t first = std::exchange(begin, part.end);
    // Each part's box test counts as a test too: a million particles' boxes are bounded.
    if (budget < 1 + (part.end - first) / 3) {
      budget = 0;
      return false;
    }
    --budget;
    if (!insideBox(p, part.bounds)) continue;
    budget -= (part.end - first) / 3;
    int crossings = 0;
    for (std::size_t i = first; i + 2 < part.end; i += 3)
      if (segmentHitsTriangle(p, far, mesh.triangles[i], mesh.triangles[i + 1],
                              mesh.triangles[i + 2]) >= 0.0f)
        ++crossings;
    if (crossings % 2 == 1) return true;
  }
  return false;
}

bool boxesOverlap(const vrml::Bounds& a, const vrml::Bounds& b) {
  return !a.empty() && !b.empty() && glm::all(glm::lessThanEqual(a.min, b.max)) &&
         glm::all(glm::lessThanEqual(b.min, a.max));
}

enum class PickKind { point, line, primitive, volume };

/// Adds the visible particles of ParticleSystem `system` (its coordinates to world: `m`) as
/// they are drawn (scene/src/traversal_walk.hpp): geometryType GEOMETRY its `geometry`
/// node's mesh (`meshOf`) translated to each particle, the other types the mesh
/// particles::particleMesh makes (SPRITE facing the viewer: `viewToWorld` its turn), up to
/// kMaxTriangles triangles.
template <class MeshOf>
void addParticles(const vrml::Node& system, const particles::ParticleSimulation& simulation,
                  const glm::mat4& m, const glm::mat3& viewToWorld, const MeshOf& meshOf,
                  WorldMesh& out) {
  if (!system.get<FieldType::SFBool>("visible", true)) return;
  const particles::GeometryType type = particles::geometryTypeOf(
      system.get<FieldType::SFString>("geometryType", std::string("QUAD")));
  if (type != particles::GeometryType::geometry) {
    addMesh(particles::particleMesh(system, type, simulation.particles(),
                                    glm::inverse(glm::mat3(m)) * viewToWorld),
            m, out);
    return;
  }
  const vrml::NodePtr& geometry = system.sfnode("geometry");
  if (!geometry || geometry->unresolved) return;
  const vrml::Mesh& mesh = meshOf(*geometry);
  for (const particles::Particle& p : simulation.particles()) {
    if (out.triangles.size() + out.segments.size() >= kMaxTriangles * 3 ||
        out.points.size() >= kMaxTriangles * 3)
      return;
    if (p.visible) addMesh(mesh, glm::translate(m, p.position), out);
  }
}

}  // namespace

bool ExecutionModel::State::classifyPickSensor(NodeState& ns) {
  using vrml::NodeTypeId;
  const NodeTypeId id = ns.node->typeId();
  if (id != NodeTypeId::PointPickSensor && id != NodeTypeId::LinePickSensor &&
      id != NodeTypeId::PrimitivePickSensor && id != NodeTypeId::VolumePickSensor)
    return false;
  ns.pick = std::make_unique<PickSensorState>();
  pickSensors.push_back(&ns);
  return true;
}

void ExecutionModel::State::evaluatePickSensors() {
  if (pickSensors.empty() || !scene) return;
  using vrml::NodeTypeId;
  // The world matrices of the drawn graph (first instance of each node), as the
  // environmental sensors find theirs.
  // Each node's parent matrix, and whether it is pickable (under no PickableGroup whose
  // pickable is FALSE).
  // The innermost PickableGroup around it (null: none), whose objectType filters the
  // sensors (pickableGroupParents: the group around each group).
  struct Place {
    glm::mat4 parent;
    bool pickable;
    const vrml::Node* group;
  };
  vrml::NodeMap<Place> matrices;
  std::unordered_map<const vrml::Node*, const vrml::Node*> pickableGroupParents;
  std::function<void(const std::vector<vrml::NodePtr>&, const glm::mat4&, bool, const vrml::Node*,
                     int)>
      walk = [&](const std::vector<vrml::NodePtr>& list, const glm::mat4& m, bool pickable,
                 const vrml::Node* group, int depth) {
        if (depth > 1000) return;
        for (const vrml::NodePtr& c : list) {
          if (!c || c->unresolved) continue;
          const bool places = vrml::placesChildren(c->typeId());
          const glm::mat4 cm = places ? m * vrml::transformMatrix(*c) : m;
          if (!matrices.try_emplace(c.get(), Place{m, pickable, group}).second) continue;
          const bool isGroup = c->typeId() == NodeTypeId::PickableGroup;
          if (isGroup) pickableGroupParents.try_emplace(c.get(), group);
          const vrml::Node* innerGroup = isGroup ? c.get() : group;
          const bool inner = pickable && (!isGroup || c->get<FieldType::SFBool>("pickable", true));
          if (c->typeId() == NodeTypeId::Switch) {
            const auto& choice = c->mfnode("choice");
            const int which = c->get<FieldType::SFInt32>("whichChoice", -1);
            if (which >= 0 && static_cast<std::size_t>(which) < choice.size())
              walk({choice[static_cast<std::size_t>(which)]}, m, inner, innerGroup, depth + 1);
          } else if (c->typeId() == NodeTypeId::LOD || c->typeId() == NodeTypeId::GeoLOD) {
            const std::span<const vrml::NodePtr> shown = shownNodes(*c);
            walk({shown.begin(), shown.end()}, m, inner, innerGroup, depth + 1);
          } else if (places || c->is(vrml::AbstractType::X3DGroupingNode)) {
            walk(c->mfnode("children"), cm, inner, innerGroup, depth + 1);
          }
        }
      };
  walk(scene->rootNodes, glm::mat4(1.0f), true, nullptr, 0);
  // Whether sensor `sensor` may pick under `group` and every PickableGroup around it.
  const auto groupsAdmit = [&](const vrml::Node& sensor, const vrml::Node* group) {
    for (int depth = 0; group != nullptr && depth <= 1000; ++depth) {
      if (!objectTypesMatch(sensor, *group)) return false;
      const auto up = pickableGroupParents.find(group);
      group = up != pickableGroupParents.end() ? up->second : nullptr;
    }
    return true;
  };
  const auto meshOf = [&](const vrml::Node& geometry) -> const vrml::Mesh& {
    const std::uint64_t revision = vrml::revisionWithFields(geometry);
    auto [it, added] = pickMeshes.try_emplace(&geometry);
    if (added || it->second.first != revision) it->second = {revision, vrml::tessellate(geometry)};
    return it->second.second;
  };

  // The viewer's turn, which SPRITE particles face (none known: the world's axes).
  const glm::mat3 viewToWorld = viewer ? glm::mat3_cast(viewer->orientation) : glm::mat3(1.0f);

  for (NodeState* ns : pickSensors) {
    const vrml::Node& n = *ns->node;
    PickSensorState& st = *ns->pick;
    const auto where = matrices.find(&n);
    const vrml::NodePtr& picking = n.sfnode("pickingGeometry");
    std::vector<const vrml::Node*> picked;
    std::vector<vrml::NodePtr> pickedNodes;
    std::vector<glm::vec3> points, normals;
    if (n.get<FieldType::SFBool>("enabled", true) && where != matrices.end() && picking &&
        !picking->unresolved && !hasObjectType(n, "NONE")) {
      const glm::mat4 sensorToWorld = where->second.parent;
      const glm::mat4 worldToSensor = glm::inverse(sensorToWorld);
      const PickKind kind = n.typeId() == NodeTypeId::PointPickSensor       ? PickKind::point
                            : n.typeId() == NodeTypeId::LinePickSensor      ? PickKind::line
                            : n.typeId() == NodeTypeId::PrimitivePickSensor ? PickKind::primitive
                                                                            : PickKind::volume;
      const bool bounds =
          n.get<FieldType::SFString>("intersectionType", std::string("BOUNDS")) != "GEOMETRY";
      WorldMesh probe;
      addMesh(meshOf(*picking), sensorToWorld, probe);
      const glm::vec3 origin(sensorToWorld[3]);
      struct Hit {
        vrml::NodePtr target;
        float distance;
        std::vector<glm::vec3> points, normals;
      };
      std::vector<Hit> hits;
      std::size_t budget = kMaxTests;
      for (const vrml::NodePtr& target : n.mfnode("pickTarget")) {
        if (!target || target->unresolved) continue;
        const auto t = matrices.find(target.get());
        if (t == matrices.end() || !t->second.pickable) continue;  // not drawn, not pickable
        // The objectType of the PickableGroups around it (its own, if it is one, and those
        // inside it: gather below).
        if (!groupsAdmit(n, t->second.group)) continue;
        // The target's shapes, outside PickableGroups whose pickable is FALSE.
        WorldMesh mesh;
        std::function<void(const vrml::Node&, const glm::mat4&, int)> gather =
            [&](const vrml::Node& node, const glm::mat4& m, int depth) {
              if (depth > 1000 || mesh.triangles.size() >= kMaxTriangles * 3) return;
              if (node.typeId() == NodeTypeId::PickableGroup &&
                  (!node.get<FieldType::SFBool>("pickable", true) || !objectTypesMatch(n, node)))
                return;
              if (node.typeId() == NodeTypeId::Shape) {
                if (const vrml::NodePtr& g = node.sfnode("geometry"); g && !g->unresolved)
                  addMesh(meshOf(*g), m, mesh);
                return;
              }
              if (node.typeId() == NodeTypeId::ParticleSystem) {
                const auto it = nodes.find(&node);
                if (it != nodes.end() && it->second->particles)
                  addParticles(node, it->second->particles->simulation, m, viewToWorld, meshOf,
                               mesh);
                return;
              }
              const bool places = vrml::placesChildren(node.typeId());
              if (!places && !node.is(vrml::AbstractType::X3DGroupingNode)) return;
              const glm::mat4 cm = places ? m * vrml::transformMatrix(node) : m;
              for (const vrml::NodePtr& c : node.mfnode("children"))
                if (c && !c->unresolved) gather(*c, cm, depth + 1);
            };
        gather(*target, t->second.parent, 0);
        if (mesh.bounds.empty()) continue;
        Hit hit{target, glm::length(mesh.bounds.center() - origin), {}, {}};
        bool any = false;
        if (kind == PickKind::point) {
          for (const glm::vec3& p : probe.points)
            if (bounds ? insideBox(p, mesh.bounds) : insideMesh(p, mesh, budget)) {
              hit.points.push_back(glm::vec3(worldToSensor * glm::vec4(p, 1.0f)));
              any = true;
            }
        } else if (kind == PickKind::line) {
          for (std::size_t s = 0; s + 1 < probe.segments.size(); s += 2) {
            const glm::vec3 p = probe.segments[s], q = probe.segments[s + 1];
            if (bounds) {
              any = any || vrml::lineMeetsBox(p, q - p, mesh.bounds, 0.0f, 1.0f);
              continue;
            }
            if (budget < mesh.triangles.size() / 3) {
              budget = 0;
              break;
            }
            budget -= mesh.triangles.size() / 3;
            for (std::size_t i = 0; i + 2 < mesh.triangles.size(); i += 3) {
              const glm::vec3 &a = mesh.triangles[i], &b = mesh.triangles[i + 1],
                              &c = mesh.triangles[i + 2];
              const float at = segmentHitsTriangle(p, q, a, b, c);
              if (at < 0.0f) continue;
              any = true;
              const glm::vec3 point(worldToSensor * glm::vec4(p + at * (q - p), 1.0f));
              // (A line through a shared edge crosses both its triangles: one point.)
              if (std::any_of(hit.points.begin(), hit.points.end(),
                              [&](const glm::vec3& o) { return glm::length(o - point) < 1e-5f; }))
                continue;
              hit.points.push_back(point);
              glm::vec3 normal =
                  glm::mat3(glm::transpose(sensorToWorld)) * glm::cross(b - a, c - a);
              hit.normals.push_back(glm::length(normal) > 0.0f ? glm::normalize(normal) : normal);
            }
          }
        } else if (bounds) {
          any = boxesOverlap(probe.bounds, mesh.bounds);
        } else if (boxesOverlap(probe.bounds, mesh.bounds)) {
          for (const glm::vec3& p : probe.points)
            if ((any = insideMesh(p, mesh, budget))) break;
          for (std::size_t i = 0; !any && i < mesh.points.size(); ++i)
            any = insideMesh(mesh.points[i], probe, budget);
          for (std::size_t i = 0; !any && budget > 0 && i + 2 < probe.triangles.size(); i += 3)
            for (std::size_t j = 0; !any && budget > 0 && j + 2 < mesh.triangles.size();
                 j += 3, --budget)
              for (int e = 0; !any && e < 3; ++e)
                any = segmentHitsTriangle(probe.triangles[i + e], probe.triangles[i + (e + 1) % 3],
                                          mesh.triangles[j], mesh.triangles[j + 1],
                                          mesh.triangles[j + 2]) >= 0.0f;
        }
        if (any) hits.push_back(std::move(hit));
      }
      if (budget == 0 && !ns->problemReported) {
        ns->problemReported = true;
        report(vrml::Severity::warning, n,
               "more than " + std::to_string(kMaxTests) +
                   " triangle tests in one step: the rest of its targets are not tested");
      }
      const std::string order = n.get<FieldType::SFString>("sortOrder", std::string("CLOSEST"));
      if (order != "ALL")
        std::stable_sort(hits.begin(), hits.end(),
                         [](const Hit& a, const Hit& b) { return a.distance < b.distance; });
      if ((order == "CLOSEST" || order == "ANY") && hits.size() > 1) hits.resize(1);
      for (Hit& h : hits) {
        picked.push_back(h.target.get());
        pickedNodes.push_back(h.target);
        points.insert(points.end(), h.points.begin(), h.points.end());
        normals.insert(normals.end(), h.normals.begin(), h.normals.end());
      }
    }
    const auto idx = [&](const char* name) { return n.type().findExact(name); };
    const bool active = !picked.empty();
    if (active && picked != st.picked) {
      emitOwn(*ns, idx("pickedGeometry"), FieldValue::make<FieldType::MFNode>(pickedNodes));
      if (n.typeId() != NodeTypeId::PrimitivePickSensor &&
          n.typeId() != NodeTypeId::VolumePickSensor)
        emitOwn(*ns, idx("pickedPoint"), FieldValue::make<FieldType::MFVec3f>(points));
      if (n.typeId() == NodeTypeId::LinePickSensor) {
        emitOwn(*ns, idx("pickedNormal"), FieldValue::make<FieldType::MFVec3f>(normals));
        emitOwn(*ns, idx("pickedTextureCoordinate"),
                FieldValue::make<FieldType::MFVec3f>(std::vector<glm::vec3>(points.size())));
      }
    } else if (active && points != st.points && n.typeId() != NodeTypeId::PrimitivePickSensor &&
               n.typeId() != NodeTypeId::VolumePickSensor) {
      emitOwn(*ns, idx("pickedPoint"), FieldValue::make<FieldType::MFVec3f>(points));
    }
    if (active != st.active) {
      st.active = active;
      emitOwn(*ns, idx("isActive"), FieldValue::make<FieldType::SFBool>(active));
    }
    st.picked = std::move(picked);
    st.points = std::move(points);
  }
}

}  // namespace gs::runtime
