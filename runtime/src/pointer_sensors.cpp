// Pointing-device sensors (ISO/IEC 14772-1:1997 4.6.7): TouchSensor (6.48), PlaneSensor
// (6.34), SphereSensor (6.43), CylinderSensor (6.13) and Anchor (6.2) as a sensor.
//
// The sensors a pick reaches are those among the children of the grouping nodes on the
// path from the picked Shape up to the root: the lowest group with an enabled sensor (or
// an Anchor, which senses for its own children) wins, and all its enabled sensors react
// (4.6.7.2). A press over them activates them; until the release they hold the pointer
// (other sensors get nothing), the drag sensors following it on their virtual geometry
// (a plane, a sphere, a cylinder or disk fixed at activation) even off the real geometry.
// Every pointer() call is one timestamp at the clock's now().
#include "base/url.hpp"
#include "execution_state.hpp"
#include "vrml/geo_nodes.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <string_view>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

enum class SensorKind : std::uint8_t { touch, plane, sphere, cylinder, anchor };

bool sensorKindOf(const vrml::Node& n, SensorKind& kind) {
  using vrml::NodeTypeId;
  switch (n.typeId()) {
    case NodeTypeId::TouchSensor:
    case NodeTypeId::GeoTouchSensor:  // X3D 4.0 25.4.11: and hitGeoCoord_changed
      kind = SensorKind::touch;
      return true;
    case NodeTypeId::PlaneSensor:
      kind = SensorKind::plane;
      return true;
    case NodeTypeId::SphereSensor:
      kind = SensorKind::sphere;
      return true;
    case NodeTypeId::CylinderSensor:
      kind = SensorKind::cylinder;
      return true;
    case NodeTypeId::Anchor:
      kind = SensorKind::anchor;
      return true;
    default:
      return false;
  }
}

int fieldOf(const vrml::Node& n, std::string_view name) {
  return n.type().findExact(name);
}

template <FieldType T, class V>
V read(const vrml::Node& n, std::string_view name, V fallback) {
  const int i = fieldOf(n, name);
  if (i < 0) return fallback;
  const FieldValue& f = n.fieldAt(static_cast<std::size_t>(i));
  return f.type() == T ? f.get<T>() : fallback;
}

/// A sensor reached by a pick, with the matrix of its coordinate system.
struct Sensor {
  NodeState* ns = nullptr;
  SensorKind kind = SensorKind::touch;
  glm::mat4 localToWorld{1.0f};
};

/// A sensor the button went down on.
struct ActiveSensor {
  Sensor sensor;
  glm::mat4 worldToLocal{1.0f};  // fixed at activation: the virtual geometry stays put
  glm::vec3 start{0.0f};         // the hit point at activation, local coordinates
  bool disk = false;             // CylinderSensor: the disk (true) or the cylinder
  bool over = true;              // TouchSensor: the pointer is over its geometry
  bool sent = false;             // a drag sensor sent an output (autoOffset keeps it)
  glm::vec3 lastTranslation{0.0f};
  glm::vec4 lastRotation{0.0f, 0.0f, 1.0f, 0.0f};
  float lastAngle = 0.0f;
};

constexpr float kPi = 3.14159265358979f;

/// The rotation turning unit vector `a` into unit vector `b` (shortest arc).
glm::quat arc(const glm::vec3& a, const glm::vec3& b) {
  const glm::vec3 axis = glm::cross(a, b);
  const float s = glm::length(axis);
  const float angle = std::atan2(s, glm::dot(a, b));
  if (s < 1e-12f) {
    if (glm::dot(a, b) > 0.0f) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
    // Opposite: half a turn around any axis perpendicular to a.
    glm::vec3 p = glm::cross(a, glm::vec3(1.0f, 0.0f, 0.0f));
    if (glm::length(p) < 1e-6f) p = glm::cross(a, glm::vec3(0.0f, 1.0f, 0.0f));
    return glm::angleAxis(kPi, glm::normalize(p));
  }
  return glm::angleAxis(angle, axis / s);
}

glm::quat toQuat(const vrml::Rotation& r) {
  const glm::vec3 axis(r.x, r.y, r.z);
  const float len = glm::length(axis);
  if (len < 1e-12f) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return glm::angleAxis(r.w, axis / len);
}

/// An SFRotation from a quaternion; the identity is (0 0 1 0).
vrml::Rotation toRotation(glm::quat q) {
  q = glm::normalize(q);
  if (q.w < 0.0f) q = -q;
  const glm::vec3 v(q.x, q.y, q.z);
  const float s = glm::length(v);
  if (s < 1e-7f) return {0.0f, 0.0f, 1.0f, 0.0f};
  return {v.x / s, v.y / s, v.z / s, 2.0f * std::atan2(s, q.w)};
}

/// Angle of `p` around local +Y (a rotation by a about +Y adds a).
float angleAroundY(const glm::vec3& p) {
  return std::atan2(-p.z, p.x);
}

/// The nearest point o + t d with t >= 0 where a t^2 + b t + c = 0 (a ray meeting a
/// quadric); false when there is none.
bool nearestForwardRoot(const glm::vec3& o, const glm::vec3& d, double a, double b, double c,
                        glm::vec3& out) {
  if (a < 1e-18) return false;
  const double disc = b * b - 4.0 * a * c;
  if (disc < 0.0) return false;
  const double q = std::sqrt(disc);
  double t = (-b - q) / (2.0 * a);
  if (t < 0.0) t = (-b + q) / (2.0 * a);
  if (t < 0.0) return false;
  out = glm::vec3(glm::dvec3(o) + t * glm::dvec3(d));
  return true;
}

/// The ray's intersections with the infinite cylinder x^2 + z^2 = r^2 (nearest t >= 0).
bool hitCylinder(const glm::vec3& o, const glm::vec3& d, float r, glm::vec3& out) {
  return nearestForwardRoot(o, d, double(d.x) * d.x + double(d.z) * d.z,
                            2.0 * (double(o.x) * d.x + double(o.z) * d.z),
                            double(o.x) * o.x + double(o.z) * o.z - double(r) * r, out);
}

/// The ray's intersections with the sphere |p| = r (nearest t >= 0).
bool hitSphere(const glm::vec3& o, const glm::vec3& d, float r, glm::vec3& out) {
  return nearestForwardRoot(o, d, glm::dot(d, d), 2.0 * glm::dot(o, d),
                            double(glm::dot(o, o)) - double(r) * r, out);
}

/// The plane axis . p = value (axis 1: y, 2: z).
bool hitPlane(const glm::vec3& o, const glm::vec3& d, int axis, float value, glm::vec3& out) {
  if (std::abs(d[axis]) < 1e-12f) return false;
  const float t = (value - o[axis]) / d[axis];
  if (t < 0.0f) return false;
  out = o + t * d;
  out[axis] = value;
  return true;
}

}  // namespace

struct PointerState {
  bool down = false;
  bool haveRay = false;
  glm::vec3 lastOrigin{0.0f}, lastDirection{0.0f};
  std::vector<NodeState*> over;  // TouchSensors whose isOver is TRUE
  std::vector<ActiveSensor> active;
  std::vector<Sensor> under;     // what the last pointer() found under the pointer
  std::size_t nodesScanned = 0;  // wantsPointer(): the node count at the last scan
  bool sensorsSeen = false;
};

void PointerStateDeleter::operator()(PointerState* p) const {
  delete p;
}

namespace {

/// The enabled sensors of the lowest group on `hit`'s path that has any (4.6.7.2).
std::vector<Sensor> sensorsUnder(ExecutionModel::State& s, const PickResult& hit) {
  std::vector<Sensor> found;
  for (auto entry = hit.path.rbegin(); entry != hit.path.rend(); ++entry) {
    const std::vector<vrml::NodePtr>* children = entry->children;
    if (children == nullptr && entry->node != nullptr) children = &entry->node->mfnode("children");
    if (children != nullptr)
      for (const vrml::NodePtr& c : *children) {
        SensorKind kind;
        if (!c || !sensorKindOf(*c, kind) || kind == SensorKind::anchor) continue;
        if (!read<FieldType::SFBool>(*c, "enabled", true)) continue;
        found.push_back({&s.reach(c, false), kind, entry->localToWorld});
      }
    SensorKind kind;
    if (entry->node != nullptr && sensorKindOf(*entry->node, kind) && kind == SensorKind::anchor)
      found.push_back({&s.reach(*entry->node, false), kind, entry->localToWorld});
    if (!found.empty()) break;
  }
  return found;
}

/// Whether `node` senses for the geometry of `hit`: a child of a group on its path (or
/// the Anchor on it), lowest or not.
bool influences(const vrml::Node* node, const PickResult& hit) {
  for (const PickedNode& entry : hit.path) {
    if (entry.node == node) return true;
    const std::vector<vrml::NodePtr>* children = entry.children;
    if (children == nullptr && entry.node != nullptr) children = &entry.node->mfnode("children");
    if (children != nullptr)
      for (const vrml::NodePtr& c : *children)
        if (c.get() == node) return true;
  }
  return false;
}

glm::vec3 toLocal(const glm::mat4& worldToLocal, const glm::vec3& p) {
  return glm::vec3(worldToLocal * glm::vec4(p, 1.0f));
}

}  // namespace

namespace {

struct PointerRun {
  ExecutionModel::State& s;
  const PointerEvent& event;
  bool moved;

  void send(NodeState& ns, std::string_view field, FieldValue value) {
    s.emitOwn(ns, fieldOf(*ns.node, field), std::move(value));
  }

  /// hitPoint_changed, hitNormal_changed, hitTexCoord_changed of a TouchSensor (6.48),
  /// in its local coordinates.
  void hitEvents(const Sensor& sensor) {
    if (!event.hit) return;
    const PickResult& hit = *event.hit;
    const glm::mat4 inverse = glm::inverse(sensor.localToWorld);
    const glm::vec3 point = toLocal(inverse, hit.point);
    glm::vec3 normal = glm::transpose(glm::mat3(sensor.localToWorld)) * hit.normal;
    if (glm::length(normal) > 1e-12f) normal = glm::normalize(normal);
    send(*sensor.ns, "hitPoint_changed", FieldValue::make<FieldType::SFVec3f>(point));
    send(*sensor.ns, "hitNormal_changed", FieldValue::make<FieldType::SFVec3f>(normal));
    send(*sensor.ns, "hitTexCoord_changed", FieldValue::make<FieldType::SFVec2f>(hit.texCoord));
    if (sensor.ns->node->typeId() == vrml::NodeTypeId::GeoTouchSensor) {
      // The hit point's geo coordinates in the sensor's geoSystem (its geoOrigin's frame).
      const vrml::Node& n = *sensor.ns->node;
      const glm::dvec3 geo = geospatial::fromGeocentric(
          vrml::geoSystemOf(n), geospatial::fromLocal(vrml::geoFrameOf(n), glm::dvec3(point)));
      send(*sensor.ns, "hitGeoCoord_changed", FieldValue::make<FieldType::SFVec3d>(geo));
    }
  }

  /// TouchSensors' isOver (and hit events) when no sensor holds the pointer.
  void hover(PointerState& p) {
    std::vector<const Sensor*> touch;
    for (const Sensor& u : p.under)
      if (u.kind == SensorKind::touch) touch.push_back(&u);
    std::vector<NodeState*> now;
    for (NodeState* o : p.over) {
      const bool still =
          std::any_of(touch.begin(), touch.end(), [&](const Sensor* t) { return t->ns == o; });
      if (!still) send(*o, "isOver", FieldValue::make<FieldType::SFBool>(false));
    }
    for (const Sensor* t : touch) {
      const bool was = std::find(p.over.begin(), p.over.end(), t->ns) != p.over.end();
      if (!was) send(*t->ns, "isOver", FieldValue::make<FieldType::SFBool>(true));
      if (!was || moved) hitEvents(*t);
      now.push_back(t->ns);
    }
    p.over = std::move(now);
  }

  /// A drag sensor follows the bearing on its virtual geometry (6.34, 6.43, 6.13).
  void drag(ActiveSensor& a) {
    NodeState& ns = *a.sensor.ns;
    const vrml::Node& n = *ns.node;
    const glm::vec3 o = toLocal(a.worldToLocal, event.rayOrigin);
    const glm::vec3 d = glm::mat3(a.worldToLocal) * event.rayDirection;
    glm::vec3 track;
    switch (a.sensor.kind) {
      case SensorKind::plane: {
        if (!hitPlane(o, d, 2, a.start.z, track)) return;
        glm::vec3 t = read<FieldType::SFVec3f>(n, "offset", glm::vec3(0.0f)) + (track - a.start);
        const glm::vec2 lo = read<FieldType::SFVec2f>(n, "minPosition", glm::vec2(0.0f));
        const glm::vec2 hi = read<FieldType::SFVec2f>(n, "maxPosition", glm::vec2(-1.0f));
        for (int i = 0; i < 2; ++i)
          if (lo[i] <= hi[i]) t[i] = std::clamp(t[i], lo[i], hi[i]);
        send(ns, "trackPoint_changed", FieldValue::make<FieldType::SFVec3f>(track));
        send(ns, "translation_changed", FieldValue::make<FieldType::SFVec3f>(t));
        a.lastTranslation = t;
        break;
      }
      case SensorKind::sphere: {
        const float r = glm::length(a.start);
        if (r < 1e-12f || !hitSphere(o, d, r, track)) return;
        const glm::quat q =
            arc(a.start / r, glm::normalize(track)) *
            toQuat(read<FieldType::SFRotation>(n, "offset", vrml::Rotation(0, 1, 0, 0)));
        const vrml::Rotation rotation = toRotation(q);
        send(ns, "trackPoint_changed", FieldValue::make<FieldType::SFVec3f>(track));
        send(ns, "rotation_changed", FieldValue::make<FieldType::SFRotation>(rotation));
        a.lastRotation = rotation;
        break;
      }
      case SensorKind::cylinder: {
        if (a.disk) {
          if (!hitPlane(o, d, 1, a.start.y, track)) return;
        } else {
          const float r = glm::length(glm::vec2(a.start.x, a.start.z));
          if (r < 1e-12f || !hitCylinder(o, d, r, track)) return;
        }
        if (glm::length(glm::vec2(track.x, track.z)) < 1e-12f) return;
        float angle = angleAroundY(track) - angleAroundY(a.start);
        while (angle > kPi) angle -= 2.0f * kPi;
        while (angle <= -kPi) angle += 2.0f * kPi;
        angle += read<FieldType::SFFloat>(n, "offset", 0.0f);
        const float lo = read<FieldType::SFFloat>(n, "minAngle", 0.0f);
        const float hi = read<FieldType::SFFloat>(n, "maxAngle", -1.0f);
        if (lo <= hi) angle = std::clamp(angle, lo, hi);
        send(ns, "trackPoint_changed", FieldValue::make<FieldType::SFVec3f>(track));
        send(ns, "rotation_changed",
             FieldValue::make<FieldType::SFRotation>(vrml::Rotation(0.0f, 1.0f, 0.0f, angle)));
        a.lastAngle = angle;
        break;
      }
      case SensorKind::touch:
      case SensorKind::anchor:
        return;
    }
    a.sent = true;
  }

  ActiveSensor activate(const Sensor& sensor) {
    ActiveSensor a;
    a.sensor = sensor;
    a.worldToLocal = glm::inverse(sensor.localToWorld);
    if (event.hit) a.start = toLocal(a.worldToLocal, event.hit->point);
    if (sensor.kind == SensorKind::cylinder) {
      // 6.13: a bearing within diskAngle of the local Y axis drags a disk, else a cylinder.
      glm::vec3 d = glm::mat3(a.worldToLocal) * event.rayDirection;
      if (glm::length(d) > 1e-12f) d = glm::normalize(d);
      const float toAxis = std::acos(std::clamp(std::abs(d.y), 0.0f, 1.0f));
      a.disk = toAxis < read<FieldType::SFFloat>(*sensor.ns->node, "diskAngle", 0.262f);
    }
    return a;
  }

  void release(ActiveSensor& a) {
    NodeState& ns = *a.sensor.ns;
    vrml::Node& n = *ns.node;
    switch (a.sensor.kind) {
      case SensorKind::touch:
        send(ns, "isActive", FieldValue::make<FieldType::SFBool>(false));
        // 6.48: touchTime when released over the sensor's geometry.
        if (a.over) send(ns, "touchTime", FieldValue::make<FieldType::SFTime>(s.model.now()));
        break;
      case SensorKind::anchor:
        // 6.2: a click (press and release over its children) follows the link.
        if (event.hit && influences(&n, *event.hit))
          s.requestUrl(read<FieldType::MFString>(n, "url", std::vector<std::string>{}),
                       read<FieldType::MFString>(n, "parameter", std::vector<std::string>{}), &n);
        break;
      case SensorKind::plane:
      case SensorKind::sphere:
      case SensorKind::cylinder: {
        send(ns, "isActive", FieldValue::make<FieldType::SFBool>(false));
        if (!a.sent || !read<FieldType::SFBool>(n, "autoOffset", true)) break;
        if (a.sensor.kind == SensorKind::plane)
          send(ns, "offset", FieldValue::make<FieldType::SFVec3f>(a.lastTranslation));
        else if (a.sensor.kind == SensorKind::sphere)
          send(ns, "offset", FieldValue::make<FieldType::SFRotation>(a.lastRotation));
        else
          send(ns, "offset", FieldValue::make<FieldType::SFFloat>(a.lastAngle));
        break;
      }
    }
  }
};

}  // namespace

bool ExecutionModel::pointer(const PointerEvent& event) {
  State& s = *s_;
  if (!s.pointer) s.pointer.reset(new PointerState);
  PointerState& p = *s.pointer;
  ++s.stamp;
  ++stats_.cascades;
  s.eventsThisCascade = 0;
  s.cascadeOverflow = false;

  const bool moved =
      !p.haveRay || event.rayOrigin != p.lastOrigin || event.rayDirection != p.lastDirection;
  p.haveRay = true;
  p.lastOrigin = event.rayOrigin;
  p.lastDirection = event.rayDirection;
  p.under = event.hit ? sensorsUnder(s, *event.hit) : std::vector<Sensor>{};
  PointerRun run{s, event, moved};

  const bool press = event.buttonDown && !p.down;
  const bool releasing = !event.buttonDown && p.down;
  p.down = event.buttonDown;

  if (p.active.empty()) {
    run.hover(p);
    if (press) {
      // 4.6.7.2: the sensors under the pointer become active and hold it until release.
      for (const Sensor& u : p.under) p.active.push_back(run.activate(u));
      for (ActiveSensor& a : p.active)
        if (a.sensor.kind != SensorKind::anchor)
          run.send(*a.sensor.ns, "isActive", FieldValue::make<FieldType::SFBool>(true));
    }
  } else {
    for (ActiveSensor& a : p.active) {
      if (a.sensor.kind == SensorKind::touch) {
        // An active TouchSensor tracks whether the pointer is still over its geometry.
        const bool over = event.hit && influences(a.sensor.ns->node, *event.hit);
        if (over != a.over)
          run.send(*a.sensor.ns, "isOver", FieldValue::make<FieldType::SFBool>(over));
        if (over && (moved || !a.over)) run.hitEvents(a.sensor);
        a.over = over;
        auto it = std::find(p.over.begin(), p.over.end(), a.sensor.ns);
        if (over && it == p.over.end()) p.over.push_back(a.sensor.ns);
        if (!over && it != p.over.end()) p.over.erase(it);
      } else if (moved && a.sensor.kind != SensorKind::anchor) {
        run.drag(a);
      }
    }
    if (releasing) {
      std::vector<ActiveSensor> done;
      done.swap(p.active);
      for (ActiveSensor& a : done) run.release(a);
      run.hover(p);  // sensors under the pointer now, the released ones included
    }
  }
  s.runCascade();
  s.initializeScripts();
  return !p.active.empty();
}

PointerHint ExecutionModel::pointerHint() const {
  PointerHint hint;
  if (!s_->pointer) return hint;
  const PointerState& p = *s_->pointer;
  hint.clickable = !p.under.empty() || !p.active.empty();
  auto describe = [&](const Sensor& sensor) {
    if (sensor.kind == SensorKind::anchor && hint.description.empty())
      hint.description = read<FieldType::SFString>(*sensor.ns->node, "description", std::string());
  };
  for (const ActiveSensor& a : p.active) describe(a.sensor);
  for (const Sensor& u : p.under) describe(u);
  return hint;
}

bool ExecutionModel::wantsPointer() const {
  State& s = *s_;
  if (!s.pointer) s.pointer.reset(new PointerState);
  PointerState& p = *s.pointer;
  if (!p.active.empty()) return true;
  if (p.nodesScanned != s.nodes.size()) {  // nodes are only ever added
    p.nodesScanned = s.nodes.size();
    p.sensorsSeen = false;
    for (const auto& [node, ns] : s.nodes) {
      SensorKind kind;
      if (sensorKindOf(*node, kind) || node->typeId() == vrml::NodeTypeId::Inline) {
        p.sensorsSeen = true;
        break;
      }
    }
  }
  return p.sensorsSeen;
}

void ExecutionModel::State::requestUrl(const std::vector<std::string>& url,
                                       const std::vector<std::string>& parameter,
                                       const vrml::Node* anchor) {
  if (url.empty()) return;
  const auto from = anchor != nullptr ? nodeScenes.find(anchor) : nodeScenes.end();
  const std::string inlineUrl = from != nodeScenes.end() ? from->second->url : std::string();
  const std::string& base = anchor != nullptr ? anchor->urlBaseOr(inlineUrl) : inlineUrl;
  if (!base.empty() && !url.front().starts_with("#")) {
    // Written in another file than the world's: its URLs are that file's, under its rules.
    std::vector<std::string> own;
    for (const std::string& u : url) {
      if (u.starts_with("#")) {  // a Viewpoint of the world: as written
        own.push_back(u);
        continue;
      }
      std::string error;
      const std::string resolved = base::resolveUrl(base, u);
      if (base::mayReference(base, resolved, error))
        own.push_back(resolved);
      else
        model.diagnostics_.warning(anchor->location, "link not followed: " + error);
    }
    if (!own.empty() && model.options_.loadUrl) model.options_.loadUrl(own, parameter);
    return;
  }
  if (url.front().starts_with("#")) {
    // 6.2: "#Name" binds the Viewpoint DEFed Name of this world (file order first).
    const std::string name = url.front().substr(1);
    NodeState* target = nullptr;
    for (NodeState* c : candidates[static_cast<std::size_t>(BindableKind::Viewpoint)])
      if (c->node->defName == name) {
        target = c;
        break;
      }
    if (target == nullptr)
      for (auto& [node, ns] : nodes)
        if (ns->role == NodeRole::bindable && ns->bindable == BindableKind::Viewpoint &&
            node->defName == name) {
          target = ns.get();
          break;
        }
    if (target == nullptr) {
      model.diagnostics_.warning({},
                                 "no Viewpoint named '" + name + "' for the link " + url.front());
      return;
    }
    bind(*target, true);
    return;
  }
  if (model.options_.loadUrl) model.options_.loadUrl(url, parameter);
}

}  // namespace gs::runtime
