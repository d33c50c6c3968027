// ProximitySensor (6.38) and VisibilitySensor (6.52): the viewer's pose against boxes in
// the sensors' coordinate systems; X3D's TransformSensor (X3D 4.0 clause 22.4.3): a target
// node's coordinate system against the box. Evaluated once a frame when the world has any.
#include "execution_state.hpp"
#include "vrml/geo_nodes.hpp"

#include "vrml/transform.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <optional>
#include <unordered_set>
#include <utility>
#include <vector>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

glm::vec3 vec3Field(const vrml::Node& n, vrml::FieldName name) {
  return n.get<FieldType::SFVec3f>(name, glm::vec3(0.0f));
}

/// The view-projection matrix of the viewer (OpenGL clip space).
glm::mat4 viewProjection(const ViewerPose& v) {
  const float aspect = v.aspect > 0.0f ? v.aspect : 1.0f;
  // fieldOfView spans the smaller side (6.53): vertical when the view is wider than tall.
  const float fovY =
      aspect >= 1.0f ? v.fieldOfView : 2.0f * std::atan(std::tan(v.fieldOfView * 0.5f) / aspect);
  const glm::mat4 projection = glm::perspective(fovY, aspect, v.nearClip, v.farClip);
  const glm::mat4 view =
      glm::inverse(glm::translate(glm::mat4(1.0f), v.position) * glm::mat4_cast(v.orientation));
  return projection * view;
}

/// Whether any part of the box (centre, size, in the coordinates `m` maps to world) may be
/// in view: false only when all eight corners lie outside one clip plane.
bool boxMayBeVisible(const glm::mat4& clip, const glm::vec3& center, const glm::vec3& size) {
  std::array<glm::vec4, 8> c;
  for (int i = 0; i < 8; ++i) {
    const glm::vec3 corner = center + 0.5f * size *
                                          glm::vec3((i & 1) ? 1.0f : -1.0f, (i & 2) ? 1.0f : -1.0f,
                                                    (i & 4) ? 1.0f : -1.0f);
    c[static_cast<std::size_t>(i)] = clip * glm::vec4(corner, 1.0f);
  }
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      bool allOut = true;
      for (const glm::vec4& p : c)
        if (sign * p[axis] <= p.w) allOut = false;
      if (allOut) return false;
    }
  return true;
}

vrml::Rotation rotationOf(const glm::quat& q0) {
  glm::quat q = glm::normalize(q0);
  if (q.w < 0.0f) q = -q;
  const float s = std::sqrt(std::max(0.0f, 1.0f - q.w * q.w));
  if (s < 1e-6f) return {0.0f, 0.0f, 1.0f, 0.0f};
  return {q.x / s, q.y / s, q.z / s, 2.0f * std::acos(std::min(1.0f, q.w))};
}

}  // namespace

void ExecutionModel::State::evaluateEnvironmentSensors() {
  if (environmentSensors == 0 || !scene) return;
  const glm::mat4 clip = viewer ? viewProjection(*viewer) : glm::mat4(1.0f);
  const double now = model.now();
  // The TransformSensors met by the walk, and the coordinate systems of their targets.
  std::vector<std::pair<NodeState*, glm::mat4>> metSensors;
  vrml::NodeMap<std::optional<glm::mat4>> targets;  // set by the walk where it meets them
  for (const NodeState* ts : transformSensors)
    if (const vrml::NodePtr& t = ts->node->sfnode("targetObject"); t && !t->unresolved)
      targets.try_emplace(t.get());
  // Inside the box: events as 6.38 says for the ProximitySensor, for the viewer (local
  // position and orientation in the sensor's coordinates) or for a TransformSensor's target.
  auto report = [&](NodeState& ns, bool inside, const glm::vec3& local,
                    const glm::quat& localOrientation) {
    const vrml::Node& n = *ns.node;
    const auto idx = [&](const char* name) { return n.type().findExact(name); };
    if (inside != ns.sensorActive) {
      ns.sensorActive = inside;
      if (inside) {
        emitOwn(ns, idx("isActive"), FieldValue::make<FieldType::SFBool>(true));
        emitOwn(ns, idx("enterTime"), FieldValue::make<FieldType::SFTime>(now));
      } else {
        emitOwn(ns, idx("isActive"), FieldValue::make<FieldType::SFBool>(false));
        emitOwn(ns, idx("exitTime"), FieldValue::make<FieldType::SFTime>(now));
      }
    }
    if (inside && ns.role != NodeRole::visibility) {
      // position_changed / orientation_changed while inside, when they change (6.38).
      const vrml::Rotation r = rotationOf(localOrientation);
      if (local != ns.lastPosition || r != ns.lastOrientation) {
        ns.lastPosition = local;
        ns.lastOrientation = r;
        emitOwn(ns, idx("position_changed"), FieldValue::make<FieldType::SFVec3f>(local));
        emitOwn(ns, idx("orientation_changed"), FieldValue::make<FieldType::SFRotation>(r));
        if (n.typeId() == vrml::NodeTypeId::GeoProximitySensor)  // X3D 4.0 25.4.7
          emitOwn(ns, idx("geoCoord_changed"),
                  FieldValue::make<FieldType::SFVec3d>(geospatial::fromGeocentric(
                      vrml::geoSystemOf(n),
                      geospatial::fromLocal(vrml::geoFrameOf(n), glm::dvec3(local)))));
      }
    }
  };
  std::vector<NodeState*>& met = sensorsMet;  // each sensor the walk meets, in its order
  met.clear();
  auto sensor = [&](NodeState& ns, const glm::mat4& m) {
    met.push_back(&ns);
    if (ns.role == NodeRole::transformSensor) {
      metSensors.emplace_back(&ns, m);
      return;
    }
    if (!viewer) return;
    const vrml::Node& n = *ns.node;
    const bool enabled = n.get<FieldType::SFBool>("enabled", true);
    glm::vec3 center = vec3Field(n, "center");
    const glm::vec3 size = vec3Field(n, "size");
    if (n.typeId() == vrml::NodeTypeId::GeoProximitySensor)  // its box centred at geoCenter
      if (const glm::dvec3 g = n.get<FieldType::SFVec3d>("geoCenter", glm::dvec3(0.0));
          g != glm::dvec3(0.0))
        center = glm::vec3(vrml::geoToLocal(n, g));
    bool inside = false;
    glm::vec3 local(0.0f);
    glm::quat localOrientation(1.0f, 0.0f, 0.0f, 0.0f);
    if (enabled && size.x > 0.0f && size.y > 0.0f && size.z > 0.0f) {
      if (ns.role == NodeRole::proximity) {
        const glm::mat4 inv = glm::inverse(m);
        local = glm::vec3(inv * glm::vec4(viewer->position, 1.0f));
        const glm::vec3 d = glm::abs(local - center);
        inside = d.x <= size.x * 0.5f && d.y <= size.y * 0.5f && d.z <= size.z * 0.5f;
        localOrientation = glm::quat_cast(glm::mat3(inv)) * viewer->orientation;
      } else {
        inside = boxMayBeVisible(clip * m, center, size);
      }
    }
    report(ns, inside, local, localOrientation);
  };
  // The sensors' coordinate systems: a walk of the drawn graph (whichChoice of a Switch,
  // the level a LOD shows and the nodes a GeoLOD shows, as drawing last said).
  std::function<void(const std::vector<vrml::NodePtr>&, const glm::mat4&, int)> walk =
      [&](const std::vector<vrml::NodePtr>& list, const glm::mat4& m, int depth) {
        if (depth > 1000) return;
        for (const vrml::NodePtr& c : list) {
          if (!c) continue;
          using vrml::NodeTypeId;
          const NodeTypeId type = c->typeId();
          const bool places = vrml::placesChildren(type);
          if (!targets.empty())
            if (const auto t = targets.find(c.get()); t != targets.end() && !t->second)
              t->second = places ? m * vrml::transformMatrix(*c) : m;  // its first instance
          if (places) {
            walk(c->mfnode("children"), m * vrml::transformMatrix(*c), depth + 1);
          } else if (type == NodeTypeId::Switch) {
            const auto& choice = c->mfnode("choice");
            const int which = c->get<FieldType::SFInt32>("whichChoice", -1);
            if (which >= 0 && static_cast<std::size_t>(which) < choice.size())
              walk({choice[static_cast<std::size_t>(which)]}, m, depth + 1);
          } else if (type == NodeTypeId::LOD || type == NodeTypeId::GeoLOD) {
            const std::span<const vrml::NodePtr> shown = shownNodes(*c);
            walk({shown.begin(), shown.end()}, m, depth + 1);
          } else if (c->is(vrml::AbstractType::X3DGroupingNode)) {
            walk(c->mfnode("children"), m, depth + 1);
          } else if (type == NodeTypeId::ProximitySensor || type == NodeTypeId::VisibilitySensor ||
                     type == NodeTypeId::TransformSensor ||
                     type == NodeTypeId::GeoProximitySensor) {
            const auto it = nodes.find(c.get());
            if (it != nodes.end()) sensor(*it->second, m);
          }
        }
      };
  walk(scene->rootNodes, glm::mat4(1.0f), 0);
  // TransformSensor (X3D 4.0 clause 22.4.3): the target's coordinate system (its origin and
  // axes: a Transform target's translation and rotation) against the sensor's box, in the
  // sensor's coordinates. A target not drawn, or none, is outside.
  for (auto& [ns, m] : metSensors) {
    const vrml::Node& n = *ns->node;
    const glm::vec3 center = vec3Field(n, "center"), size = vec3Field(n, "size");
    bool inside = false;
    glm::vec3 local(0.0f);
    glm::quat localOrientation(1.0f, 0.0f, 0.0f, 0.0f);
    const vrml::NodePtr& target = n.sfnode("targetObject");
    const auto t = target ? targets.find(target.get()) : targets.end();
    if (n.get<FieldType::SFBool>("enabled", true) && t != targets.end() && t->second &&
        size.x > 0.0f && size.y > 0.0f && size.z > 0.0f) {
      const glm::mat4 relative = glm::inverse(m) * *t->second;
      local = glm::vec3(relative[3]);
      const glm::vec3 d = glm::abs(local - center);
      inside = d.x <= size.x * 0.5f && d.y <= size.y * 0.5f && d.z <= size.z * 0.5f;
      localOrientation = glm::quat_cast(glm::mat3(relative));
    }
    report(*ns, inside, local, localOrientation);
  }
  // A sensor the walk did not meet (its Switch choice, LOD level or GeoLOD children are
  // no longer drawn) is outside.
  std::vector<NodeState*> wasActive;
  wasActive.swap(activeEnvironmentSensors);
  std::unordered_set<NodeState*>& seen = sensorScratch;  // kept: no allocation per frame
  if (!wasActive.empty()) {
    seen.clear();
    seen.insert(met.begin(), met.end());
    for (NodeState* ns : wasActive)
      if (ns->sensorActive && !ns->unloaded && !seen.contains(ns))
        report(*ns, false, glm::vec3(0.0f), glm::quat(1.0f, 0.0f, 0.0f, 0.0f));
  }
  seen.clear();
  for (NodeState* ns : met)
    if (ns->sensorActive && seen.insert(ns).second) activeEnvironmentSensors.push_back(ns);
}

}  // namespace gs::runtime
