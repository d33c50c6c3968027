// What nodes do with the events they receive: exposedFields (4.10.3 / 5.1), TimeSensor
// (6.50), the interpolators (4.6.8), the bindable stacks (4.6.10), grouping nodes'
// addChildren / removeChildren (6.21 Group, 6.52 Transform ...), Scripts (4.12).
#include "execution_state.hpp"

#include <algorithm>
#include <optional>
#include <string_view>
#include <unordered_set>
#include <vector>

namespace gs::runtime {

using vrml::AccessType;
using vrml::FieldType;

namespace {

/// The interpolator kind of an interpolator node (VRML97 4.6.8, 6.x; X3D 4.0 clause 19,
/// EaseInEaseOut included though X3D 4.0 makes it a plain X3DChildNode), or nothing.
std::optional<InterpolatorKind> interpolatorKind(vrml::NodeTypeId id) {
  using vrml::NodeTypeId;
  switch (id) {
    case NodeTypeId::ColorInterpolator:
      return InterpolatorKind::Color;
    case NodeTypeId::CoordinateInterpolator:
      return InterpolatorKind::Coordinate;
    case NodeTypeId::NormalInterpolator:
      return InterpolatorKind::Normal;
    case NodeTypeId::OrientationInterpolator:
      return InterpolatorKind::Orientation;
    case NodeTypeId::PositionInterpolator:
      return InterpolatorKind::Position;
    case NodeTypeId::ScalarInterpolator:
      return InterpolatorKind::Scalar;
    case NodeTypeId::CoordinateInterpolator2D:
      return InterpolatorKind::Coordinate2D;
    case NodeTypeId::PositionInterpolator2D:
      return InterpolatorKind::Position2D;
    case NodeTypeId::EaseInEaseOut:
      return InterpolatorKind::EaseInEaseOut;
    case NodeTypeId::SplinePositionInterpolator:
      return InterpolatorKind::SplinePosition;
    case NodeTypeId::SplinePositionInterpolator2D:
      return InterpolatorKind::SplinePosition2D;
    case NodeTypeId::SplineScalarInterpolator:
      return InterpolatorKind::SplineScalar;
    case NodeTypeId::SquadOrientationInterpolator:
      return InterpolatorKind::SquadOrientation;
    default:
      return std::nullopt;
  }
}

/// The stack of an X3DBindableNode of VRML97 (4.6.10), or nothing.
std::optional<BindableKind> bindableKind(vrml::NodeTypeId id) {
  using vrml::NodeTypeId;
  switch (id) {
    case NodeTypeId::Viewpoint:
    case NodeTypeId::OrthoViewpoint:  // X3D: one viewpoint stack (clause 23.2.1)
    case NodeTypeId::GeoViewpoint:
      return BindableKind::Viewpoint;
    case NodeTypeId::NavigationInfo:
      return BindableKind::NavigationInfo;
    case NodeTypeId::Background:
    case NodeTypeId::TextureBackground:
      return BindableKind::Background;
    case NodeTypeId::Fog:
      return BindableKind::Fog;
    default:
      return std::nullopt;
  }
}

template <FieldType T, class V>
V value(const vrml::Node& n, int field, V fallback) {
  if (field < 0) return fallback;
  const vrml::FieldValue& f = n.fieldAt(static_cast<std::size_t>(field));
  return f.type() == T ? f.get<T>() : fallback;
}

/// An SFBool field of `n` (FALSE when absent).
bool boolField(const vrml::Node& n, int field) {
  return value<FieldType::SFBool>(n, field, false);
}

TimeFields timeFieldsOf(const vrml::Node& n, const TimeSensorFields& f) {
  TimeFields t;
  t.cycleInterval = value<FieldType::SFTime>(n, f.cycleInterval, 1.0);
  t.enabled = value<FieldType::SFBool>(n, f.enabled, true);
  t.loop = value<FieldType::SFBool>(n, f.loop, false);
  t.startTime = value<FieldType::SFTime>(n, f.startTime, 0.0);
  t.stopTime = value<FieldType::SFTime>(n, f.stopTime, 0.0);
  return t;
}

}  // namespace

void ExecutionModel::State::classify(NodeState& ns) {
  const vrml::NodeType& type = ns.node->type();
  auto idx = [&](std::string_view name) { return type.findExact(name); };
  // The world a Script or an Anchor of an Inline's world came from: its URLs are that
  // world's (EsScript::resolveOwnUrl, requestUrl).
  if (reachingInline != nullptr && (type.script || ns.node->typeId() == vrml::NodeTypeId::Anchor))
    nodeScenes[ns.node] = reachingInline;
  if (type.script) {
    ns.role = NodeRole::script;
    if (model.options_.scripts && scriptFilesArriving(*ns.node)) {
      arrivingScripts.push_back(&ns);  // made when its file arrives (startArrivedScripts)
      return;
    }
    if (model.options_.scripts) {
      ns.script = model.options_.scripts(*ns.node, model, model.options_.scriptLimits);
    } else {
      model.diagnostics_.warning(ns.node->location,
                                 "Script not run: this build runs no scripting language");
    }
    newScripts.push_back(&ns);
    return;
  }
  using vrml::AbstractType;
  using vrml::NodeTypeId;
  const NodeTypeId id = type.id();
  if (classifyMedia(ns)) return;
  if (classifyEventUtility(ns)) return;
  if (classifyFollower(ns)) return;
  if (classifySkin(ns)) return;
  if (classifyParticleSystem(ns)) return;
  if (classifyPickSensor(ns)) return;
  if (classifyRigidBodyPhysics(ns)) return;
  if (classifyDis(ns)) return;
  if (classifyHumanoid(ns)) return;
  if (classifyKeySensor(ns)) return;
  if (classifyLoadSensor(ns)) return;
  if (classifyNurbsInterpolator(ns)) return;
  if (classifyGeoInterpolator(ns)) return;
  if (id == NodeTypeId::TimeSensor) {
    ns.role = NodeRole::timeSensor;
    TimeSensorFields& f = ns.timeFields;
    f.cycleInterval = idx("cycleInterval");
    f.enabled = idx("enabled");
    f.loop = idx("loop");
    f.startTime = idx("startTime");
    f.stopTime = idx("stopTime");
    f.cycleTime = idx("cycleTime");
    f.fraction = idx("fraction_changed");
    f.isActive = idx("isActive");
    f.time = idx("time");
    timeSensors.push_back(&ns);
    return;
  }
  if (const auto kind = interpolatorKind(id)) {
    const bool ease = *kind == InterpolatorKind::EaseInEaseOut;
    ns.role = NodeRole::interpolator;
    ns.interpolator = *kind;
    ns.setFraction = idx("set_fraction");
    ns.key = idx("key");
    ns.keyValue = idx(ease ? "easeInEaseOut" : "keyValue");
    ns.valueChanged = idx(ease ? "modifiedFraction_changed" : "value_changed");
    ns.keyVelocity = idx("keyVelocity");  // the splines (X3D 4.0 19.4.10-19.4.12)
    ns.closed = idx("closed");
    ns.normalizeVelocity = idx("normalizeVelocity");
    return;
  }
  if (type.is(AbstractType::X3DInterpolatorNode)) return;
  if (type.is(AbstractType::X3DBindableNode)) {
    if (const auto kind = bindableKind(id)) {
      ns.role = NodeRole::bindable;
      ns.bindable = *kind;
      ns.setBind = idx("set_bind");
      ns.isBound = idx("isBound");
      ns.bindTime = idx("bindTime");
    }
    return;
  }
  if (id == NodeTypeId::ProximitySensor || id == NodeTypeId::VisibilitySensor ||
      id == NodeTypeId::TransformSensor || id == NodeTypeId::GeoProximitySensor) {
    ns.role = id == NodeTypeId::ProximitySensor || id == NodeTypeId::GeoProximitySensor
                  ? NodeRole::proximity
              : id == NodeTypeId::VisibilitySensor ? NodeRole::visibility
                                                   : NodeRole::transformSensor;
    if (ns.role == NodeRole::transformSensor) transformSensors.push_back(&ns);
    ++environmentSensors;
    return;
  }
  // Every grouping node (X3DGroupingNode: Anchor, Billboard, Collision, Group, Transform,
  // OutlineGroup ...) takes addChildren / removeChildren. VRML97's Switch and LOD are
  // X3DGroupingNodes in X3D but have no such events in VRML97 (index -1: nothing to do).
  if (type.is(AbstractType::X3DGroupingNode)) {
    ns.role = NodeRole::grouping;
    ns.addChildren = idx("addChildren");
    ns.removeChildren = idx("removeChildren");
    ns.children = idx("children");
    return;
  }
}

void ExecutionModel::State::report(vrml::Severity severity, const vrml::Node& node,
                                   const std::string& message) {
  model.diagnostics_.items.push_back(
      {severity, node.location,
       node.typeName() + (node.defName.empty() ? "" : " " + node.defName) + ": " + message});
}

void ExecutionModel::State::evaluateTimeSensor(NodeState& ns) {
  const TimeSensorFields& f = ns.timeFields;
  // The time fields change only through setField (which bumps the revision), so they are
  // read again only after a write: most frames only the sensor's own outputs changed.
  if (ns.node->revision() != ns.timeFieldsRevision) ns.timeFieldsCache = timeFieldsOf(*ns.node, f);
  const TimeFields fields = ns.timeFieldsCache;
  const double now = model.now();
  const TimeStep step = evaluateTime(ns.time, fields, now);
  using vrml::FieldValue;
  // Order of 6.50: isActive TRUE, cycleTime, fraction_changed, time; isActive FALSE last.
  if (step.activated) emitOwn(ns, f.isActive, FieldValue::make<FieldType::SFBool>(true));
  if (step.newCycle) emitOwn(ns, f.cycleTime, FieldValue::make<FieldType::SFTime>(step.cycleTime));
  if (step.output) {
    emitOwn(ns, f.fraction,
            FieldValue::make<FieldType::SFFloat>(static_cast<float>(step.fraction)));
    emitOwn(ns, f.time, FieldValue::make<FieldType::SFTime>(now));
  }
  if (step.deactivated) emitOwn(ns, f.isActive, FieldValue::make<FieldType::SFBool>(false));
  // Only outputs were written since the fields were read: the cache stays valid.
  ns.timeFieldsRevision = ns.node->revision();
}

void ExecutionModel::State::bind(NodeState& ns, bool on) {
  auto& stack = stacks[static_cast<std::size_t>(ns.bindable)];
  using vrml::FieldValue;
  const auto sendBound = [&](NodeState& n, bool bound) {
    emitOwn(n, n.isBound, FieldValue::make<FieldType::SFBool>(bound));
    if (bound) emitOwn(n, n.bindTime, FieldValue::make<FieldType::SFTime>(model.now()));
    // X3D 4.0 clause 23.3.1: a viewpoint's own NavigationInfo (its `navigationInfo`) gets
    // set_bind TRUE when the viewpoint is bound and FALSE when it is unbound (X_ITE 15
    // routes isBound to it).
    if (n.bindable == BindableKind::Viewpoint)
      if (const vrml::FieldValue* f = n.node->field("navigationInfo");
          f != nullptr && f->type() == FieldType::SFNode) {
        const vrml::NodePtr& nav = f->get<FieldType::SFNode>();
        if (nav && !nav->unresolved && nav->typeId() == vrml::NodeTypeId::NavigationInfo) {
          NodeState& navState = reach(nav, false);
          if (navState.role == NodeRole::bindable && navState.setBind >= 0)
            queue.push_back(
                {&navState, navState.setBind, FieldValue::make<FieldType::SFBool>(bound)});
        }
      }
  };
  const auto pos = std::find(stack.begin(), stack.end(), &ns);
  if (on) {
    if (!stack.empty() && stack.back() == &ns) return;  // already bound: no events
    if (!stack.empty()) sendBound(*stack.back(), false);
    if (pos != stack.end()) stack.erase(pos);
    stack.push_back(&ns);
    sendBound(ns, true);
  } else {
    if (pos == stack.end()) return;
    const bool wasTop = (pos + 1 == stack.end());
    stack.erase(pos);
    if (!wasTop) return;
    sendBound(ns, false);
    if (!stack.empty()) sendBound(*stack.back(), true);
  }
  ++model.bindingRevision_;
}

void ExecutionModel::State::bindFirstCandidates() {
  for (std::size_t k = 0; k < kBindableKindCount; ++k)
    if (stacks[k].empty() && !candidates[k].empty()) bind(*candidates[k].front(), true);
}

void ExecutionModel::State::rebindFrom(const std::vector<vrml::NodePtr>& roots) {
  for (auto& c : candidates) c.clear();
  // Depth first in file order, with a list rather than recursion; not into Inlines, whose
  // worlds bind nothing (4.6.10).
  std::unordered_set<const vrml::Node*> seen;
  std::vector<vrml::Node*> pending;
  for (auto it = roots.rbegin(); it != roots.rend(); ++it)
    if (*it) pending.push_back(it->get());
  while (!pending.empty()) {
    vrml::Node* n = pending.back();
    pending.pop_back();
    if (!seen.insert(n).second) continue;
    NodeState& ns = reach(*n, false);
    if (ns.role == NodeRole::bindable)
      candidates[static_cast<std::size_t>(ns.bindable)].push_back(&ns);
    const std::size_t before = pending.size();
    if (n->typeId() == vrml::NodeTypeId::LayerSet) {  // its active layer's only (35.4.2)
      const int active = n->get<FieldType::SFInt32>("activeLayer", 0);
      const vrml::FieldValue* layers = n->field("layers");
      if (layers != nullptr && layers->type() == FieldType::MFNode) {
        const auto& list = layers->get<FieldType::MFNode>();
        if (active >= 1 && static_cast<std::size_t>(active) <= list.size() && list[active - 1u])
          pending.push_back(list[active - 1u].get());
      }
      continue;
    }
    pushChildNodes(*n, pending);
    // A viewpoint's own NavigationInfo (X3D 4.0 clause 23.3.1) is bound with it, not as a
    // candidate of the graph (X_ITE 15 finds bindables in the graph only).
    if (ns.role == NodeRole::bindable && ns.bindable == BindableKind::Viewpoint)
      if (const vrml::FieldValue* f = n->field("navigationInfo");
          f != nullptr && f->type() == FieldType::SFNode && f->get<FieldType::SFNode>()) {
        const vrml::Node* own = f->get<FieldType::SFNode>().get();
        pending.erase(
            std::remove(pending.begin() + static_cast<std::ptrdiff_t>(before), pending.end(), own),
            pending.end());
      }
    std::reverse(pending.begin() + static_cast<std::ptrdiff_t>(before), pending.end());
  }
  for (std::size_t k = 0; k < kBindableKindCount; ++k) {
    auto& stack = stacks[k];
    if (stack.empty()) continue;
    NodeState* top = stack.back();
    if (!candidates[k].empty() && candidates[k].front() == top) {  // stays bound
      stack.assign(1, top);
      continue;
    }
    emitOwn(*top, top->isBound, vrml::FieldValue::make<FieldType::SFBool>(false));
    stack.clear();
    ++model.bindingRevision_;
  }
  bindFirstCandidates();
}

namespace {

/// The first element of an interpolator's keyValue (its MF types), else null.
const void* elementsOf(const vrml::FieldValue& v) {
  switch (v.type()) {
    case FieldType::MFFloat:
      return v.get<FieldType::MFFloat>().data();
    case FieldType::MFVec3f:
      return v.get<FieldType::MFVec3f>().data();
    case FieldType::MFColor:
      return v.get<FieldType::MFColor>().data();
    case FieldType::MFRotation:
      return v.get<FieldType::MFRotation>().data();
    case FieldType::MFVec2f:
      return v.get<FieldType::MFVec2f>().data();
    case FieldType::MFDouble:
      return v.get<FieldType::MFDouble>().data();
    case FieldType::MFVec3d:
      return v.get<FieldType::MFVec3d>().data();
    default:
      return nullptr;
  }
}

}  // namespace

void ExecutionModel::State::deliver(NodeState& ns, int field, vrml::FieldValue value) {
  vrml::Node& node = *ns.node;
  if (field < 0 || static_cast<std::size_t>(field) >= node.fieldCount()) return;
  const vrml::FieldSpec& spec = node.type().fields[static_cast<std::size_t>(field)];
  if (spec.type != value.type()) return;
  // The graph stays acyclic (X3D 4.0 clause 4.4.2.2): a value that holds the node itself
  // or one of its ancestors is refused (graph_cycles.cpp), said once per node.
  if ((spec.type == FieldType::SFNode || spec.type == FieldType::MFNode) &&
      !spec.name.ends_with("removeChildren") && wouldContainItself(node, field, value)) {
    if (!ns.cycleReported)
      report(vrml::Severity::error, node,
             spec.name +
                 ": the value holds this node or a node above it (a node cannot be among its "
                 "own descendants): the event is ignored");
    ns.cycleReported = true;
    return;
  }
  switch (ns.role) {
    case NodeRole::timeSensor: {
      const TimeSensorFields& f = ns.timeFields;
      const TimeFields now = timeFieldsOf(node, f);
      // 6.50: startTime and cycleInterval are ignored while active; so is a stopTime
      // at or before startTime.
      if (ns.time.active && (field == f.startTime || field == f.cycleInterval)) return;
      if (field == f.stopTime && ignoresStopTime(ns.time, now, value.get<FieldType::SFTime>()))
        return;
      emitOwn(ns, field, std::move(value));
      evaluateTimeSensor(ns);
      return;
    }
    case NodeRole::interpolator:
      if (field == ns.setFraction) {
        if (ns.key < 0 || ns.keyValue < 0 || ns.valueChanged < 0) return;
        std::string problem;
        const auto& key = node.fieldAt(static_cast<std::size_t>(ns.key)).get<FieldType::MFFloat>();
        const vrml::FieldValue& keyValue = node.fieldAt(static_cast<std::size_t>(ns.keyValue));
        const float fraction = value.get<FieldType::SFFloat>();
        ns.keysHint = key.data();
        ns.keyValuesHint = elementsOf(keyValue);
        std::optional<vrml::FieldValue> out;
        if (nonLinearInterpolator(ns.interpolator)) {
          SplineOptions options;
          if (ns.keyVelocity >= 0)
            options.keyVelocity = &node.fieldAt(static_cast<std::size_t>(ns.keyVelocity));
          options.closed = boolField(node, ns.closed);
          options.normalizeVelocity = boolField(node, ns.normalizeVelocity);
          out = interpolateX3d(ns.interpolator, key, keyValue, options, fraction, problem);
        } else {
          out = interpolate(ns.interpolator, key, keyValue, fraction, problem);
        }
        if (!out) {
          if (!ns.problemReported) report(vrml::Severity::error, node, problem + "; no output");
          ns.problemReported = true;
          return;
        }
        emitOwn(ns, ns.valueChanged, std::move(*out));
        return;
      }
      break;
    case NodeRole::bindable:
      if (field == ns.setBind) {
        bind(ns, value.get<FieldType::SFBool>());
        return;
      }
      break;
    case NodeRole::grouping:
      if ((field == ns.addChildren || field == ns.removeChildren) && ns.children >= 0) {
        auto children =
            node.fieldAt(static_cast<std::size_t>(ns.children)).get<FieldType::MFNode>();
        for (const vrml::NodePtr& c : value.get<FieldType::MFNode>()) {
          if (!c) continue;
          const auto it = std::find(children.begin(), children.end(), c);
          if (field == ns.addChildren && it == children.end()) {
            children.push_back(c);
            reach(c, false);
          } else if (field == ns.removeChildren && it != children.end()) {
            children.erase(it);
          }
        }
        emitOwn(ns, ns.children, vrml::FieldValue::make<FieldType::MFNode>(std::move(children)));
        return;
      }
      break;
    case NodeRole::script:
      node.setField(static_cast<std::size_t>(field), value);
      if (ns.script && !ns.script->stopped()) {
        ns.scriptHadEvents = true;
        ns.script->eventIn(field, value, model.now());
      }
      return;
    case NodeRole::media:
      deliverMedia(ns, field, std::move(value));
      return;
    case NodeRole::eventUtility:
      if (field == ns.utility->input || field == ns.utility->next ||
          field == ns.utility->previous) {
        deliverEventUtility(ns, field, std::move(value));
        return;
      }
      break;  // toggle, integerKey, key, keyValue: exposedFields
    case NodeRole::follower:
      if (field == ns.follower->setDestination || field == ns.follower->setValue) {
        deliverFollower(ns, field, std::move(value));
        return;
      }
      break;  // tau, tolerance: exposedFields
    case NodeRole::keySensor:
      if (field == ns.keys->enabled) {
        deliverKeySensor(ns, field, std::move(value));
        return;
      }
      break;  // description, deletionAllowed: exposedFields
    case NodeRole::loadSensor:
      if (field == ns.load->enabled || field == ns.load->timeOut || field == ns.load->children) {
        deliverLoadSensor(ns, field, std::move(value));
        return;
      }
      break;  // description, metadata: exposedFields
    case NodeRole::nurbsInterpolator:
      if (field == ns.setFraction) {
        deliverNurbsInterpolator(ns, std::move(value));
        return;
      }
      break;  // order, knot, weight, controlPoint: exposedFields
    case NodeRole::geoInterpolator:
      if (field == ns.setFraction) {
        deliverGeoInterpolator(ns, value);
        return;
      }
      break;  // key, keyValue: exposedFields
    case NodeRole::plain:
      if (node.typeId() == vrml::NodeTypeId::HAnimMotion &&
          (spec.name == "next" || spec.name == "previous")) {
        if (value.get<FieldType::SFBool>()) stepHAnimMotion(ns, spec.name == "next" ? 1 : -1);
        return;
      }
      if (node.typeId() == vrml::NodeTypeId::HAnimMotion && spec.name == "enabled") {
        emitOwn(ns, field, std::move(value));
        enableHAnimMotion(ns);
        return;
      }
      break;
    case NodeRole::transformSensor:
    case NodeRole::proximity:
    case NodeRole::visibility:
      break;
  }
  if (spec.access == AccessType::exposedField) {
    emitOwn(ns, field, std::move(value));
    return;
  }
  if (spec.access == AccessType::eventIn && spec.name.starts_with("set_")) {
    // set_coordIndex and the like write the field of the same name (6.23 ...).
    const int target = node.type().findExact(std::string_view(spec.name).substr(4));
    if (target >= 0 && node.type().fields[static_cast<std::size_t>(target)].type == value.type())
      node.setField(static_cast<std::size_t>(target), std::move(value));
  }
}

namespace {

/// Every node reachable from `from` through SFNode and MFNode fields (PROTO instances'
/// interfaces included), depth first without recursion.
std::unordered_set<const vrml::Node*> reachableFrom(const std::vector<vrml::NodePtr>& from) {
  std::unordered_set<const vrml::Node*> seen;
  std::vector<vrml::Node*> pending;
  for (const vrml::NodePtr& n : from)
    if (n) pending.push_back(n.get());
  while (!pending.empty()) {
    const vrml::Node* n = pending.back();
    pending.pop_back();
    if (!seen.insert(n).second) continue;
    pushChildNodes(*n, pending);
  }
  return seen;
}

}  // namespace

void ExecutionModel::State::unloadReplacedWorld() {
  std::vector<vrml::NodePtr> old;
  old.swap(replacedNodes);
  std::unordered_set<const vrml::Node*> gone = reachableFrom(old);
  if (scene)
    for (const vrml::Node* n : reachableFrom(scene->rootNodes)) gone.erase(n);
  if (gone.empty()) return;
  // The worlds of the Inline nodes that go, and of the Inlines inside those, go too,
  // unless an Inline that stays shows the same world.
  for (bool more = true; more;) {
    more = false;
    for (const auto& [inlineNode, world] : inlineWorlds) {
      if (!gone.contains(inlineNode) || unloadedInlineScenes.contains(world)) continue;
      const bool shownElsewhere = std::any_of(
          inlineWorlds.begin(), inlineWorlds.end(),
          [&, w = world](const auto& e) { return e.second == w && !gone.contains(e.first); });
      if (shownElsewhere) continue;
      std::vector<vrml::NodePtr> nodesOfWorld = world->rootNodes;
      nodesOfWorld.insert(nodesOfWorld.end(), world->hiddenNodes.begin(), world->hiddenNodes.end());
      gone.merge(reachableFrom(nodesOfWorld));
      unloadedInlineScenes.insert(world);
      more = true;
    }
  }
  for (const vrml::Scene* world : unloadedInlineScenes) inlineSceneSet.erase(world);
  std::erase_if(inlineScenes, [&](const InlineCursor& c) {
    return unloadedInlineScenes.contains(c.scene.get());
  });
  const auto unloaded = [&](const NodeState* ns) { return gone.count(ns->node) != 0; };
  for (NodeState* s : scripts)
    if (unloaded(s) && s->script && !s->script->stopped()) s->script->shutdown(model.now());
  runCascade();  // what the shutdown() calls sent
  for (auto* list :
       {&timeSensors, &scripts, &mediaNodes, &skins, &followers, &transformSensors, &keySensors,
        &loadSensors, &particleSystems, &pickSensors, &rigidBodyCollections, &collisionSensors,
        &activeEnvironmentSensors, &newRigidBodyCollections, &espduTransforms, &newLoadSensors,
        &newScripts, &arrivingScripts})
    std::erase_if(*list, unloaded);
  for (const vrml::Node* n : gone) {
    nodeScenes.erase(n);
    if (const auto it = nodes.find(n); it != nodes.end()) it->second->unloaded = true;
  }
}

}  // namespace gs::runtime
