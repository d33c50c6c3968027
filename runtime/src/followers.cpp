// The X3D Followers component (ISO/IEC 19775-1:2023 clause 39): the dampers
// (X3DDamperNode: ColorDamper, CoordinateDamper, OrientationDamper, PositionDamper,
// PositionDamper2D, ScalarDamper, TexCoordDamper2D) and the chasers (X3DChaserNode: the
// same seven as Chasers). A follower's value moves towards its destination on the
// runtime's clock, so `--time T` frames it exactly:
// - A damper is `order` first-order low-pass filters in a cascade (39.3.2): at each step
//   of dt seconds every stage moves towards the one before it by 1 - exp(-dt / tau), the
//   first stage towards the destination; it stops (isActive FALSE) when every stage is
//   within `tolerance` of the destination (-1: 0.001), tau 0 or order 0 jump at once.
// - A chaser reaches a new destination in exactly `duration` seconds (39.3.1): its value is
//   the sum of the step responses of every destination change, each the smooth step
//   (1 - cos(pi t / duration)) / 2, so a destination changed while moving blends in.
// Values are handled as flat lists of numbers; rotations as unit quaternions (component-wise,
// renormalized, each destination on the same hemisphere as the one before).
#include "execution_state.hpp"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

/// At most this many destination changes are blended at once, holding at most this many
/// numbers together (a coordinate chaser fed long lists); older ones complete at once.
constexpr std::size_t kMaxChaserSteps = 256;
constexpr std::size_t kMaxChaserNumbers = std::size_t{1} << 22;
/// The tolerance a damper uses when its field says -1 (the browser's choice).
constexpr double kDefaultTolerance = 1e-3;
constexpr double kPi = 3.14159265358979323846;

using Values = std::vector<double>;

bool followable(FieldType t) {
  switch (t) {
    case FieldType::SFFloat:
    case FieldType::SFVec2f:
    case FieldType::SFVec3f:
    case FieldType::SFColor:
    case FieldType::SFRotation:
    case FieldType::MFVec2f:
    case FieldType::MFVec3f:
      return true;
    default:
      return false;
  }
}

template <class V, int N>
void append(Values& out, const V& v) {
  for (int i = 0; i < N; ++i) out.push_back(static_cast<double>(v[i]));
}

/// The numbers of `v` (of a followable type); a rotation as a unit quaternion x, y, z, w.
Values flatten(const FieldValue& v) {
  Values out;
  switch (v.type()) {
    case FieldType::SFFloat:
      out.push_back(v.get<FieldType::SFFloat>());
      break;
    case FieldType::SFVec2f:
      append<glm::vec2, 2>(out, v.get<FieldType::SFVec2f>());
      break;
    case FieldType::SFVec3f:
      append<glm::vec3, 3>(out, v.get<FieldType::SFVec3f>());
      break;
    case FieldType::SFColor:
      append<glm::vec3, 3>(out, v.get<FieldType::SFColor>());
      break;
    case FieldType::SFRotation: {
      const vrml::Rotation r = v.get<FieldType::SFRotation>();
      const glm::vec3 axis(r.x, r.y, r.z);
      const float len = glm::length(axis);
      const glm::quat q = len > 0.0f && std::isfinite(r.w) ? glm::angleAxis(r.w, axis / len)
                                                           : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
      out = {q.x, q.y, q.z, q.w};
      break;
    }
    case FieldType::MFVec2f:
      for (const glm::vec2& p : v.get<FieldType::MFVec2f>()) append<glm::vec2, 2>(out, p);
      break;
    case FieldType::MFVec3f:
      for (const glm::vec3& p : v.get<FieldType::MFVec3f>()) append<glm::vec3, 3>(out, p);
      break;
    default:
      break;
  }
  return out;
}

/// The value of type `t` whose numbers are `n` (flatten's inverse).
FieldValue unflatten(FieldType t, const Values& n) {
  auto f = [&](std::size_t i) { return i < n.size() ? static_cast<float>(n[i]) : 0.0f; };
  switch (t) {
    case FieldType::SFFloat:
      return FieldValue::make<FieldType::SFFloat>(f(0));
    case FieldType::SFVec2f:
      return FieldValue::make<FieldType::SFVec2f>(glm::vec2(f(0), f(1)));
    case FieldType::SFVec3f:
      return FieldValue::make<FieldType::SFVec3f>(glm::vec3(f(0), f(1), f(2)));
    case FieldType::SFColor:
      return FieldValue::make<FieldType::SFColor>(glm::vec3(f(0), f(1), f(2)));
    case FieldType::SFRotation: {
      glm::quat q(f(3), f(0), f(1), f(2));
      const float len = glm::length(q);
      q = len > 0.0f ? q / len : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
      const float angle = 2.0f * std::acos(std::clamp(q.w, -1.0f, 1.0f));
      const float s = std::sqrt(std::max(0.0f, 1.0f - q.w * q.w));
      const glm::vec3 axis = s > 1e-6f ? glm::vec3(q.x, q.y, q.z) / s : glm::vec3(0, 1, 0);
      return FieldValue::make<FieldType::SFRotation>(vrml::Rotation(axis, angle));
    }
    case FieldType::MFVec2f: {
      std::vector<glm::vec2> out(n.size() / 2);
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f(2 * i), f(2 * i + 1)};
      return FieldValue::make<FieldType::MFVec2f>(std::move(out));
    }
    case FieldType::MFVec3f: {
      std::vector<glm::vec3> out(n.size() / 3);
      for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f(3 * i), f(3 * i + 1), f(3 * i + 2)};
      return FieldValue::make<FieldType::MFVec3f>(std::move(out));
    }
    default:
      return FieldValue(t);
  }
}

double distance(const Values& a, const Values& b) {
  if (a.size() != b.size()) return 1e300;
  double d = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  return d;
}

/// A rotation's quaternion turned to the hemisphere of `reference` (the short way round).
void alignQuaternion(Values& q, const Values& reference) {
  if (q.size() != 4 || reference.size() != 4) return;
  double dot = 0.0;
  for (int i = 0; i < 4; ++i) dot += q[i] * reference[i];
  if (dot < 0.0)
    for (double& c : q) c = -c;
}

/// The smooth step response of a chaser, 0 at t <= 0 and 1 at t >= 1.
double stepResponse(double t) {
  if (t <= 0.0) return 0.0;
  if (t >= 1.0) return 1.0;
  return 0.5 - 0.5 * std::cos(kPi * t);
}

double timeField(const vrml::Node& node, int i, double fallback) {
  if (i < 0) return fallback;
  const FieldValue& v = node.fieldAt(static_cast<std::size_t>(i));
  return v.type() == FieldType::SFTime ? v.get<FieldType::SFTime>() : fallback;
}

}  // namespace

bool ExecutionModel::State::classifyFollower(NodeState& ns) {
  const vrml::NodeType& type = ns.node->type();
  const bool damper = type.is(vrml::AbstractType::X3DDamperNode);
  if (!damper && !type.is(vrml::AbstractType::X3DChaserNode)) return false;
  const int valueChanged = type.findExact("value_changed");
  if (valueChanged < 0) return false;
  const FieldType t = type.fields[static_cast<std::size_t>(valueChanged)].type;
  if (!followable(t)) return false;
  ns.role = NodeRole::follower;
  ns.follower = std::make_unique<FollowerState>();
  FollowerState& f = *ns.follower;
  f.damper = damper;
  f.type = t;
  f.valueChanged = valueChanged;
  f.setDestination = type.findExact("set_destination");
  f.setValue = type.findExact("set_value");
  f.isActive = type.findExact("isActive");
  f.tau = type.findExact("tau");
  f.tolerance = type.findExact("tolerance");
  const vrml::Node& node = *ns.node;
  auto initial = [&](std::string_view name) {
    const int i = type.findExact(name);
    return i >= 0 ? flatten(node.fieldAt(static_cast<std::size_t>(i))) : Values();
  };
  Values value = initial("initialValue");
  Values destination = initial("initialDestination");
  if (t == FieldType::SFRotation) alignQuaternion(destination, value);
  f.lastTime = model.now();
  if (damper) {
    const int order = type.findExact("order");
    f.order =
        order >= 0
            ? std::clamp(node.fieldAt(static_cast<std::size_t>(order)).get<FieldType::SFInt32>(), 0,
                         5)
            : 3;
    f.buffer.assign(static_cast<std::size_t>(f.order) + 1, value);
    f.buffer[0] = destination;
  } else {
    const int duration = type.findExact("duration");
    f.duration = std::max(0.0, timeField(node, duration, 1.0));
    f.base = value;
    f.destination = destination;
    if (distance(value, destination) > 0.0) {
      Values delta(destination.size());
      for (std::size_t i = 0; i < delta.size() && i < value.size(); ++i)
        delta[i] = destination[i] - value[i];
      f.steps.push_back({model.now(), std::move(delta)});
    }
  }
  f.active = distance(value, destination) > 0.0;
  followers.push_back(&ns);
  return true;
}

void ExecutionModel::State::deliverFollower(NodeState& ns, int field, vrml::FieldValue value) {
  FollowerState& f = *ns.follower;
  Values v = flatten(value);
  const double now = model.now();
  const bool toValue = field == f.setValue;
  if (f.damper) {
    if (toValue) {
      if (f.type == FieldType::SFRotation) alignQuaternion(v, f.buffer[0]);
      for (std::size_t i = 1; i < f.buffer.size(); ++i) f.buffer[i] = v;
    } else {
      if (f.type == FieldType::SFRotation) alignQuaternion(v, f.buffer.back());
      f.buffer[0] = std::move(v);
    }
  } else {
    // The output now, then the change as one more step response from here.
    Values current = f.base;
    for (const FollowerState::Step& s : f.steps)
      for (std::size_t i = 0; i < current.size() && i < s.delta.size(); ++i)
        current[i] += s.delta[i] * stepResponse((now - s.time) / std::max(f.duration, 1e-9));
    if (toValue) {
      if (f.type == FieldType::SFRotation) alignQuaternion(v, current);
      f.base = v;
      f.steps.clear();
      if (v.size() == f.destination.size() && distance(v, f.destination) > 0.0) {
        Values delta(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) delta[i] = f.destination[i] - v[i];
        f.steps.push_back({now, std::move(delta)});
      }
    } else {
      if (f.type == FieldType::SFRotation) alignQuaternion(v, f.destination);
      if (v.size() != f.destination.size() || v.size() != f.base.size()) {
        // A coordinate list of another length: no path between them, jump.
        f.base = v;
        f.steps.clear();
      } else {
        Values delta(v.size());
        for (std::size_t i = 0; i < v.size(); ++i) delta[i] = v[i] - f.destination[i];
        while (!f.steps.empty() && (f.steps.size() >= kMaxChaserSteps ||
                                    (f.steps.size() + 1) * v.size() > kMaxChaserNumbers)) {
          for (std::size_t i = 0; i < f.base.size(); ++i) f.base[i] += f.steps.front().delta[i];
          f.steps.erase(f.steps.begin());
        }
        f.steps.push_back({now, std::move(delta)});
      }
      f.destination = std::move(v);
    }
  }
  if (toValue) emitOwn(ns, f.valueChanged, unflatten(f.type, f.damper ? f.buffer.back() : f.base));
  f.lastTime = now;
  if (!f.active) {
    f.active = true;
    f.announced = true;
    if (f.isActive >= 0) emitOwn(ns, f.isActive, FieldValue::make<FieldType::SFBool>(true));
  }
}

void ExecutionModel::State::evaluateFollower(NodeState& ns) {
  FollowerState& f = *ns.follower;
  if (!f.active) return;
  const double now = model.now();
  if (!f.announced) {
    f.announced = true;
    if (f.isActive >= 0) emitOwn(ns, f.isActive, FieldValue::make<FieldType::SFBool>(true));
  }
  bool done = false;
  Values out;
  if (f.damper) {
    const double tau = timeField(*ns.node, f.tau, 0.3);
    const double dt = now - f.lastTime;
    if (!(tau > 0.0) || f.order == 0) {
      for (Values& b : f.buffer) b = f.buffer[0];
    } else if (dt > 0.0) {
      const double alpha = std::exp(-dt / tau);
      for (std::size_t i = 1; i < f.buffer.size(); ++i) {
        Values& b = f.buffer[i];
        const Values& target = f.buffer[i - 1];
        if (b.size() != target.size()) {
          b = target;
          continue;
        }
        for (std::size_t k = 0; k < b.size(); ++k) b[k] = target[k] + (b[k] - target[k]) * alpha;
      }
    }
    double tolerance = kDefaultTolerance;
    if (f.tolerance >= 0) {
      const FieldValue& t = ns.node->fieldAt(static_cast<std::size_t>(f.tolerance));
      if (t.type() == FieldType::SFFloat && t.get<FieldType::SFFloat>() >= 0.0f)
        tolerance = t.get<FieldType::SFFloat>();
    }
    done = true;
    for (std::size_t i = 1; i < f.buffer.size(); ++i)
      done = done && distance(f.buffer[i], f.buffer[0]) <= tolerance;
    if (done)
      for (Values& b : f.buffer) b = f.buffer[0];
    out = f.buffer.back();
  } else {
    const double duration = std::max(f.duration, 1e-9);
    out = f.base;
    std::erase_if(f.steps, [&](const FollowerState::Step& s) {
      const double r = stepResponse((now - s.time) / duration);
      for (std::size_t i = 0; i < out.size() && i < s.delta.size(); ++i) {
        out[i] += s.delta[i] * r;
        if (r >= 1.0) f.base[i] += s.delta[i];  // finished: part of the base from now on
      }
      return r >= 1.0;
    });
    done = f.steps.empty();
    if (done) out = f.base = f.destination;
  }
  f.lastTime = now;
  emitOwn(ns, f.valueChanged, unflatten(f.type, out));
  if (done) {
    f.active = false;
    f.announced = false;
    if (f.isActive >= 0) emitOwn(ns, f.isActive, FieldValue::make<FieldType::SFBool>(false));
  }
}

}  // namespace gs::runtime
