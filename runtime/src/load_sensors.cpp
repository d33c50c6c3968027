// The X3D LoadSensor (X3D 4.0 clause 9.4.3, Networking component level 3): it watches the
// X3DUrlObject nodes of its `children` field (X3D 3's `watchList`) and reports when they
// have all loaded (progress 1, isLoaded TRUE, loadTime) or when one failed or its timeOut
// passed first (isLoaded FALSE). The runtime loads nothing itself: loaders report each url
// object's state through ExecutionModel::setUrlObjectState (docs/runtime.md, "LoadSensor").
//
// A watch starts when the world (or the Inline world holding the sensor) is taken in, when
// enabled becomes TRUE and when a new children list is set. While it runs, isActive is
// TRUE and progress is the fraction of the watched nodes that have loaded. Nodes in
// children that are not X3DUrlObjects are ignored; X3DUrlObjects whose loading GhostSpace
// does not report (anything but Inline, ImageTexture, ImageTexture3D, MovieTexture and
// AudioClip: Anchor, Script, shaders ...) count as loaded unless a report came for them.
// A watch with nothing to watch sends nothing.
#include "execution_state.hpp"

#include <algorithm>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

FieldValue loadBool(bool b) {
  return FieldValue::make<FieldType::SFBool>(b);
}

/// Whether a loader of GhostSpace reports the loading of `node` (setUrlObjectState); the
/// other url objects count as loaded until a report says otherwise.
bool loadReported(const vrml::Node& node) {
  using vrml::NodeTypeId;
  switch (node.typeId()) {
    case NodeTypeId::Inline:
    case NodeTypeId::ImageTexture:
    case NodeTypeId::ImageTexture3D:
    case NodeTypeId::MovieTexture:
    case NodeTypeId::AudioClip:
      return true;
    default:
      return false;
  }
}

bool loadSensorEnabled(const NodeState& ns) {
  const int f = ns.load->enabled;
  if (f < 0) return true;
  const FieldValue& v = ns.node->fieldAt(static_cast<std::size_t>(f));
  return v.type() != FieldType::SFBool || v.get<FieldType::SFBool>();
}

double loadSensorTimeOut(const NodeState& ns) {
  const int f = ns.load->timeOut;
  if (f < 0) return 0.0;
  const FieldValue& v = ns.node->fieldAt(static_cast<std::size_t>(f));
  return v.type() == FieldType::SFTime ? v.get<FieldType::SFTime>() : 0.0;
}

}  // namespace

bool ExecutionModel::State::classifyLoadSensor(NodeState& ns) {
  if (ns.node->typeId() != vrml::NodeTypeId::LoadSensor) return false;
  ns.role = NodeRole::loadSensor;
  ns.load = std::make_unique<LoadSensorState>();
  LoadSensorState& l = *ns.load;
  const vrml::NodeType& type = ns.node->type();
  l.enabled = type.findExact("enabled");
  l.timeOut = type.findExact("timeOut");
  l.children = type.findExact("children");
  l.isActive = type.findExact("isActive");
  l.isLoaded = type.findExact("isLoaded");
  l.loadTime = type.findExact("loadTime");
  l.progress = type.findExact("progress");
  loadSensors.push_back(&ns);
  newLoadSensors.push_back(&ns);
  return true;
}

void ExecutionModel::State::startNewLoadSensors() {
  if (newLoadSensors.empty()) return;
  std::vector<NodeState*> batch;
  batch.swap(newLoadSensors);
  for (NodeState* ns : batch) startLoadWatch(*ns);
}

void ExecutionModel::State::startLoadWatch(NodeState& ns) {
  if (!loadSensorEnabled(ns)) return;
  LoadSensorState& l = *ns.load;
  l.watching = true;
  l.started = model.now();
  evaluateLoadSensor(ns);
}

void ExecutionModel::State::evaluateLoadSensors() {
  for (NodeState* ns : loadSensors)
    if (ns->load->watching) evaluateLoadSensor(*ns);
}

void ExecutionModel::State::evaluateLoadSensor(NodeState& ns) {
  LoadSensorState& l = *ns.load;
  if (!l.watching) return;
  std::size_t watched = 0, loaded = 0, failed = 0;
  if (l.children >= 0) {
    const FieldValue& v = ns.node->fieldAt(static_cast<std::size_t>(l.children));
    if (v.type() == FieldType::MFNode)
      for (const vrml::NodePtr& c : v.get<FieldType::MFNode>()) {
        if (!c || !c->type().is(vrml::AbstractType::X3DUrlObject)) continue;
        ++watched;
        // What its loader reported; before any report, loading when a loader will report.
        const auto it = urlStates.find(c.get());
        const UrlLoadState state = it != urlStates.end() ? it->second
                                   : loadReported(*c)    ? UrlLoadState::loading
                                                         : UrlLoadState::loaded;
        if (state == UrlLoadState::loaded) ++loaded;
        if (state == UrlLoadState::failed) ++failed;
      }
  }
  const auto end = [&](bool success) {
    l.watching = false;
    if (success) {
      if (l.progressSent != 1.0f)
        emitOwn(ns, l.progress, FieldValue::make<FieldType::SFFloat>(1.0f));
      l.progressSent = 1.0f;
      emitOwn(ns, l.isLoaded, loadBool(true));
      emitOwn(ns, l.loadTime, FieldValue::make<FieldType::SFTime>(model.now()));
    } else {
      emitOwn(ns, l.isLoaded, loadBool(false));
    }
    if (l.active) {
      l.active = false;
      emitOwn(ns, l.isActive, loadBool(false));
    }
    l.progressSent = -1.0f;  // the next watch starts with progress 0
  };
  if (watched == 0) {  // nothing to watch: nothing to report (an active watch just ends)
    l.watching = false;
    l.progressSent = -1.0f;
    if (l.active) {
      l.active = false;
      emitOwn(ns, l.isActive, loadBool(false));
    }
    return;
  }
  if (loaded == watched) return end(true);
  if (failed > 0) return end(false);
  const double timeOut = loadSensorTimeOut(ns);
  if (timeOut > 0.0 && model.now() >= l.started + timeOut) return end(false);
  if (!l.active) {
    l.active = true;
    emitOwn(ns, l.isActive, loadBool(true));
  }
  const float fraction = static_cast<float>(loaded) / static_cast<float>(watched);
  if (fraction != l.progressSent) {
    l.progressSent = fraction;
    emitOwn(ns, l.progress, FieldValue::make<FieldType::SFFloat>(fraction));
  }
}

void ExecutionModel::State::deliverLoadSensor(NodeState& ns, int field, FieldValue value) {
  emitOwn(ns, field, std::move(value));
  LoadSensorState& l = *ns.load;
  if (field == l.enabled) {
    if (loadSensorEnabled(ns)) {
      if (!l.watching) startLoadWatch(ns);
      return;
    }
    l.watching = false;
    l.progressSent = -1.0f;
    if (l.active) {
      l.active = false;
      emitOwn(ns, l.isActive, loadBool(false));
    }
  } else if (field == l.children) {
    startLoadWatch(ns);  // a new list: a new watch (isActive stays TRUE when it was)
  } else if (field == l.timeOut) {
    evaluateLoadSensor(ns);  // a shorter timeOut may have passed already
  }
}

void ExecutionModel::setUrlObjectState(const vrml::Node& node, UrlLoadState state) {
  const auto [it, inserted] = s_->urlStates.try_emplace(&node, state);
  if (!inserted) {
    if (it->second == state) return;
    it->second = state;
  } else if (state == UrlLoadState::loading) {
    return;  // what an unreported node is taken to be already
  }
  const bool watching = std::any_of(s_->loadSensors.begin(), s_->loadSensors.end(),
                                    [](const NodeState* ns) { return ns->load->watching; });
  if (!watching) return;
  ++s_->stamp;
  ++stats_.cascades;
  s_->eventsThisCascade = 0;
  s_->cascadeOverflow = false;
  s_->evaluateLoadSensors();
  s_->runCascade();
  s_->evaluateSkins();
}

UrlLoadState ExecutionModel::urlObjectState(const vrml::Node& node) const {
  const auto it = s_->urlStates.find(&node);
  return it == s_->urlStates.end() ? UrlLoadState::loading : it->second;
}

}  // namespace gs::runtime
