// The ScriptContext services of the execution model (ISO/IEC 14772-1 annex C, ISO/IEC
// 19777-1): events a Script sends, routes it adds and deletes, worlds and nodes it makes,
// the world it replaces, and what it asks the browser. The cascade is in
// execution_model.cpp.
#include "execution_state.hpp"

#include "base/data_url.hpp"
#include "base/url.hpp"
#include "encodings/parser.hpp"
#include "vrml/proto.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <unordered_set>

namespace gs::runtime {

using vrml::AccessType;
using vrml::FieldType;

// ---- ScriptContext ----

void ExecutionModel::emitScriptEvent(vrml::Node& script, int field, vrml::FieldValue value) {
  const auto& fields = script.type().fields;
  if (field < 0 || static_cast<std::size_t>(field) >= fields.size() ||
      fields[static_cast<std::size_t>(field)].type != value.type() ||
      (fields[static_cast<std::size_t>(field)].access != AccessType::eventOut &&
       fields[static_cast<std::size_t>(field)].access != AccessType::exposedField)) {
    diagnostics_.error(script.location, "a Script sent an event on a field it does not have");
    return;
  }
  s_->emitOwn(s_->reach(script, false), field, std::move(value));
}

void ExecutionModel::sendEvent(vrml::Node& node, int field, vrml::FieldValue value) {
  const auto& fields = node.type().fields;
  if (field < 0 || static_cast<std::size_t>(field) >= fields.size() ||
      fields[static_cast<std::size_t>(field)].type != value.type())
    return;
  s_->queue.push_back({&s_->reach(node, false), field, std::move(value)});
}

std::string ExecutionModel::worldUrl() const {
  return s_->scene ? s_->scene->url : std::string();
}

namespace {

/// Resolves a route end as a ROUTE statement names it on `type`; -1 when the type has no
/// such eventOut (out) or eventIn.
int routeEnd(const vrml::NodeType& type, const std::string& name, bool out) {
  const int i = type.findField(name);
  if (i < 0) return -1;
  const AccessType a = type.fields[static_cast<std::size_t>(i)].access;
  if (a == AccessType::exposedField) return i;
  return (a == (out ? AccessType::eventOut : AccessType::eventIn)) ? i : -1;
}

/// One end of a route as the route table stores it: a member of a built-in or Script node.
struct RouteEndpoint {
  vrml::NodePtr node;
  int field = -1;
};

/// The members a route end `node.name` stands for: the node's own member, or, for a PROTO
/// instance, the body members its declared interface member is IS-connected to (4.8.3).
/// `type` is set to the member's field type; empty when there is no such member.
std::vector<RouteEndpoint> routeEndpoints(const vrml::NodePtr& node, const std::string& name,
                                          bool out, FieldType& type) {
  std::vector<RouteEndpoint> ends;
  const vrml::ProtoInstance* p = vrml::declaredInterface(*node);
  const vrml::NodeType& declared = p != nullptr ? *p->type : node->type();
  const int i = routeEnd(declared, name, out);
  if (i < 0) return ends;
  type = declared.fields[static_cast<std::size_t>(i)].type;
  if (p == nullptr) {
    ends.push_back({node, i});
    return ends;
  }
  for (const vrml::InstanceLink& k : p->linksOf(i)) {
    const bool fits = k.nodeAccess == AccessType::exposedField ||
                      k.nodeAccess == (out ? AccessType::eventOut : AccessType::eventIn);
    if (vrml::NodePtr body = k.node.lock(); fits && body) ends.push_back({body, k.nodeField});
  }
  if (ends.empty()) type = FieldType::SFBool;  // an interface member IS connects to nothing
  return ends;
}

}  // namespace

bool ExecutionModel::addRoute(const vrml::NodePtr& from, const std::string& eventOut,
                              const vrml::NodePtr& to, const std::string& eventIn) {
  if (!from || !to) return false;
  FieldType st = FieldType::SFBool, dt = FieldType::SFBool;
  const std::vector<RouteEndpoint> a = routeEndpoints(from, eventOut, true, st);
  const std::vector<RouteEndpoint> b = routeEndpoints(to, eventIn, false, dt);
  if (a.empty() || b.empty() || st != dt) {
    const std::string fromType = from->protoName().empty() ? from->typeName() : from->protoName();
    const std::string toType = to->protoName().empty() ? to->typeName() : to->protoName();
    diagnostics_.error(from->location, "addRoute " + fromType + "." + eventOut + " TO " + toType +
                                           "." + eventIn +
                                           ": no such events or their types differ");
    return false;
  }
  bool any = false;
  for (const RouteEndpoint& f : a)
    for (const RouteEndpoint& t : b) {
      s_->reach(f.node, false);
      s_->reach(t.node, false);
      any = s_->connect(*f.node, f.field, *t.node, t.field) || any;
    }
  return any;
}

bool ExecutionModel::deleteRoute(const vrml::NodePtr& from, const std::string& eventOut,
                                 const vrml::NodePtr& to, const std::string& eventIn) {
  if (!from || !to) return false;
  FieldType st = FieldType::SFBool, dt = FieldType::SFBool;
  bool any = false;
  for (const RouteEndpoint& f : routeEndpoints(from, eventOut, true, st))
    for (const RouteEndpoint& t : routeEndpoints(to, eventIn, false, dt)) {
      auto it = s_->nodes.find(f.node.get());
      auto jt = s_->nodes.find(t.node.get());
      if (it == s_->nodes.end() || jt == s_->nodes.end()) continue;
      OutPort& port = it->second->out[static_cast<std::size_t>(f.field)];
      if (port.remove({jt->second.get(), t.field})) any = true;
    }
  return any;
}

bool ExecutionModel::hasRoute(const vrml::NodePtr& from, const std::string& eventOut,
                              const vrml::NodePtr& to, const std::string& eventIn) const {
  if (!from || !to) return false;
  FieldType st = FieldType::SFBool, dt = FieldType::SFBool;
  for (const RouteEndpoint& f : routeEndpoints(from, eventOut, true, st))
    for (const RouteEndpoint& t : routeEndpoints(to, eventIn, false, dt)) {
      const auto it = s_->nodes.find(f.node.get());
      const auto jt = s_->nodes.find(t.node.get());
      if (it == s_->nodes.end() || jt == s_->nodes.end()) continue;
      if (it->second->out[static_cast<std::size_t>(f.field)].has({jt->second.get(), t.field}))
        return true;
    }
  return false;
}

namespace {

/// Gives every node of `scene` without a base of its own `base` (vrml::Node::urlBase, as
/// an EXTERNPROTO's file gives its nodes): nodes made from a text that is not the world's
/// file keep that text's URLs and rules wherever a Script puts them (the traversal resolves
/// an Inline, texture or sound by them). Without recursion: the text may nest deeply.
void markMadeNodes(const vrml::Scene& scene, const std::string& base) {
  const auto shared = std::make_shared<const std::string>(base);
  std::unordered_set<const vrml::Node*> seen;
  std::vector<vrml::Node*> pending;
  for (const auto* list : {&scene.rootNodes, &scene.hiddenNodes})
    for (const vrml::NodePtr& n : *list)
      if (n) pending.push_back(n.get());
  while (!pending.empty()) {
    vrml::Node* n = pending.back();
    pending.pop_back();
    if (!seen.insert(n).second) continue;
    if (!n->urlBase) n->urlBase = shared;  // else from a file nested deeper: kept
    pushChildNodes(*n, pending);
  }
}

}  // namespace

void ExecutionModel::countMadeNodes(const vrml::Scene& made) {
  // Every node the text made, each once (a DEF/USE shares one), without recursion.
  std::unordered_set<const vrml::Node*> seen;
  std::vector<vrml::Node*> pending;
  for (const auto* list : {&made.rootNodes, &made.hiddenNodes})
    for (const vrml::NodePtr& n : *list)
      if (n) pending.push_back(n.get());
  while (!pending.empty()) {
    const vrml::Node* n = pending.back();
    pending.pop_back();
    if (seen.insert(n).second) pushChildNodes(*n, pending);
  }
  const std::size_t limit = options_.scriptLimits.madeNodes;
  if (s_->madeNodes + seen.size() > limit)
    throw ScriptLimitError("the Scripts of this world hold " + std::to_string(s_->madeNodes) +
                           " nodes they made; " + std::to_string(seen.size()) +
                           " more would pass the limit of " + std::to_string(limit) +
                           " (ScriptLimits::madeNodes)");
  s_->madeNodes += seen.size();
}

std::vector<vrml::NodePtr> ExecutionModel::createVrmlFromString(const std::string& text) {
  return createSceneFromString(text, nullptr)->rootNodes;
}

std::shared_ptr<vrml::Scene> ExecutionModel::createSceneFromString(const std::string& text,
                                                                   const vrml::Node* script,
                                                                   const std::string& url) {
  std::string bytes = text;
  if (!bytes.starts_with("#VRML") && !bytes.starts_with("#X3D"))
    bytes = "#VRML V2.0 utf8\n" + bytes;
  // A Script in an Inline's world makes nodes of that world (its URL, its rules); a text
  // read from `url` makes nodes of its own scene, which the model keeps as their world.
  const vrml::Scene* own = script != nullptr ? sceneOf(*script) : nullptr;
  if (own == s_->scene.get()) own = nullptr;
  const std::string textUrl = !url.empty()     ? base::resolveUrl(worldUrl(), url)
                              : own != nullptr ? own->url
                                               : worldUrl();
  auto made = std::make_shared<vrml::Scene>(vrml::parseVrml(bytes, textUrl));
  countMadeNodes(*made);  // throws ScriptLimitError past ScriptLimits::madeNodes
  for (vrml::Diagnostic& d : made->diagnostics.items) diagnostics_.items.push_back(std::move(d));
  made->diagnostics.items.clear();
  if (!url.empty() || own != nullptr) markMadeNodes(*made, textUrl);
  if (!url.empty()) {
    s_->urlScenes.push_back(made);
    own = made.get();
  }
  std::size_t roots = 0, hidden = 0, routes = 0;
  const vrml::Scene* outer = s_->reachingInline;
  s_->reachingInline = own;
  s_->takeScene(*made, roots, hidden, routes, false);
  s_->reachingInline = outer;
  return made;
}

const vrml::Scene* ExecutionModel::currentScene() const {
  return s_->scene.get();
}

const vrml::Scene* ExecutionModel::sceneOf(const vrml::Node& script) const {
  const auto it = s_->nodeScenes.find(&script);
  return it != s_->nodeScenes.end() ? it->second : s_->scene.get();
}

void ExecutionModel::setImportedNode(const std::string& localName, vrml::NodePtr node) {
  imported_[localName] = std::move(node);
}

bool ExecutionModel::addRootNode(const vrml::NodePtr& node) {
  if (!node || !s_->scene) return false;
  // The world's Scene is no const object (see the header): its root list may change.
  auto& roots = const_cast<vrml::Scene&>(*s_->scene).rootNodes;
  if (std::find(roots.begin(), roots.end(), node) != roots.end()) return false;
  roots.push_back(node);
  if (s_->isTaking(*s_->scene)) return true;  // the take under way reaches it
  s_->reach(node, true);
  s_->rootsSeen = std::max(s_->rootsSeen, roots.size());
  s_->startNewLoadSensors();
  return true;
}

bool ExecutionModel::removeRootNode(const vrml::NodePtr& node) {
  if (!node || !s_->scene) return false;
  auto& roots = const_cast<vrml::Scene&>(*s_->scene).rootNodes;
  const auto it = std::find(roots.begin(), roots.end(), node);
  if (it == roots.end() || s_->isTaking(*s_->scene)) return false;  // not while it is read
  if (static_cast<std::size_t>(it - roots.begin()) < s_->rootsSeen) --s_->rootsSeen;
  roots.erase(it);
  return true;
}

bool ExecutionModel::changeInlineRoots(const vrml::Scene& scene, const vrml::NodePtr& node,
                                       bool add) {
  if (!node || s_->inlineSceneSet.count(&scene) == 0) return false;
  // Not an object defined const (see the header): an Inline's root list may change.
  auto& roots = const_cast<vrml::Scene&>(scene).rootNodes;
  const auto it = std::find(roots.begin(), roots.end(), node);
  if (add == (it != roots.end())) return false;
  if (s_->isTaking(scene)) {  // a Script's code while the world is read: that take reaches it
    if (add) roots.push_back(node);
    return add;
  }
  for (State::InlineCursor& c : s_->inlineScenes) {
    if (c.scene.get() != &scene) continue;
    if (!add) {
      if (static_cast<std::size_t>(it - roots.begin()) < c.roots) --c.roots;
      roots.erase(it);
      return true;
    }
    roots.push_back(node);
    s_->takeInlineScene(c);  // reaches the new root (and any the file added since)
    s_->startNewLoadSensors();
    return true;
  }
  return false;
}

vrml::NodePtr ExecutionModel::importedNode(const std::string& localName) const {
  const auto it = imported_.find(localName);
  return it != imported_.end() ? it->second : nullptr;
}

void ExecutionModel::loadUrl(const std::vector<std::string>& url,
                             const std::vector<std::string>& parameter) {
  s_->requestUrl(url, parameter);  // `#Name` binds a Viewpoint (pointer_sensors.cpp)
}

bool ExecutionModel::fetchText(const std::string& url, std::string& text, std::string& error) {
  // Relative to the world's URL (after redirects), under the fetcher's rules.
  const std::string world = s_->scene ? s_->scene->url : std::string();
  // A Script's own file was asked for in the background before the Script was made
  // (State::scriptFilesArriving), so it is ready here; a createVrmlFromURL text is read
  // whole during the call.
  const std::string resolved = base::resolveUrl(world, url);
  base::Fetcher& fetcher = base::fetcherOr(options_.fetcher);
  base::Fetched got = fetcher.fetch(resolved, world, base::FetchMode::background);
  if (got.pending()) got = fetcher.fetch(resolved, world, base::FetchMode::whole);
  if (!got.ready()) {
    error = "cannot read '" + url + "': " + got.error;
    return false;
  }
  text = std::move(got.bytes);
  return true;
}

bool ExecutionModel::worldReplaced() const {
  return s_->worldReplaced;
}

void ExecutionModel::replaceWorld(const std::vector<vrml::NodePtr>& nodes) {
  if (!s_->scene) return;
  s_->worldReplaced = true;
  // The world's Scene is no const object (see the header): its root list may change.
  auto& roots = const_cast<vrml::Scene&>(*s_->scene).rootNodes;
  s_->replacedNodes.insert(s_->replacedNodes.end(), roots.begin(), roots.end());
  const auto& hidden = s_->scene->hiddenNodes;
  s_->replacedNodes.insert(s_->replacedNodes.end(), hidden.begin(), hidden.end());
  roots.clear();
  for (const vrml::NodePtr& n : nodes)
    if (n && std::find(roots.begin(), roots.end(), n) == roots.end()) roots.push_back(n);
  // A node of a world replaced before may come back: registered afresh.
  const bool reviving = s_->revivingUnloaded;
  s_->revivingUnloaded = true;
  for (const vrml::NodePtr& n : roots) s_->reach(n, false);
  s_->revivingUnloaded = reviving;
  s_->rootsSeen = roots.size();
  s_->rebindFrom(roots);
  s_->startNewLoadSensors();
}

void ExecutionModel::setDescription(const std::string& text) {
  std::fprintf(stderr, "%s\n", text.c_str());
}

const std::string* ExecutionModel::browserOption(const std::string& name) const {
  const auto it = options_.browserOptions.find(name);
  return it == options_.browserOptions.end() ? nullptr : &it->second.value;
}

bool ExecutionModel::setBrowserOption(const std::string& name, const std::string& value) {
  const auto it = options_.browserOptions.find(name);
  if (it == options_.browserOptions.end()) return false;
  if (it->second.accepts && !it->second.accepts(value)) return false;
  it->second.value = value;
  return true;
}

const RenderingProperties* ExecutionModel::renderingProperties() const {
  return options_.rendering.maxLights > 0 ? &options_.rendering : nullptr;
}

void ExecutionModel::print(const std::string& text) {
  std::fprintf(stderr, "%s\n", text.c_str());
}

void ExecutionModel::scriptDiagnostic(vrml::Severity severity, const vrml::SourceLocation& where,
                                      const std::string& message) {
  diagnostics_.items.push_back({severity, where, message});
}

}  // namespace gs::runtime
