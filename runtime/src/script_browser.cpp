// The Browser object of annex C.6.1 (ISO/IEC 14772-1) and the global print(): thin
// calls into ScriptContext, with their arguments converted to VRML values.
#include "script_ecmascript_internal.hpp"

#include <algorithm>
#include <chrono>
#include <string_view>
#include <utility>

#ifndef GS_VERSION
#define GS_VERSION "0"
#endif

namespace gs::runtime::es {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

constexpr std::size_t kMaxPrint = 16384;  // bytes of one print() line

std::string stringArg(duk_context* c, duk_idx_t idx) {
  duk_size_t len = 0;
  const char* s = duk_to_lstring(c, idx, &len);
  return std::string(s, len);
}

duk_ret_t print(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::string line;
  duk_idx_t n = duk_get_top(c);
  for (duk_idx_t i = 0; i < n && line.size() < kMaxPrint; ++i) {
    if (i > 0) line += ' ';
    line += stringArg(c, i);
  }
  if (line.size() > kMaxPrint) {
    line.resize(kMaxPrint);
    line += "... (print() output cut at " + std::to_string(kMaxPrint) + " bytes)";
  }
  self.context().print(line);
  return 0;
}

duk_ret_t getName(duk_context* c) {
  duk_push_string(c, "GhostSpace");
  return 1;
}

duk_ret_t getVersion(duk_context* c) {
  duk_push_string(c, GS_VERSION);
  return 1;
}

duk_ret_t getCurrentTime(duk_context* c) {
  duk_push_number(c, EsScript::of(c).context().now());
  return 1;
}

duk_ret_t getCurrentFrameRate(duk_context* c) {
  duk_push_number(c, EsScript::of(c).context().frameRate());
  return 1;
}

// getBrowserProperty(name) (ISO/IEC 19777-1 clause 7.2.3; the property names of ISO/IEC
// 19775-2 6.3.12, as X_ITE answers them): whether this browser has the capability. What a
// Script can do here: abstract node types (X3DConstants, getNodeType), concrete ones
// (createNode), PROTO instances (createProto) and files of the Classic VRML and XML
// encodings; no external SAI, no DOM import and no binary encoding. Any other name: false.
duk_ret_t getBrowserProperty(duk_context* c) {
  static constexpr std::pair<std::string_view, bool> kProperties[] = {
      {"ABSTRACT_NODES", true},        {"CONCRETE_NODES", true},  {"EXTERNAL_INTERACTIONS", false},
      {"PROTOTYPE_CREATE", true},      {"DOM_IMPORT", false},     {"XML_ENCODING", true},
      {"CLASSIC_VRML_ENCODING", true}, {"BINARY_ENCODING", false}};
  const std::string name = stringArg(c, 0);
  bool has = false;
  for (const auto& [key, value] : kProperties)
    if (name == key) has = value;
  duk_push_boolean(c, has);
  return 1;
}

// Its browser options: those the host has (ExecutionOptions::browserOptions, "Shading";
// X_ITE's test worlds switch it with buttons). getBrowserOption(name) gives the value, or
// undefined for an option the browser has not; setBrowserOption(name, value) answers
// whether the value was taken.
duk_ret_t getBrowserOption(duk_context* c) {
  const std::string* value = EsScript::of(c).context().browserOption(stringArg(c, 0));
  if (value == nullptr)
    duk_push_undefined(c);
  else
    duk_push_lstring(c, value->data(), value->size());
  return 1;
}

duk_ret_t setBrowserOption(duk_context* c) {
  duk_push_boolean(c, EsScript::of(c).context().setBrowserOption(stringArg(c, 0), stringArg(c, 1)));
  return 1;
}

duk_ret_t getCurrentSpeed(duk_context* c) {
  duk_push_number(c, 0.0);  // the viewer's speed is not known to the runtime
  return 1;
}

duk_ret_t getWorldURL(duk_context* c) {
  std::string url = EsScript::of(c).context().worldUrl();
  duk_push_lstring(c, url.data(), url.size());
  return 1;
}

std::vector<vrml::NodePtr> nodesArg(EsScript& self, duk_context* c, duk_idx_t idx,
                                    const char* what) {
  FieldValue v = self.requireValue(c, idx, FieldType::MFNode, what);
  return std::move(v.get<FieldType::MFNode>());
}

std::vector<std::string> stringsArg(EsScript& self, duk_context* c, duk_idx_t idx,
                                    const char* what) {
  FieldValue v = self.requireValue(c, idx, FieldType::MFString, what);
  return std::move(v.get<FieldType::MFString>());
}

// replaceWorld(nodes), or replaceWorld(scene) as 19777-1 takes it: an object with
// rootNodes (createX3DFromString's X3DScene) is replaced by them.
duk_ret_t replaceWorld(duk_context* c) {
  EsScript& self = EsScript::of(c);
  if (duk_is_object(c, 0) && !duk_is_array(c, 0) && self.nodeAt(c, 0) == nullptr &&
      duk_has_prop_string(c, 0, "rootNodes")) {
    duk_get_prop_string(c, 0, "rootNodes");
    duk_replace(c, 0);
  }
  self.context().replaceWorld(nodesArg(self, c, 0, "Browser.replaceWorld"));
  return 0;
}

// Longest text for createVrmlFromString / createVrmlFromURL: the nodes it makes live
// outside the Script's heap, so the text is bounded by the heap's limit.
std::size_t maxVrmlText(std::size_t heapBytes) {
  return std::max<std::size_t>(65536, heapBytes / 64);
}

duk_ret_t createVrmlFromString(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::string text = stringArg(c, 0);
  std::size_t max = maxVrmlText(self.limits().heapBytes);
  if (text.size() > max)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR,
                 "Browser.createVrmlFromString: the text is longer than %lu bytes",
                 static_cast<unsigned long>(max));
  FieldValue nodes = FieldValue::make<FieldType::MFNode>(self.createFromText(c, text)->rootNodes);
  self.pushValue(c, nodes);
  return 1;
}

// createVrmlFromURL(url, node, event): reads the first url entry that can be read, parses
// it and sends its root nodes to eventIn `event` of `node` (C.6.1; the standard lets this
// happen later; here it happens during the call, as an event at the current timestamp).
duk_ret_t createVrmlFromURL(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::vector<std::string> urls = stringsArg(self, c, 0, "Browser.createVrmlFromURL url");
  FieldValue target = self.requireValue(c, 1, FieldType::SFNode, "Browser.createVrmlFromURL node");
  std::string event = stringArg(c, 2);
  vrml::NodePtr node = target.get<FieldType::SFNode>();
  if (!node) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "Browser.createVrmlFromURL: node is NULL");
  int field = node->type().findField(event);
  if (field < 0 || node->type().fields[static_cast<std::size_t>(field)].type != FieldType::MFNode ||
      node->type().fields[static_cast<std::size_t>(field)].access == vrml::AccessType::field ||
      node->type().fields[static_cast<std::size_t>(field)].access == vrml::AccessType::eventOut)
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "Browser.createVrmlFromURL: %s has no MFNode eventIn '%s'",
                 node->typeName().c_str(), event.c_str());
  for (const std::string& url : urls) {
    std::string text, error, resolved;
    if (!self.resolveOwnUrl(url, resolved, error)) {
      self.warn("Browser.createVrmlFromURL: " + error);
      continue;
    }
    // Reading does not count against the call's time budget.
    auto start = std::chrono::steady_clock::now();
    bool ok = self.context().fetchText(resolved, text, error);
    self.extendDeadline(std::chrono::steady_clock::now() - start);
    if (!ok) {
      self.warn("Browser.createVrmlFromURL: " +
                (error.empty() ? "cannot read '" + url + "'" : error));
      continue;
    }
    if (text.size() > maxVrmlText(self.limits().heapBytes)) {
      self.warn("Browser.createVrmlFromURL: '" + url + "' is too large for a Script");
      continue;
    }
    // The text's own URL is its base and its rules (a text from the network names no local
    // file, whatever world asked for it).
    FieldValue nodes =
        FieldValue::make<FieldType::MFNode>(self.createFromText(c, text, resolved)->rootNodes);
    self.sendChangedLiveFields(c, *node);  // what the Script changed in place before, first
    self.context().sendEvent(*node, field, std::move(nodes));
    return 0;
  }
  return 0;
}

// Browser.description (19777-1): setting it calls setDescription; reading it gives the
// last text set.
constexpr const char* kDescriptionKey = DUK_HIDDEN_SYMBOL("gsDescription");

duk_ret_t getDescription(duk_context* c) {
  duk_push_this(c);
  duk_get_prop_string(c, -1, kDescriptionKey);
  if (duk_is_undefined(c, -1)) duk_push_string(c, "");
  return 1;
}

duk_ret_t putDescription(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::string text = stringArg(c, 0);
  duk_push_this(c);
  duk_push_lstring(c, text.data(), text.size());
  duk_put_prop_string(c, -2, kDescriptionKey);
  self.context().setDescription(text);
  return 0;
}

// createX3DFromString(text) (ISO/IEC 19777-1 clause 7.2.3): as createVrmlFromString, for
// X3D Classic VRML text ("#X3D V3.3 utf8" assumed when it has no header); returns an
// X3DScene of the text's whole scene (EsScript::pushCreatedScene).
duk_ret_t createX3DFromString(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::string text = stringArg(c, 0);
  std::size_t max = maxVrmlText(self.limits().heapBytes);
  if (text.size() > max)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR,
                 "Browser.createX3DFromString: the text is longer than %lu bytes",
                 static_cast<unsigned long>(max));
  if (!text.starts_with("#X3D") && !text.starts_with("#VRML")) text = "#X3D V3.3 utf8\n" + text;
  self.pushCreatedScene(c, self.createFromText(c, text));
  return 1;
}

// createX3DFromURL(url, event, node) as 19777-1 orders it, or (url, node, event) as
// createVrmlFromURL does.
duk_ret_t createX3DFromURL(duk_context* c) {
  if (duk_is_string(c, 1) && duk_is_object(c, 2)) duk_swap(c, 1, 2);
  return createVrmlFromURL(c);
}

duk_ret_t route(duk_context* c, bool add) {
  EsScript& self = EsScript::of(c);
  const char* what = add ? "Browser.addRoute" : "Browser.deleteRoute";
  FieldValue from = self.requireValue(c, 0, FieldType::SFNode, what);
  std::string eventOut = stringArg(c, 1);
  FieldValue to = self.requireValue(c, 2, FieldType::SFNode, what);
  std::string eventIn = stringArg(c, 3);
  const vrml::NodePtr& a = from.get<FieldType::SFNode>();
  const vrml::NodePtr& b = to.get<FieldType::SFNode>();
  if (!a || !b) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s: a node is NULL", what);
  bool ok = self.route(c, add, a, eventOut, b, eventIn);
  duk_push_boolean(c, ok);
  return 1;
}

duk_ret_t addRoute(duk_context* c) {
  return route(c, true);
}
duk_ret_t deleteRoute(duk_context* c) {
  return route(c, false);
}

duk_ret_t loadURL(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::vector<std::string> url = stringsArg(self, c, 0, "Browser.loadURL url");
  std::vector<std::string> parameter;
  if (!duk_is_undefined(c, 1)) parameter = stringsArg(self, c, 1, "Browser.loadURL parameter");
  // A Script written in an Inline's world or an EXTERNPROTO's file names that file's URLs,
  // under its rules (a remote world's Script links to no local file).
  std::vector<std::string> own;
  for (const std::string& u : url) {
    std::string resolved, error;
    if (u.starts_with("#") || self.resolveOwnUrl(u, resolved, error))
      own.push_back(u.starts_with("#") ? u : resolved);
    else
      self.warn("Browser.loadURL: link not followed: " + error);
  }
  if (!own.empty()) self.context().loadUrl(own, parameter);
  return 0;
}

duk_ret_t setDescription(duk_context* c) {
  EsScript& self = EsScript::of(c);
  self.context().setDescription(stringArg(c, 0));
  return 0;
}

}  // namespace

void EsScript::installBrowser(duk_context* c) {
  static constexpr NativeFunction kBrowser[] = {
      {"getName", getName, 0},
      {"getVersion", getVersion, 0},
      {"getCurrentTime", getCurrentTime, 0},
      {"getCurrentFrameRate", getCurrentFrameRate, 0},
      {"getCurrentSpeed", getCurrentSpeed, 0},
      {"getWorldURL", getWorldURL, 0},
      {"replaceWorld", replaceWorld, 1},
      {"createVrmlFromString", createVrmlFromString, 1},
      {"createVrmlFromURL", createVrmlFromURL, 3},
      {"addRoute", addRoute, 4},
      {"deleteRoute", deleteRoute, 4},
      {"loadURL", loadURL, 2},
      {"setDescription", setDescription, 1},
      {"print", print, DUK_VARARGS},
      // ISO/IEC 19777-1 additions
      {"println", print, DUK_VARARGS},
      {"createX3DFromString", createX3DFromString, 1},
      {"createX3DFromURL", createX3DFromURL, 3},
      {"getBrowserProperty", getBrowserProperty, 1},
      {"getBrowserOption", getBrowserOption, 1},
      {"setBrowserOption", setBrowserOption, 2},
  };
  duk_push_global_object(c);
  duk_push_object(c);
  putNativeFunctions(c, kBrowser);
  // 19777-1's properties: name and version, currentSpeed and currentFrameRate (read as
  // the get* functions answer), currentScene (the X3DScene made by kPreludeX3D).
  duk_push_string(c, "name");
  duk_push_string(c, "GhostSpace");
  duk_def_prop(c, -3, DUK_DEFPROP_HAVE_VALUE | DUK_DEFPROP_SET_ENUMERABLE);
  duk_push_string(c, "version");
  duk_push_string(c, GS_VERSION);
  duk_def_prop(c, -3, DUK_DEFPROP_HAVE_VALUE | DUK_DEFPROP_SET_ENUMERABLE);
  duk_push_string(c, "currentSpeed");
  duk_push_c_function(c, getCurrentSpeed, 0);
  duk_def_prop(c, -3, DUK_DEFPROP_HAVE_GETTER | DUK_DEFPROP_SET_ENUMERABLE);
  duk_push_string(c, "currentFrameRate");
  duk_push_c_function(c, getCurrentFrameRate, 0);
  duk_def_prop(c, -3, DUK_DEFPROP_HAVE_GETTER | DUK_DEFPROP_SET_ENUMERABLE);
  duk_push_string(c, "description");
  duk_push_c_function(c, getDescription, 0);
  duk_push_c_function(c, putDescription, 1);
  duk_def_prop(c, -4,
               DUK_DEFPROP_HAVE_GETTER | DUK_DEFPROP_HAVE_SETTER | DUK_DEFPROP_SET_ENUMERABLE);
  if (duk_has_prop_string(c, -2, "__gsScene")) {  // X3D Scripts only (EsScript::wantsX3D)
    duk_push_string(c, "currentScene");
    duk_get_prop_string(c, -3, "__gsScene");
    duk_def_prop(c, -3, DUK_DEFPROP_HAVE_VALUE | DUK_DEFPROP_SET_ENUMERABLE);
    duk_del_prop_string(c, -2, "__gsScene");
    duk_push_global_stash(c);
    duk_get_prop_string(c, -3, "__gsSceneMaker");
    duk_put_prop_string(c, -2, kSceneMakerKey);
    duk_pop(c);
    duk_del_prop_string(c, -2, "__gsSceneMaker");
  }
  if (duk_get_prop_string(c, -2, "__gsBrowserX3D")) {  // X3D Scripts: 19777-1's additions
    duk_dup(c, -2);
    duk_call(c, 1);
    duk_del_prop_string(c, -3, "__gsBrowserX3D");
  }
  duk_pop(c);
  duk_put_prop_string(c, -2, "Browser");
  // print(), and addRoute / deleteRoute without "Browser." as FreeWRL's tests use them.
  duk_push_c_function(c, print, DUK_VARARGS);
  duk_put_prop_string(c, -2, "print");
  duk_push_c_function(c, addRoute, 4);
  duk_put_prop_string(c, -2, "addRoute");
  duk_push_c_function(c, deleteRoute, 4);
  duk_put_prop_string(c, -2, "deleteRoute");
  duk_pop(c);
}

}  // namespace gs::runtime::es
