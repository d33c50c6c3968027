// The route table and the event cascade (clause 4.10) and the clock's ticks (4.11). The
// ScriptContext services are in script_context.cpp; node-specific behaviour in node_roles.cpp.
#include "execution_state.hpp"

#include "base/data_url.hpp"
#include "base/url.hpp"

#include <algorithm>

#include <cmath>
#include <filesystem>

namespace gs::runtime {

using vrml::FieldType;

// ---- registration ----

NodeState& ExecutionModel::State::reach(vrml::Node& node, bool bindables) {
  auto [it, inserted] = nodes.try_emplace(&node);
  if (inserted) {
    it->second = std::make_unique<NodeState>();
  } else if (it->second->unloaded && revivingUnloaded) {
    // A node of an unloaded world that a world being taken holds again: a fresh record,
    // whose routes, and whose owner, are the old one's (a route into it names this one).
    NodeState& old = *it->second;
    NodeState fresh;
    fresh.out = std::move(old.out);
    fresh.routedFields = old.routedFields;
    fresh.keepAlive = std::move(old.keepAlive);
    old = std::move(fresh);
  } else {
    return *it->second;
  }
  NodeState& ns = *it->second;
  ns.node = &node;
  const std::size_t n = node.fieldCount();
  ns.out.resize(n);
  if (n > 0) ns.fieldsHint = &node.fieldAt(0);
  classify(ns);
  if (ns.role == NodeRole::bindable && bindables)
    candidates[static_cast<std::size_t>(ns.bindable)].push_back(&ns);
  // Children and other node-valued fields, depth first in file order. Inside a LayerSet
  // only the active layer's bindable nodes are bound (X3D 4.0 clause 35.4.2: activeLayer
  // 1..N is layers[activeLayer - 1], 0 the root layer); every layer is drawn with the
  // bound camera, background and fog (docs/x3d.md, "Layering").
  if (node.typeId() == vrml::NodeTypeId::LayerSet) {
    const int active = node.get<FieldType::SFInt32>("activeLayer", 0);
    const int layersField = node.type().findExact("layers");
    for (std::size_t i = 0; i < n; ++i) {
      const vrml::FieldValue& v = node.fieldAt(i);
      if (v.type() != FieldType::MFNode && v.type() != FieldType::SFNode) continue;
      if (v.type() == FieldType::SFNode) {
        if (const vrml::NodePtr& c = v.get<FieldType::SFNode>()) reach(c, false);
        continue;
      }
      const auto& list = v.get<FieldType::MFNode>();
      for (std::size_t k = 0; k < list.size(); ++k)
        if (list[k])
          reach(list[k], bindables && static_cast<int>(i) == layersField &&
                             static_cast<int>(k) + 1 == active);
    }
    return ns;
  }
  // A viewpoint's own NavigationInfo (X3D 4.0 clause 23.3.1) is bound with it, not as a
  // candidate of the graph (X_ITE 15 finds bindables in the graph only).
  const int ownNavigation = ns.role == NodeRole::bindable && ns.bindable == BindableKind::Viewpoint
                                ? node.type().findExact("navigationInfo")
                                : -1;
  for (std::size_t i = 0; i < n; ++i) {
    const vrml::FieldValue& v = node.fieldAt(i);
    if (v.type() == FieldType::SFNode) {
      if (const vrml::NodePtr& c = v.get<FieldType::SFNode>())
        reach(c, bindables && static_cast<int>(i) != ownNavigation);
    } else if (v.type() == FieldType::MFNode) {
      for (const vrml::NodePtr& c : v.get<FieldType::MFNode>())
        if (c) reach(c, bindables);
    }
  }
  return ns;
}

NodeState& ExecutionModel::State::reach(const vrml::NodePtr& node, bool bindables) {
  NodeState& ns = reach(*node, bindables);
  // An alias made for a back reference owns nothing (use_count 0): its owner keeps it.
  if (!ns.keepAlive && node.use_count() > 0) ns.keepAlive = node;
  return ns;
}

void ExecutionModel::State::takeInlineScene(InlineCursor& c) {
  const vrml::Scene* outer = reachingInline;  // a Script's code may reach here from a take
  reachingInline = c.scene.get();
  takeScene(*c.scene, c.roots, c.hidden, c.routes, false);
  reachingInline = outer;
}

bool ExecutionModel::State::connect(vrml::Node& from, int fromField, vrml::Node& to, int toField) {
  NodeState& a = reach(from, false);
  NodeState& b = reach(to, false);
  if (fromField < 0 || static_cast<std::size_t>(fromField) >= a.out.size()) return false;
  a.out[static_cast<std::size_t>(fromField)].add({&b, toField});  // a duplicate is ignored
  if (fromField < 32) a.routedFields |= std::uint32_t{1} << fromField;
  return true;
}

void ExecutionModel::State::takeScene(const vrml::Scene& s, std::size_t& roots, std::size_t& hidden,
                                      std::size_t& routes, bool bindables) {
  // A Script's code runs while its node is reached, and may add a root to this very scene
  // (addRootNode, changeInlineRoots): the lists may grow under these loops, so each node is
  // copied before it is reached, and a root added meanwhile is reached by this loop.
  taking.push_back(&s);
  const bool reviving = revivingUnloaded;
  revivingUnloaded = true;
  for (; roots < s.rootNodes.size(); ++roots)
    if (const vrml::NodePtr n = s.rootNodes[roots]) reach(n, bindables);
  for (; hidden < s.hiddenNodes.size(); ++hidden)
    if (const vrml::NodePtr n = s.hiddenNodes[hidden]) reach(n, false);
  for (; routes < s.routes.size(); ++routes) {
    const vrml::Route& r = s.routes[routes];
    if (!r.fromNode || !r.toNode) continue;
    const int from = r.fromNode->type().findField(r.fromField);
    const int to = r.toNode->type().findField(r.toField);
    if (from < 0 || to < 0) continue;  // the parser reported it
    connect(*r.fromNode, from, *r.toNode, to);
  }
  revivingUnloaded = reviving;
  taking.pop_back();
}

// ---- events ----

namespace {

/// Prefetches the line of `node` that holds its type, fields and revision (vrml::Node
/// keeps them first; 16-byte aligned, they may reach into the next line).
[[gnu::always_inline]] inline void prefetchNode(const vrml::Node* node) {
  __builtin_prefetch(node);
  __builtin_prefetch(reinterpret_cast<const char*>(node) + 56);
}

/// Prefetches both lines a port may straddle (48 bytes, 16-byte aligned).
[[gnu::always_inline]] inline void prefetchPort(const OutPort* port) {
  __builtin_prefetch(port);
  __builtin_prefetch(reinterpret_cast<const char*>(port + 1) - 1);
}

/// How many events (or TimeSensors) ahead runCascade() (advanceTo()) fetches a record, and
/// how many what the record points to.
constexpr std::size_t kStateAhead = 8, kDataAhead = 4;

/// Whether eventOut `field` of `ns` may have routes (NodeState::routedFields).
bool routed(const NodeState& ns, int field) {
  return field >= 32 || (ns.routedFields >> field & 1u) != 0;
}

/// Prefetches the two lines of a record that an event reads (NodeState's layout).
[[gnu::always_inline]] inline void prefetchState(const NodeState* ns) {
  __builtin_prefetch(ns);
  __builtin_prefetch(&ns->setFraction);
}

/// Prefetches what delivering an event to `field` of `to` reads and writes, from its
/// record (which must have arrived): the node, the eventOut port its answer goes out on
/// (an interpolator's value_changed, else the exposedField's own index), the fields it
/// writes, and an interpolator's key and keyValue.
[[gnu::always_inline]] inline void prefetchDelivery(const NodeState& to, int field) {
  prefetchNode(to.node);
  const bool interpolator = to.role == NodeRole::interpolator;
  const int port = interpolator ? to.valueChanged : field;
  if (port < 0 || static_cast<std::size_t>(port) >= to.out.size()) return;
  if (routed(to, port)) prefetchPort(to.out.data() + port);
  if (!interpolator) {
    if (to.fieldsHint) __builtin_prefetch(to.fieldsHint + port);
    return;
  }
  if (to.fieldsHint && to.key >= 0 && to.keyValue >= 0) {  // key and keyValue, then their data
    __builtin_prefetch(to.fieldsHint + to.key);
    __builtin_prefetch(to.fieldsHint + to.keyValue);
  }
  __builtin_prefetch(to.keysHint);
  __builtin_prefetch(to.keyValuesHint);
}

}  // namespace

void ExecutionModel::State::emit(NodeState& from, int field, const vrml::FieldValue& value) {
  ExecutionStatistics& st = model.stats_;
  if (!routed(from, field) && !model.options_.trace) {
    ++st.eventsSent;  // never routed: nothing to send to, no loop to break (4.10.3)
    return;
  }
  OutPort& port = from.out[static_cast<std::size_t>(field)];
  if (port.lastSent == stamp) {  // 4.10.3: one event per eventOut per timestamp ends loops
    ++st.eventsDropped;
    return;
  }
  port.lastSent = stamp;
  ++st.eventsSent;
  if (model.options_.trace) [[unlikely]]
    model.options_.trace({model.now(), from.node, field, &value});
  if (port.first.to == nullptr) return;
  queue.push_back({port.first.to, port.first.field, value});
  for (const RouteTarget& r : port.more) queue.push_back({r.to, r.field, value});
}

void ExecutionModel::State::emitOwn(NodeState& from, int field, vrml::FieldValue value) {
  if (field < 0) return;
  emit(from, field, value);
  from.node->setField(static_cast<std::size_t>(field), std::move(value));
}

void ExecutionModel::State::runCascade() {
  for (;;) {
    while (queueHead < queue.size()) {
      if (++eventsThisCascade > model.options_.maxEventsPerCascade) {
        if (!cascadeOverflow)
          model.diagnostics_.error({}, "more than " +
                                           std::to_string(model.options_.maxEventsPerCascade) +
                                           " events at one timestamp: the cascade was cut "
                                           "(limit maxEventsPerCascade)");
        cascadeOverflow = true;
        queue.clear();
        queueHead = 0;
        break;
      }
      // Fetch what the events a few places ahead will read (a cascade over many nodes
      // waits on memory, not on work): their records first, what the records point to
      // (node, ports, fields, keys) once the records have arrived.
      if (queueHead + kStateAhead < queue.size()) prefetchState(queue[queueHead + kStateAhead].to);
      if (queueHead + kDataAhead < queue.size()) {
        const PendingEvent& ahead = queue[queueHead + kDataAhead];
        prefetchDelivery(*ahead.to, ahead.field);
      }
      // deliver() may append to the queue (and so move it): take the event out first.
      PendingEvent& next = queue[queueHead++];
      NodeState* to = next.to;
      const int field = next.field;
      vrml::FieldValue value = std::move(next.value);
      ++model.stats_.eventsDelivered;
      deliver(*to, field, std::move(value));
    }
    queue.clear();  // keeps its capacity for the next cascade
    queueHead = 0;
    // 4.12.6: eventsProcessed() after the events of this timestamp reached a Script.
    bool more = false;
    for (NodeState* s : scripts) {
      if (!s->scriptHadEvents) continue;
      s->scriptHadEvents = false;
      if (s->script && !s->script->stopped()) s->script->eventsProcessed(model.now());
      more = true;
    }
    if (!more || queueHead >= queue.size()) break;
  }
}

void ExecutionModel::State::initializeScripts() {
  while (!newScripts.empty()) {
    std::vector<NodeState*> batch;
    batch.swap(newScripts);
    for (NodeState* s : batch) {
      scripts.push_back(s);
      if (s->script) s->script->initialize(model.now());
    }
    runCascade();
  }
}

bool ExecutionModel::State::scriptFilesArriving(const vrml::Node& script) {
  // Relative to the file that wrote the Script (an EXTERNPROTO's: vrml::Node::urlBase; an
  // Inline's world's: nodeScenes), else the world's.
  const auto inlineScene = nodeScenes.find(&script);
  const std::string worldUrl = inlineScene != nodeScenes.end() ? inlineScene->second->url
                               : scene                         ? scene->url
                                                               : std::string();
  const std::string world = script.urlBaseOr(worldUrl);
  const vrml::FieldValue* urls = script.field("url");
  if (urls == nullptr || urls->type() != vrml::FieldType::MFString) return false;
  for (const std::string& entry : urls->get<vrml::FieldType::MFString>()) {
    const ScriptUrlEntry e = classifyScriptUrl(entry);
    if (e.kind == ScriptUrlEntry::Kind::inlineSource) return false;  // runs its own text first
    if (e.kind != ScriptUrlEntry::Kind::file) continue;
    // Local files and data: URLs answer at once: nothing to wait for, and nothing read
    // here (the factory's fetchText reads the file); a refused or missing one is skipped.
    const std::string url = base::resolveUrl(world, entry);
    if (base::isDataUrl(url)) return false;
    std::string refused;
    const std::string path = base::localFileFor(url, world, refused);
    if (!refused.empty()) continue;
    if (!path.empty()) {
      std::error_code ec;
      if (std::filesystem::is_regular_file(path, ec)) return false;
      continue;
    }
    const base::Fetched got =
        base::fetcherOr(model.options_.fetcher).fetch(url, world, base::FetchMode::background);
    if (got.pending()) return true;
    if (got.ready()) return false;
  }
  return false;
}

void ExecutionModel::State::startArrivedScripts() {
  if (arrivingScripts.empty()) return;
  bool started = false;
  std::erase_if(arrivingScripts, [&](NodeState* ns) {
    if (scriptFilesArriving(*ns->node)) return false;  // still on its way: kept
    ns->script = model.options_.scripts(*ns->node, model, model.options_.scriptLimits);
    newScripts.push_back(ns);
    started = true;
    return true;
  });
  if (started) initializeScripts();
}

// ---- ExecutionModel ----

ExecutionModel::ExecutionModel(std::shared_ptr<const vrml::Scene> scene, double loadTime,
                               ExecutionOptions options)
    : s_(std::make_unique<State>(*this)), clock_(loadTime), options_(std::move(options)) {
  s_->scene = std::move(scene);
  s_->stamp = 1;
  if (s_->scene) s_->takeScene(*s_->scene, s_->rootsSeen, s_->hiddenSeen, s_->routesSeen, true);
  s_->bindFirstCandidates();
  s_->startNewLoadSensors();  // X3D 9.4.3: a LoadSensor starts watching when the world loads
  s_->startNewRigidBodyCollections();
  s_->runCascade();
  s_->initializeScripts();
  for (NodeState* t : s_->timeSensors) s_->evaluateTimeSensor(*t);
  if (!s_->skins.empty()) s_->evaluateHAnimMotions();  // their cycles start at the load
  s_->runCascade();
  s_->evaluateSkins();
  ++stats_.cascades;
}

ExecutionModel::~ExecutionModel() {
  for (NodeState* s : s_->scripts)
    if (s->script && !s->script->stopped()) s->script->shutdown(now());
  // The world's nodes own one another through shared pointers: a field that names a node
  // placed elsewhere and leads back to its own node (a Script's SFNode field naming its
  // ancestor, a TransformSensor below the Transform it watches) would keep them all alive
  // after the world. Such fields are emptied now; nothing reads them any more. Only nodes
  // the model owns are read: one first met without an owning pointer may be gone.
  for (auto& [node, ns] : s_->nodes)
    if (ns->keepAlive) breakReferenceCycles(*ns->keepAlive);
}

void ExecutionModel::sceneGrew() {
  ++s_->stamp;
  if (s_->scene) s_->takeScene(*s_->scene, s_->rootsSeen, s_->hiddenSeen, s_->routesSeen, true);
  for (State::InlineCursor& c : s_->inlineScenes) s_->takeInlineScene(c);
  s_->bindFirstCandidates();
  s_->startNewLoadSensors();
  s_->runCascade();
  s_->initializeScripts();
  s_->startArrivedScripts();
  s_->evaluateSkins();
}

void ExecutionModel::noteInlineWorld(const vrml::Node& inlineNode, const vrml::Scene* scene) {
  if (scene != nullptr) s_->inlineWorlds[&inlineNode] = scene;
}

void ExecutionModel::addInlineScene(std::shared_ptr<const vrml::Scene> scene) {
  if (!scene) return;
  if (s_->inlineSceneSet.contains(scene.get())) return;
  if (s_->unloadedInlineScenes.contains(scene.get())) {
    // Unloaded with the world that held its Inline: taken again once an Inline that was
    // not unloaded (a node of the new world) shows it.
    const auto live = [&](const auto& entry) {
      if (entry.second != scene.get()) return false;
      const auto it = s_->nodes.find(entry.first);
      return it == s_->nodes.end() || !it->second->unloaded;
    };
    if (std::none_of(s_->inlineWorlds.begin(), s_->inlineWorlds.end(), live)) return;
    s_->unloadedInlineScenes.erase(scene.get());
  }
  s_->inlineSceneSet.insert(scene.get());
  State::InlineCursor& c = s_->inlineScenes.emplace_back();
  c.scene = std::move(scene);
  const std::size_t firstSensor = s_->timeSensors.size();
  ++s_->stamp;
  s_->takeInlineScene(c);
  s_->startNewLoadSensors();
  s_->initializeScripts();
  // The Inline's world starts now: its TimeSensors as at load (4.10.3's initial events).
  for (std::size_t i = firstSensor; i < s_->timeSensors.size(); ++i)
    s_->evaluateTimeSensor(*s_->timeSensors[i]);
  s_->runCascade();
  s_->evaluateSkins();
}

void ExecutionModel::worldLoaded(bool complete) {
  if (s_->worldLoadedSent) return;
  s_->worldLoadedSent = true;
  sendBrowserEvent(complete ? BrowserEvent::initialized : BrowserEvent::initializationError);
}

void ExecutionModel::linkFailed() {
  sendBrowserEvent(BrowserEvent::initializationError);
}

void ExecutionModel::sendBrowserEvent(BrowserEvent event) {
  s_->initializeScripts();                             // those the last growth made
  const std::vector<NodeState*> loaded = s_->scripts;  // (a callback may make Scripts)
  for (NodeState* s : loaded)
    if (s->script && !s->script->stopped()) s->script->browserEvent(event, now());
  s_->runCascade();
  s_->initializeScripts();  // those the callbacks made
}

void ExecutionModel::advanceTo(double time) {
  if (time < now()) return;
  clock_.set(time);
  ++s_->stamp;
  ++stats_.cascades;
  s_->eventsThisCascade = 0;
  s_->cascadeOverflow = false;
  if (!s_->replacedNodes.empty()) s_->unloadReplacedWorld();  // Browser.replaceWorld's
  const std::vector<NodeState*>& sensors = s_->timeSensors;
  for (std::size_t i = 0; i < sensors.size(); ++i) {
    // As in runCascade: fetch the sensors' records, then their nodes, the ports
    // fraction_changed and time go out on, and the fields they write.
    if (i + kStateAhead < sensors.size()) {
      __builtin_prefetch(sensors[i + kStateAhead]);
      __builtin_prefetch(&sensors[i + kStateAhead]->timeFields);
      __builtin_prefetch(&sensors[i + kStateAhead]->timeFieldsRevision);
    }
    if (i + kDataAhead < sensors.size()) {
      const NodeState* ahead = sensors[i + kDataAhead];
      prefetchNode(ahead->node);
      for (const int port : {ahead->timeFields.fraction, ahead->timeFields.time})
        if (port >= 0 && static_cast<std::size_t>(port) < ahead->out.size()) {
          if (routed(*ahead, port)) prefetchPort(ahead->out.data() + port);
          if (ahead->fieldsHint) __builtin_prefetch(ahead->fieldsHint + port);
        }
    }
    s_->evaluateTimeSensor(*sensors[i]);
  }
  for (NodeState* m : s_->mediaNodes) s_->evaluateMedia(*m);
  for (NodeState* f : s_->followers) s_->evaluateFollower(*f);
  s_->evaluateParticleSystems();
  s_->startNewLoadSensors();  // made since (createVrmlFromString, addChildren)
  s_->evaluateLoadSensors();  // their timeOuts
  s_->evaluateEnvironmentSensors();
  s_->evaluatePickSensors();
  if (!s_->espduTransforms.empty()) s_->evaluateDis();
  if (!s_->skins.empty()) s_->evaluateHAnimMotions();
  for (PendingEvent& e : s_->posted) s_->queue.push_back(std::move(e));
  s_->posted.clear();
  s_->runCascade();
  if (!s_->rigidBodyCollections.empty() || !s_->collisionSensors.empty()) {
    // X_ITE's sensor phase: physics after the frame's time events, drawn this frame.
    s_->evaluateRigidBodyPhysics();
    s_->runCascade();
  }
  s_->startArrivedScripts();  // a Script whose file arrived starts now (initialize())
  if (!s_->newScripts.empty()) s_->initializeScripts();  // made by Scripts this frame
  s_->evaluateSkins();
}

std::size_t ExecutionModel::scriptsArriving() const {
  return s_->arrivingScripts.size();
}

void ExecutionModel::advanceBy(double duration, double step) {
  if (!(step > 0.0)) step = 1.0 / 60.0;
  const double end = now() + duration;
  // Steps counted, not accumulated, so N steps of S land on the same times everywhere.
  const double start = now();
  const auto count = static_cast<long long>(std::ceil(duration / step - 1e-9));
  for (long long i = 1; i < count; ++i) advanceTo(start + static_cast<double>(i) * step);
  advanceTo(end);
}

bool ExecutionModel::postEvent(vrml::Node& node, int field, vrml::FieldValue value) {
  const auto& fields = node.type().fields;
  if (field < 0 || static_cast<std::size_t>(field) >= fields.size() ||
      fields[static_cast<std::size_t>(field)].type != value.type()) {
    diagnostics_.error(node.location,
                       "event of the wrong type or to a missing field of " + node.typeName());
    return false;
  }
  s_->posted.push_back({&s_->reach(node, false), field, std::move(value)});
  return true;
}

void ExecutionModel::processEvents() {
  ++s_->stamp;
  ++stats_.cascades;
  s_->eventsThisCascade = 0;
  for (PendingEvent& e : s_->posted) s_->queue.push_back(std::move(e));
  s_->posted.clear();
  s_->runCascade();
  s_->evaluateSkins();
}

void ExecutionModel::setViewer(const ViewerPose& viewer) {
  s_->viewer = viewer;
}

vrml::Node* ExecutionModel::bound(BindableKind kind) const {
  const auto& stack = s_->stacks[static_cast<std::size_t>(kind)];
  return stack.empty() ? nullptr : stack.back()->node;
}

std::vector<vrml::Node*> ExecutionModel::bindStack(BindableKind kind) const {
  std::vector<vrml::Node*> out;
  for (NodeState* n : s_->stacks[static_cast<std::size_t>(kind)]) out.push_back(n->node);
  return out;
}

bool ExecutionModel::animating() const {
  for (const NodeState* t : s_->timeSensors)
    if (t->time.active) return true;
  for (const NodeState* m : s_->mediaNodes)
    if (m->media->state.active) return true;
  for (const NodeState* p : s_->particleSystems)
    if (p->particles->simulation.active()) return true;
  for (const NodeState* l : s_->loadSensors)  // a timeOut still to pass
    if (l->load->watching && l->load->timeOut >= 0 &&
        l->node->fieldAt(static_cast<std::size_t>(l->load->timeOut)).get<FieldType::SFTime>() > 0.0)
      return true;
  return !s_->posted.empty();
}

}  // namespace gs::runtime
