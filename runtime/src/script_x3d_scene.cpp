// The X3DScene natives that read or edit a scene's own tables (ISO/IEC 19777-1 clause
// 7.4.11, X3DExecutionContext and X3DScene, with X_ITE 15's names where 19777-1 has none):
// named nodes, META statements, EXPORTs and the ROUTE list. Each takes the X3DScene
// object first: Browser.currentScene (the world, or the Inline's world the Script is in)
// or a scene createX3DFromString made. Installed on __gsX3D by installX3DHooks.
#include "script_ecmascript_internal.hpp"
#include "vrml/proto.hpp"
#include "vrml/scene.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <unordered_set>

namespace gs::runtime::es {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

// A scene's tables live outside the Script's heap, so what a Script puts in them is bounded
// apart: at most kMaxTableEntries entries each, names of at most kMaxNameBytes, and META
// values of at most a quarter of the heap's limit in all (a hostile Script adding values
// in a loop gets a RangeError).
constexpr std::size_t kMaxTableEntries = 16384;
constexpr std::size_t kMaxNameBytes = 1024;

// A RangeError when `entries` more would take a table of `size` past kMaxTableEntries.
void x3dCheckTableRoom(duk_context* c, std::size_t size, std::size_t entries, const char* what,
                       const std::string& name) {
  if (name.size() > kMaxNameBytes)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "%s: the name is longer than %lu bytes", what,
                 static_cast<unsigned long>(kMaxNameBytes));
  if (size + entries > kMaxTableEntries)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "%s: the scene holds %lu entries already (the limit)",
                 what, static_cast<unsigned long>(kMaxTableEntries));
}

// The operations of the edit hooks (their second argument).
enum X3dEdit : int { kEditAdd = 0, kEditUpdate = 1, kEditRemove = 2 };
// metaData's operations.
enum X3dMetaOp : int { kMetaGet = 0, kMetaSet = 1, kMetaAdd = 2, kMetaRemove = 3 };

// The function an edit hook's `op` stands for, for its messages.
const char* x3dEditName(int op, const char* add, const char* update, const char* remove) {
  return op == kEditAdd ? add : op == kEditUpdate ? update : remove;
}

// The editable scene of the hook's X3DScene object (argument 0); a TypeError when none.
vrml::Scene& x3dEditedScene(EsScript& self, duk_context* c, const char* what) {
  vrml::Scene* scene = x3dEditableSceneOf(self, c, 0);
  if (scene == nullptr) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s: the Script has no scene", what);
  return *scene;
}

// The non-NULL node of argument `idx`; a TypeError naming `what` otherwise.
vrml::NodePtr x3dNodeArg(EsScript& self, duk_context* c, duk_idx_t idx, const char* what) {
  FieldValue v = self.requireValue(c, idx, FieldType::SFNode, what);
  vrml::NodePtr n = v.get<FieldType::SFNode>();
  if (!n) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s: the node is NULL", what);
  return n;
}

// Every DEF name under `nodes` (depth first in file order, not inside PROTO instances,
// whose names are their bodies'), the first node of each name; the walk checks the
// Script's deadline.
void x3dCollectNamed(const std::vector<vrml::NodePtr>& nodes, EsScript& self, duk_context* c,
                     std::unordered_set<const vrml::Node*>& seen,
                     std::vector<std::pair<std::string, vrml::NodePtr>>& out, int depth) {
  if (depth > 512) return;  // as deep as the traversal walks (scene::kMaxWalkDepth)
  for (const vrml::NodePtr& n : nodes) {
    if (!n || !seen.insert(n.get()).second) continue;
    if ((seen.size() & 4095u) == 0) self.checkDeadline(c);
    if (!n->defName.empty() &&
        std::none_of(out.begin(), out.end(), [&](const auto& e) { return e.first == n->defName; }))
      out.emplace_back(n->defName, n);
    if (vrml::declaredInterface(*n) != nullptr) continue;
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const FieldValue& v = n->fieldAt(i);
      if (v.type() == FieldType::SFNode)
        x3dCollectNamed({v.get<FieldType::SFNode>()}, self, c, seen, out, depth + 1);
      else if (v.type() == FieldType::MFNode)
        x3dCollectNamed(v.get<FieldType::MFNode>(), self, c, seen, out, depth + 1);
    }
  }
}

// namedNodes(scene): {name: node, ...} of the names Scripts gave (first) and the scene's DEF
// names, one node per name, as getNamedNode answers them.
duk_ret_t x3dNamedNodes(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  std::vector<std::pair<std::string, vrml::NodePtr>> named;
  if (scene != nullptr) {
    for (auto it = scene->x3d.namedNodes.rbegin(); it != scene->x3d.namedNodes.rend(); ++it)
      if (std::none_of(named.begin(), named.end(),
                       [&](const auto& e) { return e.first == it->first; }))
        named.push_back(*it);
    std::unordered_set<const vrml::Node*> seen;
    x3dCollectNamed(scene->rootNodes, self, c, seen, named, 0);
  }
  duk_push_object(c);
  for (const auto& [name, node] : named) {
    self.pushNode(c, node);
    duk_put_prop_lstring(c, -2, name.data(), name.size());
  }
  return 1;
}

// Whether `name` names a node of `scene`: one a Script named, or a DEF name in its graph.
bool x3dNameInUse(EsScript& self, duk_context* c, const vrml::Scene& scene,
                  const std::string& name) {
  for (const auto& e : scene.x3d.namedNodes)
    if (e.first == name) return true;
  std::vector<std::pair<std::string, vrml::NodePtr>> named;
  std::unordered_set<const vrml::Node*> seen;
  x3dCollectNamed(scene.rootNodes, self, c, seen, named, 0);
  return std::any_of(named.begin(), named.end(), [&](const auto& e) { return e.first == name; });
}

// editNamedNode(scene, op, name, node): addNamedNode (a name in use: an Error), updateNamedNode
// (the node takes the name as its DEF name, and getNamedNode finds it under it) and
// removeNamedNode (the name's nodes lose it).
duk_ret_t x3dEditNamedNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const int op = duk_to_int(c, 1);
  const char* what = x3dEditName(op, "addNamedNode", "updateNamedNode", "removeNamedNode");
  vrml::Scene& scene = x3dEditedScene(self, c, what);
  const std::string name = x3dString(c, 2);
  auto& table = scene.x3d.namedNodes;
  if (op == kEditRemove) {
    for (const auto& e : table)
      if (e.first == name && e.second && e.second->defName == name) e.second->defName.clear();
    std::erase_if(table, [&](const auto& e) { return e.first == name; });
    std::vector<std::pair<std::string, vrml::NodePtr>> named;
    std::unordered_set<const vrml::Node*> seen;
    x3dCollectNamed(scene.rootNodes, self, c, seen, named, 0);
    for (const auto& e : named)
      if (e.first == name) e.second->defName.clear();
    return 0;
  }
  if (name.empty()) GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: the name is empty", what);
  vrml::NodePtr node = x3dNodeArg(self, c, 3, what);
  if (op == kEditAdd && x3dNameInUse(self, c, scene, name))
    GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: the name '%s' is in use", what, name.substr(0, 64).c_str());
  const auto replaced = [&](const auto& e) { return e.first == name || e.second == node; };
  x3dCheckTableRoom(
      c,
      table.size() - static_cast<std::size_t>(std::count_if(table.begin(), table.end(), replaced)),
      1, what, name);
  std::erase_if(table, replaced);
  node->defName = name;
  table.emplace_back(name, std::move(node));
  return 0;
}

// metaData(scene, op, name, values): getMetaData (an Array of the values of the META
// statements called `name`, or undefined), setMetaData (they become `values`), addMetaData
// (one more) and removeMetaData (none left).
duk_ret_t x3dMetaData(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const int op = duk_to_int(c, 1);
  const std::string name = x3dString(c, 2);
  if (op == kMetaGet) {
    const vrml::Scene* scene = x3dSceneOf(self, c, 0);
    duk_idx_t array = -1;
    duk_uarridx_t k = 0;
    if (scene != nullptr)
      for (const auto& [key, content] : scene->x3d.meta) {
        if (key != name) continue;
        if (array < 0) array = duk_push_array(c);
        duk_push_lstring(c, content.data(), content.size());
        duk_put_prop_index(c, array, k++);
      }
    if (array < 0) duk_push_undefined(c);
    return 1;
  }
  const char* what = op == kMetaSet   ? "setMetaData"
                     : op == kMetaAdd ? "addMetaData"
                                      : "removeMetaData";
  vrml::Scene& scene = x3dEditedScene(self, c, what);
  auto& meta = scene.x3d.meta;
  if (op == kMetaRemove) {
    std::erase_if(meta, [&](const auto& m) { return m.first == name; });
    return 0;
  }
  if (name.empty()) GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: the name is empty", what);
  FieldValue values = self.requireValue(c, 3, FieldType::MFString, what);
  const auto& list = values.get<FieldType::MFString>();
  if (list.empty()) GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: no value given", what);
  // What stays (setMetaData replaces the name's values), then what comes: checked first,
  // so a refused call changes nothing.
  const auto replaced = [&](const auto& m) { return op == kMetaSet && m.first == name; };
  std::size_t kept = 0, bytes = 0;
  for (const auto& m : meta)
    if (!replaced(m)) {
      ++kept;
      bytes += m.first.size() + m.second.size();
    }
  x3dCheckTableRoom(c, kept, list.size(), what, name);
  for (const std::string& v : list) bytes += name.size() + v.size();
  if (bytes > self.limits().heapBytes / 4)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR,
                 "%s: the scene's META statements would hold more than %lu bytes", what,
                 static_cast<unsigned long>(self.limits().heapBytes / 4));
  std::erase_if(meta, replaced);
  for (const std::string& v : list) meta.emplace_back(name, v);
  return 0;
}

// editExportedNode(scene, op, name, node): addExportedNode (a name in use: an Error),
// updateExportedNode (the scene EXPORTs `node` as `name`) and removeExportedNode.
duk_ret_t x3dEditExportedNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const int op = duk_to_int(c, 1);
  const char* what = x3dEditName(op, "addExportedNode", "updateExportedNode", "removeExportedNode");
  vrml::Scene& scene = x3dEditedScene(self, c, what);
  const std::string name = x3dString(c, 2);
  auto& exports = scene.x3d.exports;
  const auto named = [&](const vrml::X3dExport& e) { return e.exportedName == name; };
  if (op == kEditRemove) {
    std::erase_if(exports, named);
    return 0;
  }
  if (name.empty()) GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: the exported name is empty", what);
  vrml::NodePtr node = x3dNodeArg(self, c, 3, what);
  if (op == kEditAdd && std::any_of(exports.begin(), exports.end(), named))
    GS_DUK_ERROR(c, DUK_ERR_ERROR, "%s: the exported name '%s' is in use", what,
                 name.substr(0, 64).c_str());
  x3dCheckTableRoom(c,
                    exports.size() - static_cast<std::size_t>(
                                         std::count_if(exports.begin(), exports.end(), named)),
                    1, what, name);
  std::erase_if(exports, named);
  exports.push_back({node->defName, name, std::move(node), {}});
  return 0;
}

// routes(scene): [[fromNode, fromField, toNode, toField], ...] of the scene's ROUTEs (its
// file's, then those its addRoute made) that are still in place, each once; the walk
// checks the Script's deadline.
duk_ret_t x3dRoutes(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  duk_push_array(c);
  if (scene == nullptr) return 1;
  duk_uarridx_t k = 0;
  std::unordered_set<std::string> listed;
  std::size_t walked = 0;
  for (const auto* list : {&scene->routes, &scene->x3d.scriptRoutes})
    for (const vrml::Route& r : *list) {
      if ((++walked & 1023u) == 0) self.checkDeadline(c);
      if (!r.fromNode || !r.toNode) continue;
      std::string key =
          std::to_string(reinterpret_cast<std::uintptr_t>(r.fromNode.get())) + ' ' + r.fromField +
          ' ' + std::to_string(reinterpret_cast<std::uintptr_t>(r.toNode.get())) + ' ' + r.toField;
      if (listed.count(key) != 0) continue;
      if (!self.context().hasRoute(r.fromNode, r.fromField, r.toNode, r.toField)) continue;
      listed.insert(std::move(key));
      duk_push_array(c);
      self.pushNode(c, r.fromNode);
      duk_put_prop_index(c, -2, 0);
      duk_push_lstring(c, r.fromField.data(), r.fromField.size());
      duk_put_prop_index(c, -2, 1);
      self.pushNode(c, r.toNode);
      duk_put_prop_index(c, -2, 2);
      duk_push_lstring(c, r.toField.data(), r.toField.size());
      duk_put_prop_index(c, -2, 3);
      duk_put_prop_index(c, -2, k++);
    }
  return 1;
}

// editUnit(scene, category, name, conversionFactor): X3DScene.updateUnit (as X_ITE 15
// names it): the scene's UNIT statement of `category` (angle, force, length or mass) names
// `name`, `conversionFactor` base units each. The values already read keep their units:
// the statement is the scene's record (X3DScene.units, toVRMLString).
duk_ret_t x3dEditUnit(duk_context* c) {
  EsScript& self = EsScript::of(c);
  vrml::Scene& scene = x3dEditedScene(self, c, "updateUnit");
  const std::string category = x3dString(c, 1);
  const std::string name = x3dString(c, 2);
  const double factor = duk_to_number(c, 3);
  if (category != "angle" && category != "force" && category != "length" && category != "mass")
    GS_DUK_ERROR(c, DUK_ERR_ERROR,
                 "updateUnit: no unit category '%s' (angle, force, length or mass)",
                 category.substr(0, 64).c_str());
  if (!std::isfinite(factor) || factor <= 0.0)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "updateUnit: the conversion factor is no positive number");
  x3dCheckTableRoom(c, 0, 0, "updateUnit", name);
  std::erase_if(scene.x3d.units, [&](const vrml::X3dUnit& u) { return u.category == category; });
  scene.x3d.units.push_back({category, name, factor});
  return 0;
}

// editComponent(scene, op, name, level): X3DScene.addComponent (a component the scene
// names already: an Error), updateComponent (its level set, or it added) and
// removeComponent (as X_ITE 15 names them): the scene's COMPONENT statements.
duk_ret_t x3dEditComponent(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const int op = duk_to_int(c, 1);
  const char* what = x3dEditName(op, "addComponent", "updateComponent", "removeComponent");
  vrml::Scene& scene = x3dEditedScene(self, c, what);
  const std::string name = x3dString(c, 2);
  auto& table = scene.x3d.components;
  const auto it =
      std::find_if(table.begin(), table.end(), [&](const auto& e) { return e.first == name; });
  if (op == kEditRemove) {
    if (it != table.end()) table.erase(it);
    return 0;
  }
  const double level = duk_to_number(c, 3);
  if (!(level >= 1.0 && level <= 100.0))
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "%s: the level is no number from 1 to 100", what);
  if (it != table.end()) {
    if (op == kEditAdd)
      GS_DUK_ERROR(c, DUK_ERR_ERROR, "addComponent: the scene names the component '%s' already",
                   name.substr(0, 64).c_str());
    it->second = static_cast<int>(level);
    return 0;
  }
  x3dCheckTableRoom(c, table.size(), 1, what, name);
  table.emplace_back(name, static_cast<int>(level));
  return 0;
}

}  // namespace

void installX3DSceneEdits(duk_context* c) {
  static constexpr NativeFunction kHooks[] = {
      {"namedNodes", x3dNamedNodes, 1},
      {"editNamedNode", x3dEditNamedNode, 4},
      {"metaData", x3dMetaData, 4},
      {"editExportedNode", x3dEditExportedNode, 4},
      {"routes", x3dRoutes, 1},
      {"editUnit", x3dEditUnit, 4},
      {"editComponent", x3dEditComponent, 4},
  };
  putNativeFunctions(c, kHooks);
}

}  // namespace gs::runtime::es
