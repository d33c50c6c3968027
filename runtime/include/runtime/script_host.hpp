// The boundary between the execution model and a scripting language (clause 4.12
// "Scripting"; annex C, ECMAScript). The execution model calls a ScriptInstance for each
// Script node; the instance calls back through ScriptContext. Nothing here knows a
// language: runtime/script_ecmascript.hpp implements it with Duktape.
#pragma once

#include "vrml/diagnostic.hpp"
#include "vrml/field.hpp"
#include "vrml/node.hpp"
#include "vrml/scene.hpp"

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace gs::runtime {

/// Limits that keep a Script (untrusted content) from stopping the browser.
struct ScriptLimits {
  double callSeconds = 0.5;                     // wall time of one call (initialize, an eventIn...)
  std::size_t heapBytes = 64u * 1024u * 1024u;  // memory of one Script's heap
  /// Nodes the Scripts of one world made (createVrmlFromString, createX3DFromString,
  /// createNode, createProto, `new SFNode(text)`), all the world's life: they live
  /// outside the Scripts' heaps, and the execution model keeps every node it registered
  /// until the world goes (node identity), so without this bound a Script that makes nodes at
  /// every frame grows the browser's memory without end (about 600 bytes a node).
  std::size_t madeNodes = std::size_t{1} << 21;
  /// Memory of the heaps of all the Scripts of one world together (each is also held to
  /// heapBytes). An X3D Script's heap starts at about 0.7 MiB, a VRML97 one's at 0.3 MiB,
  /// so without it a file of 10,000 Script nodes (600 KB of text) would take 7 GB (500
  /// took 362 MB more than none).
  std::size_t worldHeapBytes = std::size_t{1} << 30;
  /// Routes the Scripts of one world added (Browser.addRoute, X3DExecutionContext.addRoute)
  /// and did not delete. Each costs about 24 bytes outside the heaps.
  std::size_t addedRoutes = std::size_t{1} << 22;
};

/// A Script asked for more than a ScriptLimits bound allows (ScriptContext::
/// createSceneFromString): the Script gets a RangeError with this message; nothing was
/// made.
class ScriptLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What the renderer can do, as a Script reads it with Browser.getRenderingProperty
/// (ISO/IEC 19775-2 clause 6.3.13, getRenderingProperties; the names X_ITE 15 answers).
/// Zero: not known.
struct RenderingProperties {
  int maxTextureSize = 0;    // MaxTextureSize: pixels per side of the largest texture drawn
  int textureUnits = 0;      // TextureUnits: textures one shape may combine (MultiTexture)
  int maxLights = 0;         // MaxLights: lights that light one shape at a time
  bool antialiased = false;  // Antialiased: the picture is multisampled
  int colorDepth = 0;        // ColorDepth: bits per pixel of colour (24 for RGB8)
};

/// What a running Script may ask of the browser (annex C.6 "Browser object" and the
/// eventOuts of its own node). Implemented by ExecutionModel.
class ScriptContext {
 public:
  virtual ~ScriptContext() = default;
  /// Sends eventOut `field` (an index into the Script node's type().fields, an eventOut
  /// or exposedField) with `value` at the current timestamp; the value is also stored as
  /// the field's last value. Wrong index or type: ignored with a diagnostic.
  virtual void emitScriptEvent(vrml::Node& script, int field, vrml::FieldValue value) = 0;
  /// Writes eventIn or exposedField `field` of another node directly (directOutput TRUE,
  /// 4.12.4): delivered as an event at the current timestamp.
  virtual void sendEvent(vrml::Node& node, int field, vrml::FieldValue value) = 0;
  /// The current SFTime in seconds.
  virtual double now() const = 0;
  /// Frames per second the window reaches (0 headless).
  virtual double frameRate() const = 0;
  /// URL of the world (Browser.getWorldURL).
  virtual std::string worldUrl() const = 0;
  /// Browser.addRoute / deleteRoute: field names as a ROUTE writes them. False (with a
  /// diagnostic) when the names do not resolve or the types differ.
  virtual bool addRoute(const vrml::NodePtr& from, const std::string& eventOut,
                        const vrml::NodePtr& to, const std::string& eventIn) = 0;
  virtual bool deleteRoute(const vrml::NodePtr& from, const std::string& eventOut,
                           const vrml::NodePtr& to, const std::string& eventIn) = 0;
  /// Whether the ROUTE from `eventOut` of `from` to `eventIn` of `to` is in place now
  /// (X3DExecutionContext.routes lists only those): names as addRoute takes them.
  virtual bool hasRoute(const vrml::NodePtr& from, const std::string& eventOut,
                        const vrml::NodePtr& to, const std::string& eventIn) const {
    (void)from;
    (void)eventOut;
    (void)to;
    (void)eventIn;
    return false;
  }
  /// Browser.createVrmlFromString: the root nodes of `text` parsed as a VRML97 file
  /// (relative URLs against the world's URL); parse errors become diagnostics. Text that
  /// starts with a "#VRML" or "#X3D" header is parsed as that header says
  /// (createX3DFromString, X3DScene.createNode).
  virtual std::vector<vrml::NodePtr> createVrmlFromString(const std::string& text) = 0;
  /// Browser.createX3DFromString (ISO/IEC 19777-1 clause 7.2.3): `text` read as
  /// createVrmlFromString reads it, its nodes live in the same way, and the whole scene
  /// returned: root nodes, DEF names, PROTO declarations, ROUTEs, header and EXPORTs. The
  /// default keeps only the root nodes. Never null. `script`: the Script that asks (null:
  /// none); a Script in an Inline's world (sceneOf) makes nodes that belong to that world:
  /// its URL is their base, and Scripts among them read their files under its rules.
  /// `url`: where the text was read from (createVrmlFromURL, createX3DFromURL), or empty;
  /// when given, the nodes belong to the text's own scene: its relative URLs resolve
  /// against `url`, and what it names is read under `url`'s rules (a text from the network
  /// names no local file, whatever world asked for it). Throws ScriptLimitError when the
  /// nodes made would pass ScriptLimits::madeNodes (none is kept then).
  virtual std::shared_ptr<vrml::Scene> createSceneFromString(const std::string& text,
                                                             const vrml::Node* script,
                                                             const std::string& url = {}) {
    (void)script;
    (void)url;
    auto scene = std::make_shared<vrml::Scene>();
    scene->rootNodes = createVrmlFromString(text);
    return scene;
  }
  /// The world the Script is in (the X3D binding's Browser.currentScene: root nodes, DEF
  /// names, header); null when there is none. Not owned; valid during the call.
  virtual const vrml::Scene* currentScene() const { return nullptr; }
  /// The world whose file holds `script` (the X3D binding's Browser.currentScene for that
  /// Script, as X_ITE gives a Script its execution context): an Inline's world for a Script
  /// inside it, else currentScene(). Not owned; valid during the call.
  virtual const vrml::Scene* sceneOf(const vrml::Node& script) const {
    (void)script;
    return currentScene();
  }
  /// The node an X3D IMPORT of the world names `localName` (X3D 4.0 clause 4.4.6) once
  /// its Inline's world has arrived and EXPORTs it; null before, or when there is none
  /// (X3DExecutionContext.getImportedNode).
  virtual vrml::NodePtr importedNode(const std::string& localName) const {
    (void)localName;
    return nullptr;
  }
  /// X3DScene.addRootNode (19777-1): `node` becomes the world's last root node (nothing
  /// when it is one already); it is drawn, and its sensors, interpolators and Scripts run.
  /// False when nothing changed.
  virtual bool addRootNode(const vrml::NodePtr& node) {
    (void)node;
    return false;
  }
  /// X3DScene.removeRootNode: `node` is no longer a root node of the world (its first
  /// place among them is removed); false when it was none.
  virtual bool removeRootNode(const vrml::NodePtr& node) {
    (void)node;
    return false;
  }
  /// X3DScene.addRootNode (`add`) or removeRootNode on an Inline's world, `scene` (one
  /// sceneOf gave for a Script inside it): as on the world, the node is drawn as the
  /// Inline's last child, and its sensors, interpolators and Scripts run (their bindable
  /// nodes are not bound, as an Inline's are not). False when nothing changed, when
  /// `scene` is no Inline's world this browser holds, or for a removal while the world is
  /// being read (a Script's code at its load). An Inline's world read once for several
  /// Inlines of one URL is one scene: the change shows in each.
  virtual bool changeInlineRoots(const vrml::Scene& scene, const vrml::NodePtr& node, bool add) {
    (void)scene;
    (void)node;
    (void)add;
    return false;
  }
  /// Browser.loadURL(url, parameter) and Anchor activation: the browser follows the
  /// loader's rules (4.12.10.3, 6.2); nothing happens at once.
  virtual void loadUrl(const std::vector<std::string>& url,
                       const std::vector<std::string>& parameter) = 0;
  /// The text at `url` (a Script's url entry that is not inline source), resolved
  /// against the world's URL under the loader's rules (remote content may name only
  /// http(s) URLs). False with `error` ("cannot read 'URL': why") when it cannot be read.
  virtual bool fetchText(const std::string& url, std::string& text, std::string& error) = 0;
  /// Browser.replaceWorld(nodes) (annex C.6.1; ISO/IEC 19777-1 takes an X3DScene, whose
  /// root nodes are passed): the world's root nodes become `nodes` (nulls and repeats
  /// left out), the old ones are no longer drawn, every bindable stack is emptied (its top
  /// sent isBound FALSE) and the first Viewpoint, NavigationInfo, Background and Fog among
  /// the new nodes are bound, as when a world loads (4.6.10).
  virtual void replaceWorld(const std::vector<vrml::NodePtr>& nodes) = 0;
  /// Browser.setDescription(text).
  virtual void setDescription(const std::string& text) = 0;
  /// Browser.getBrowserOption(name) (ISO/IEC 19777-1 clause 7.2.3; the option names of
  /// ISO/IEC 19775-1's table of browser options, "Shading" ...): the option's value, or
  /// null when the browser has no such option a world may read.
  virtual const std::string* browserOption(const std::string& name) const {
    (void)name;
    return nullptr;
  }
  /// Browser.setBrowserOption(name, value): true when the browser has the option and takes
  /// the value (from the next frame on); false, nothing changed, otherwise.
  virtual bool setBrowserOption(const std::string& name, const std::string& value) {
    (void)name;
    (void)value;
    return false;
  }
  /// Browser.getRenderingProperty's answers (Shading is the browser option's); null when
  /// the host gives none (the property is then undefined to the Script).
  virtual const RenderingProperties* renderingProperties() const { return nullptr; }
  /// print() / Browser.print: a line for the console (stderr).
  virtual void print(const std::string& text) = 0;
  /// A problem of the Script (error, limit reached); `where` names the world's file:line
  /// of the Script node; `message` the Script's own line where known.
  virtual void scriptDiagnostic(vrml::Severity severity, const vrml::SourceLocation& where,
                                const std::string& message) = 0;

  /// What the Scripts of this context's world use together, counted by the Script host
  /// against ScriptLimits::worldHeapBytes and addedRoutes: the bytes of their heaps, and the
  /// routes they added and did not delete.
  struct ScriptsInUse {
    std::size_t heapBytes = 0;
    std::size_t routes = 0;
    std::size_t refused = 0;  // Scripts that could not start for heapBytes (said once)
  };
  ScriptsInUse& scriptsInUse() { return inUse_; }

 private:
  ScriptsInUse inUse_;
};

/// The browser events an X3D Script's browser callbacks hear (ISO/IEC 19777-1 7.2;
/// the values are X3DConstants' numbers). SHUTDOWN_EVENT goes with shutdown(); this
/// browser has no external connection to lose, so CONNECTION_ERROR (0) is never sent.
enum class BrowserEvent : int {
  initialized = 2,          // INITIALIZED_EVENT: the world's file was read to its end
  initializationError = 4,  // INITIALIZED_ERROR: it was not, or a link could not open
};

/// One running Script node. Calls arrive on the drawing thread, in event order.
class ScriptInstance {
 public:
  virtual ~ScriptInstance() = default;
  /// initialize() (4.12.3), once, before any eventIn.
  virtual void initialize(double timestamp) = 0;
  /// The eventIn (or exposedField) `field` of the Script node received `value`: calls the
  /// function of that name with (value, timestamp) (C.4.2).
  virtual void eventIn(int field, const vrml::FieldValue& value, double timestamp) = 0;
  /// eventsProcessed() after a cascade that delivered events to this Script (4.12.6).
  virtual void eventsProcessed(double timestamp) = 0;
  /// shutdown() when the world is unloaded (4.12.3). An X3D Script's browser callbacks
  /// for SHUTDOWN_EVENT run first.
  virtual void shutdown(double timestamp) = 0;
  /// A browser event (ExecutionModel::worldLoaded, linkFailed): an X3D Script's browser
  /// callbacks for `event` run (ISO/IEC 19777-1 7.2, addBrowserListener; X_ITE 15's
  /// addBrowserCallback). None by default.
  virtual void browserEvent(BrowserEvent event, double timestamp) {
    (void)event;
    (void)timestamp;
  }
  /// Whether the Script was stopped (an error or a limit): no more calls are made.
  virtual bool stopped() const = 0;
};

/// What one entry of a Script's url field is (VRML97 6.40 and annex C.2).
struct ScriptUrlEntry {
  enum class Kind {
    empty,         ///< blank: skipped
    inlineSource,  ///< `javascript:`, `ecmascript:` or `vrmlscript:` (any case) and its code
    java,          ///< a `.class` file or a `java:` URL: not run
    file,          ///< any other: a file or URL to read (ScriptContext::fetchText)
  } kind = Kind::empty;
  /// inlineSource: the scheme as this browser names it ("javascript:" ...).
  std::string_view scheme;
  /// inlineSource: the code after the scheme; java and file: the entry without its
  /// leading blanks. Views into the entry given.
  std::string_view text;
};

/// Classifies `entry` (leading blanks skipped).
ScriptUrlEntry classifyScriptUrl(std::string_view entry);

/// Makes the instance for a Script node from the first of its url entries it can run
/// (`javascript:` / `ecmascript:` / `vrmlscript:` inline, or a file or URL read with
/// ScriptContext::fetchText). Null (with a diagnostic through `ctx`) when none can run.
using ScriptFactory = std::function<std::unique_ptr<ScriptInstance>(
    vrml::Node& script, ScriptContext& ctx, const ScriptLimits& limits)>;

}  // namespace gs::runtime
