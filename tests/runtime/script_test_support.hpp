// A ScriptContext that records what a Script asks of the browser, and helpers that parse
// Script nodes from VRML text, for the ECMAScript host's tests.
#pragma once

#include "encodings/parser.hpp"
#include "runtime/script_ecmascript.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace gs::test {

struct FakeScriptContext : runtime::ScriptContext {
  struct Event {
    vrml::Node* node = nullptr;
    int field = -1;
    vrml::FieldValue value;
  };
  std::vector<Event> emitted;  // emitScriptEvent
  std::vector<Event> sent;     // sendEvent
  std::vector<vrml::Diagnostic> diagnostics;
  std::vector<std::string> printed;
  std::vector<std::string> routes;  // "add A.x B.y" / "delete A.x B.y"
  std::vector<std::vector<std::string>> loaded;
  std::vector<vrml::NodePtr> replacedWith;
  std::string description;
  std::map<std::string, std::string> files;  // fetchText
  std::vector<std::shared_ptr<vrml::Scene>> created;
  const vrml::Scene* world = nullptr;  // currentScene
  const vrml::Scene* own = nullptr;    // sceneOf: the Inline's world the Script is in
  double time = 1000.0;
  double fps = 0.0;

  void emitScriptEvent(vrml::Node& script, int field, vrml::FieldValue value) override {
    script.setField(static_cast<std::size_t>(field), value);
    emitted.push_back({&script, field, std::move(value)});
  }
  /// Called by sendEvent when set (a browser that delivers events at once).
  std::function<void(vrml::Node&, int, const vrml::FieldValue&)> onSend;

  void sendEvent(vrml::Node& node, int field, vrml::FieldValue value) override {
    sent.push_back({&node, field, value});
    if (onSend) onSend(node, field, value);
  }
  double now() const override { return time; }
  double frameRate() const override { return fps; }
  std::string worldUrl() const override { return "file:///worlds/test.wrl"; }
  bool addRoute(const vrml::NodePtr& from, const std::string& eventOut, const vrml::NodePtr& to,
                const std::string& eventIn) override {
    routes.push_back("add " + from->defName + "." + eventOut + " " + to->defName + "." + eventIn);
    return true;
  }
  bool deleteRoute(const vrml::NodePtr& from, const std::string& eventOut, const vrml::NodePtr& to,
                   const std::string& eventIn) override {
    routes.push_back("delete " + from->defName + "." + eventOut + " " + to->defName + "." +
                     eventIn);
    return true;
  }
  std::vector<vrml::NodePtr> createVrmlFromString(const std::string& text) override {
    return createSceneFromString(text, nullptr)->rootNodes;
  }
  std::shared_ptr<vrml::Scene> createSceneFromString(const std::string& text, const vrml::Node*,
                                                     const std::string& = {}) override {
    const bool header = text.starts_with("#VRML") || text.starts_with("#X3D");
    auto scene = std::make_shared<vrml::Scene>(
        vrml::parseVrml(header ? text : "#VRML V2.0 utf8\n" + text, "createVrmlFromString"));
    created.push_back(scene);
    return scene;
  }
  void loadUrl(const std::vector<std::string>& url,
               const std::vector<std::string>& parameter) override {
    std::vector<std::string> both = url;
    both.insert(both.end(), parameter.begin(), parameter.end());
    loaded.push_back(both);
  }
  bool fetchText(const std::string& url, std::string& text, std::string& error) override {
    auto it = files.find(url);
    if (it == files.end()) {
      error = "cannot read '" + url + "': no such file";
      return false;
    }
    text = it->second;
    return true;
  }
  void replaceWorld(const std::vector<vrml::NodePtr>& nodes) override { replacedWith = nodes; }
  void setDescription(const std::string& text) override { description = text; }
  const vrml::Scene* currentScene() const override { return world; }
  const vrml::Scene* sceneOf(const vrml::Node&) const override { return own ? own : world; }
  void print(const std::string& text) override { printed.push_back(text); }
  void scriptDiagnostic(vrml::Severity severity, const vrml::SourceLocation& where,
                        const std::string& message) override {
    diagnostics.push_back({severity, where, message});
  }

  /// Every diagnostic formatted, one per line (for failure messages).
  std::string diagnosticText() const {
    std::string s;
    for (const auto& d : diagnostics) s += d.format() + "\n";
    return s;
  }
  /// The events emitted for field `name` of `script`.
  std::vector<vrml::FieldValue> emittedFor(const vrml::Node& script,
                                           const std::string& name) const {
    int f = script.type().findExact(name);
    std::vector<vrml::FieldValue> out;
    for (const auto& e : emitted)
      if (e.node == &script && e.field == f) out.push_back(e.value);
    return out;
  }
};

/// A parsed world and its first Script node (DEF S when there is one).
struct ScriptWorld {
  vrml::Scene scene;
  vrml::NodePtr script;
  std::unique_ptr<runtime::ScriptInstance> instance;

  int field(const std::string& name) const { return script->type().findExact(name); }
};

inline vrml::NodePtr findScript(const std::vector<vrml::NodePtr>& nodes) {
  for (const auto& n : nodes) {
    if (!n) continue;
    if (n->type().script) return n;
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() == vrml::FieldType::SFNode) {
        if (auto s = findScript({v.get<vrml::FieldType::SFNode>()})) return s;
      } else if (v.type() == vrml::FieldType::MFNode) {
        if (auto s = findScript(v.get<vrml::FieldType::MFNode>())) return s;
      }
    }
  }
  return nullptr;
}

/// Limits for tests that do not test the time limit: a call may take long on a loaded
/// machine under the sanitizers.
inline runtime::ScriptLimits relaxedLimits() {
  runtime::ScriptLimits l;
  l.callSeconds = 30;
  return l;
}

/// Parses `vrml` (a whole file, header included) named `url` and makes the instance of
/// its Script with `limits`.
inline ScriptWorld loadScript(FakeScriptContext& ctx, const std::string& vrml,
                              runtime::ScriptLimits limits = relaxedLimits(),
                              const std::string& url = "test.wrl") {
  ScriptWorld w;
  w.scene = vrml::parseVrml(vrml, url);
  for (const auto& d : w.scene.diagnostics.items) INFO(d.format());
  w.script = findScript(w.scene.rootNodes);
  REQUIRE(w.script);
  w.instance = runtime::ecmascriptFactory()(*w.script, ctx, limits);
  return w;
}

/// A Script in an Inline's world: the world (an empty Group) read from `worldUrl`, the
/// Inline's world `inner` (a whole file) read from `innerUrl`, both given to `ctx` as the
/// browser's world and the Script's own; the instance made from `inner`'s first Script
/// (null when it could not be made). Kept behind a pointer: `ctx` points into it.
struct InlineScript {
  vrml::Scene world, inner;
  vrml::NodePtr script;
  std::unique_ptr<runtime::ScriptInstance> instance;
};
inline std::unique_ptr<InlineScript> loadInlineScript(FakeScriptContext& ctx,
                                                      const std::string& worldUrl,
                                                      const std::string& inner,
                                                      const std::string& innerUrl) {
  auto s = std::make_unique<InlineScript>();
  s->world = vrml::parseVrml("#VRML V2.0 utf8\nGroup { }\n", worldUrl);
  s->inner = vrml::parseVrml(inner, innerUrl);
  s->script = findScript(s->inner.rootNodes);
  REQUIRE(s->script);
  ctx.world = &s->world;
  ctx.own = &s->inner;
  s->instance = runtime::ecmascriptFactory()(*s->script, ctx, relaxedLimits());
  return s;
}

/// A world holding only `Script { <interface> url "javascript: <code>" }`.
inline std::string scriptWorld(const std::string& interface, const std::string& code) {
  return "#VRML V2.0 utf8\nDEF S Script {\n" + interface + "\nurl \"javascript:\n" + code +
         "\"\n}\n";
}

}  // namespace gs::test
