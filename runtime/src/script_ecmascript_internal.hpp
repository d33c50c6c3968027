// Internals of the ECMAScript Script host (runtime/script_ecmascript.hpp), shared by
// script_ecmascript.cpp (instance, calls, limits), script_values.cpp (SF/MF values and
// SFNode objects), script_browser.cpp (Browser object, print) and script_prelude.cpp.
#pragma once

#include "runtime/script_ecmascript.hpp"

#include <duktape.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace gs::runtime::es {

/// The SF/MF classes and VrmlMatrix in ECMAScript (script_prelude.cpp).
extern const char* const kPrelude;
/// The X3D classes (ISO/IEC 19777-1), X3DConstants and X3DScene, run after kPrelude
/// (script_prelude_x3d.cpp).
extern const char* const kPreludeX3D;

/// Per-heap accounting shared with Duktape's allocator and interrupt hooks (the heap's
/// udata).
class EsScript;

struct HeapGuard {
  EsScript* self = nullptr;  // the instance owning the heap (EsScript::of)
  std::size_t used = 0;      // bytes allocated by the heap (block headers included)
  std::size_t cap = 0;       // ScriptLimits::heapBytes
  /// The bytes of all the heaps of the Script's world (ScriptContext::scriptsInUse), and
  /// their bound (ScriptLimits::worldHeapBytes).
  std::size_t* worldUsed = nullptr;
  std::size_t worldCap = 0;
  bool overCap = false;       // an allocation was refused for the cap (either of them)
  bool overWorldCap = false;  // ... for the world's
  bool active = false;        // a call is running: the deadline applies
  bool timedOut = false;
  std::chrono::steady_clock::time_point deadline;
  unsigned allocTick = 0;
  /// True (and timedOut set) once the running call is past its deadline.
  bool pastDeadline();
};

class EsScript final : public ScriptInstance {
 public:
  EsScript(vrml::Node& node, ScriptContext& ctx, const ScriptLimits& limits);
  ~EsScript() override;
  EsScript(const EsScript&) = delete;
  EsScript& operator=(const EsScript&) = delete;

  /// Creates the heap, installs the globals and runs the first url entry that compiles.
  /// False (after diagnostics) when no entry could run.
  bool load();

  void initialize(double timestamp) override;
  void eventIn(int field, const vrml::FieldValue& value, double timestamp) override;
  void eventsProcessed(double timestamp) override;
  void shutdown(double timestamp) override;
  void browserEvent(BrowserEvent event, double timestamp) override;
  bool stopped() const override { return stopped_; }

  // ---- for the native functions ----
  static EsScript& of(duk_context* c);
  ScriptContext& context() { return ctx_; }
  const ScriptLimits& limits() const { return limits_; }
  /// Moves the running call's deadline by `d` (time spent waiting for the browser).
  void extendDeadline(std::chrono::steady_clock::duration d) { guard_->deadline += d; }
  vrml::Node& node() { return node_; }
  /// ScriptContext::createSceneFromString for this Script (every Browser and X3DScene call
  /// that makes nodes from text goes through it).
  /// `url`: where the text was read from (createVrmlFromURL), or empty.
  /// A ScriptLimitError becomes a RangeError of the Script (thrown through `c`).
  std::shared_ptr<vrml::Scene> createFromText(duk_context* c, const std::string& text,
                                              const std::string& url = {});
  /// What the Script's heap passed: its own limit or its world's (for diagnostics).
  std::string overCapText() const;
  /// ScriptContext::addRoute (`add`) or deleteRoute for this Script, the routes added
  /// counted against ScriptLimits::addedRoutes: past it, a RangeError through `c`.
  bool route(duk_context* c, bool add, const vrml::NodePtr& from, const std::string& eventOut,
             const vrml::NodePtr& to, const std::string& eventIn);
  /// `url` as the Script's own file names it: a Script written in an EXTERNPROTO's file
  /// (vrml::Node::urlBase) or in an Inline's world (ScriptContext::sceneOf) resolves it
  /// against that file, under that file's rules (a remote one names no local file: false
  /// with `error`); others leave it to ScriptContext::fetchText (`target` = `url`).
  bool resolveOwnUrl(const std::string& url, std::string& target, std::string& error);
  duk_context* heap() { return duk_; }
  /// Throws a RangeError when the running call is past its deadline (long native loops).
  void checkDeadline(duk_context* c);
  /// "Script 'NAME'" for messages.
  std::string name() const;
  void warn(const std::string& message);

  // ---- values (script_values.cpp) ----
  /// Pushes `v` as an ECMAScript value (numbers, strings, booleans, SF/MF objects).
  void pushValue(duk_context* c, const vrml::FieldValue& v);
  /// Converts the value at `idx` to type `t`; false with `why` when it cannot.
  bool toValue(duk_context* c, duk_idx_t idx, vrml::FieldType t, vrml::FieldValue& out,
               std::string& why);
  /// Like toValue, but throws a TypeError naming `what` when it cannot.
  vrml::FieldValue requireValue(duk_context* c, duk_idx_t idx, vrml::FieldType t, const char* what);
  /// Pushes the SFNode object of `n` (one object per node; null for a null pointer).
  void pushNode(duk_context* c, const vrml::NodePtr& n);
  /// The node of the SFNode object at `idx`; null (and `isNode` false) if it is none.
  vrml::NodePtr nodeAt(duk_context* c, duk_idx_t idx, bool* isNode = nullptr);
  /// Installs the SFNode hooks the prelude uses (__gsNodeFromString, __gsNodeName).
  void installNodeHooks(duk_context* c);
  /// After the prelude ran: remembers the prototypes of the SF/MF classes.
  void capturePrototypes(duk_context* c);

  // ---- a node's fields as live values (script_live_fields.cpp) ----
  /// Pushes field `i` of `n` as the running call sees it. An object-valued field (SF
  /// vectors, colours, rotations, images, every MF type) is one object for the whole call,
  /// its MF arrays filling grown elements with defaults (__gsLiveMF); what the Script
  /// changes in place (v.push(p), v.length = 0, v[i].x = 1) is sent to the node when the
  /// call returns, as X_ITE's fields are live objects (X3D 4.0 ECMAScript binding, ISO/IEC
  /// 19777-1 5.2: field values of nodes are read and written through their objects).
  void pushNodeField(duk_context* c, const vrml::NodePtr& n, std::size_t i);
  /// After the Script sent `v` to field `i` of `n`: later reads in this call see `v`.
  void assignedNodeField(duk_context* c, const vrml::NodePtr& n, std::size_t i,
                         const vrml::FieldValue& v);
  /// Before the Script sends an event to `n`: sends each live field of `n` it changed in
  /// place since (as flushLiveFields would at the call's end), so that the node gets the
  /// events in the order the Script made them (`t.children.length = 0; t.addChildren = x`
  /// empties the children, then adds x, as X_ITE runs it).
  /// `except`: a field left out (the one about to be assigned, whose live object the
  /// assignment replaces).
  void sendChangedLiveFields(duk_context* c, const vrml::Node& n,
                             std::size_t except = static_cast<std::size_t>(-1));
  /// Sends each live field that differs from the node's value (or from the value last
  /// assigned to it) to its node as an event, then forgets them all.
  void flushLiveFields(duk_context* c);
  /// Forgets the live fields without sending them (a call stopped by a limit).
  void forgetLiveFields();
  /// The value of the object the Script holds in live slot `slot`, as type `t` (toValue:
  /// may run the Script's valueOf and getters); false with `why` when it is none.
  bool liveSlotValue(duk_context* c, std::size_t slot, vrml::FieldType t, vrml::FieldValue& v,
                     std::string& why);
  bool hasLiveFields() const { return !live_.empty(); }

  // ---- the X3D binding (script_x3d.cpp) ----
  /// Pushes a value of one of X3D's 22 types as an object of the X3D classes (SFDouble
  /// and MFDouble as numbers); undefined for a VRML97 type.
  void pushX3DValue(duk_context* c, const vrml::FieldValue& v);
  /// Converts the value at `idx` to X3D single-valued type `t` (SFDouble ... SFMatrix4d);
  /// false with `why` when it cannot.
  bool toX3DSingle(duk_context* c, duk_idx_t idx, vrml::FieldType t, vrml::FieldValue& out,
                   std::string& why);
  /// Whether the Script gets the X3D classes: it is in an X3D world (its node type has
  /// X3D's `metadata` field, or currentScene() is X3D) or has a field of an X3D type.
  bool wantsX3D() const;
  /// Installs the natives the X3D prelude takes (__gsX3D): scene, routes, field
  /// definitions.
  void installX3DHooks(duk_context* c);
  /// Pushes what Browser.createX3DFromString returns for `scene` (ISO/IEC 19777-1 clause
  /// 7.2.3): in an X3D Script an X3DScene over it (rootNodes, getNamedNode, protos,
  /// createProto, addRootNode ... act on that scene, not the world); elsewhere an object
  /// with its rootNodes. The scene is kept for the Script's life, as its nodes are.
  void pushCreatedScene(duk_context* c, std::shared_ptr<vrml::Scene> scene);
  /// The scene createX3DFromString made that the X3DScene object at `idx` stands for;
  /// null for Browser.currentScene (the world's, ScriptContext::currentScene) or any
  /// object that is no created scene.
  vrml::Scene* createdSceneAt(duk_context* c, duk_idx_t idx);

  // ---- Browser object and print (script_browser.cpp) ----
  void installBrowser(duk_context* c);

 private:
  struct Call;
  friend struct Call;
  static duk_ret_t callTrampoline(duk_context* c, void* udata);

  void installFields(duk_context* c);
  /// Runs `fn` (a function name, or null for the global code in `source_`) with `arg`
  /// and `timestamp` under the limits, then sends the eventOuts it assigned. False when
  /// there was no such function.
  bool run(const char* fn, const vrml::FieldValue* arg, double timestamp, const char* what,
           bool sendEvents, const char* fallback = nullptr, int storeField = -1);
  /// Reports the error on the stack top (then pops it).
  void reportError(const char* what);
  /// Stops the Script after a limit: a diagnostic, and the heap is freed when no call is
  /// running.
  void stop(const std::string& why);
  void destroyHeap();

  static duk_ret_t fieldGetter(duk_context* c);
  static duk_ret_t fieldSetter(duk_context* c);
  static duk_ret_t nodeFieldGetter(duk_context* c);
  static duk_ret_t nodeFieldSetter(duk_context* c);
  // The declared interface of a PROTO instance (vrml::declaredInterface), by member index.
  static duk_ret_t protoFieldGetter(duk_context* c);
  static duk_ret_t protoFieldSetter(duk_context* c);
  void pushAccessor(duk_context* c, std::vector<void*>& cache, std::size_t index, duk_c_function fn,
                    duk_idx_t nargs);
  void pushProto(duk_context* c, vrml::FieldType t);
  bool toMF(duk_context* c, duk_idx_t idx, vrml::FieldType t, vrml::FieldValue& out,
            std::string& why);

  vrml::Node& node_;
  ScriptContext& ctx_;
  ScriptLimits limits_;
  std::unique_ptr<HeapGuard> guard_;
  duk_context* duk_ = nullptr;
  bool stopped_ = false;
  bool loadFailed_ = false;               // the url entry being loaded did not compile
  int errorCount_ = 0;                    // errors reported (past a few, no more are)
  int depth_ = 0;                         // nested calls (a native sending an event that re-enters)
  std::string source_;                    // the Script's code
  std::string sourceName_;                // "javascript:" or the URL it came from
  std::vector<void*> protos_;             // heap pointers of the SF/MF prototypes, by FieldType
  void* fieldStore_ = nullptr;            // array holding the Script's field values, by index
  void* nodeCache_ = nullptr;             // object: node id -> its SFNode object
  std::vector<char> dirty_;               // eventOut assigned in this call
  std::vector<char> touched_;             // eventOut read in this call (may be changed in place)
  std::vector<int> changed_;              // indexes dirty or touched in this call
  std::vector<vrml::FieldValue> last_;    // value each eventOut had when last sent/seen
  std::vector<void*> getters_, setters_;  // Script field accessors (by index)
  std::vector<void*> nodeGetters_, nodeSetters_;      // SFNode field accessors (by index)
  std::vector<void*> protoGetters_, protoSetters_;    // PROTO instance interface accessors
  std::vector<vrml::NodePtr> nodes_;                  // SFNode objects' nodes, by id
  std::vector<std::shared_ptr<vrml::Scene>> scenes_;  // createX3DFromString's, by id - 1
  std::unordered_map<const vrml::Node*, std::uint32_t> nodeIds_;
  /// A node field read as an object in this call; `assigned` holds what the Script last
  /// sent to it (the node still has its old value until the event is delivered).
  struct LiveField {
    vrml::NodePtr node;
    std::size_t field = 0;
    std::optional<vrml::FieldValue> assigned;
  };
  std::vector<LiveField> live_;  // by slot of liveStore_
  std::map<std::pair<const vrml::Node*, std::size_t>, std::uint32_t> liveSlots_;
  void* liveStore_ = nullptr;        // array: slot -> the object the Script holds
  std::vector<char> warnedMissing_;  // eventIn without a function: warned once
};

/// Throws an ECMAScript error from a native function, blamed on the Script's line that
/// called it (duk_error would blame the C++ source line: DUK_ERRCODE_FLAG_NOBLAME_FILELINE,
/// internal to duktape.c, is 1 << 24).
inline constexpr duk_errcode_t kNoBlameFileLine = 1L << 24;
#define GS_DUK_ERROR(c, code, ...) \
  duk_error_raw((c), (code) | ::gs::runtime::es::kNoBlameFileLine, nullptr, 0, __VA_ARGS__)

/// Hidden property of an SFNode object holding its node id.
inline constexpr const char* kNodeIdKey = DUK_HIDDEN_SYMBOL("gsNode");
/// The id of the scene an X3DScene object made by createX3DFromString stands for (1 is
/// the first); absent on Browser.currentScene.
inline constexpr const char* kSceneIdKey = DUK_HIDDEN_SYMBOL("gsScene");
/// Global stash entry: the X3D prelude's function that makes an X3DScene object.
inline constexpr const char* kSceneMakerKey = "gsSceneMaker";

/// A native function a Script calls: its name, the C function and its argument count
/// (DUK_VARARGS: any).
struct NativeFunction {
  const char* name;
  duk_c_function fn;
  duk_idx_t nargs;
};
/// Puts each of `functions` on the object at the top of the stack, under its name.
void putNativeFunctions(duk_context* c, std::span<const NativeFunction> functions);

// ---- the X3DScene natives' shared helpers (script_x3d.cpp) ----

/// The argument at `idx` as a string (ECMAScript's ToString).
std::string x3dString(duk_context* c, duk_idx_t idx);
/// The scene of the X3DScene object at `idx` (a hook's first argument, the method's
/// `this`): one createX3DFromString made, else the Script's own (Browser.currentScene: the
/// world, or the Inline's world the Script is in); null when there is none.
const vrml::Scene* x3dSceneOf(EsScript& self, duk_context* c, duk_idx_t idx);
/// x3dSceneOf's scene, to edit (its META statements, EXPORTs, names, ROUTE list).
vrml::Scene* x3dEditableSceneOf(EsScript& self, duk_context* c, duk_idx_t idx);
/// Whether the X3DScene object at `idx` is the Script's currentScene and that is an
/// Inline's world rather than the browser's.
bool x3dInlineScene(EsScript& self, duk_context* c, duk_idx_t idx);
/// Puts the natives of X3DScene's named nodes, META statements, EXPORT edits and route
/// list (script_x3d_scene.cpp) on the object at the top of the stack (__gsX3D).
void installX3DSceneEdits(duk_context* c);
/// Puts the natives of the browser's profiles, components and rendering properties and of
/// a scene's PROFILE, COMPONENT and UNIT statements (script_x3d_info.cpp) on the object at
/// the top of the stack (__gsX3D).
void installX3DInfo(duk_context* c);
/// Puts the natives that write a scene or a node as text (script_x3d_text.cpp) on the
/// object at the top of the stack (__gsX3D).
void installX3DText(duk_context* c);

/// Component `k` of a vector-like script object (SFVec3f, SFVec3d, SFColorRGBA, an array):
/// its property `name` ("x", "r" ...), else its index k, as a number (NaN when neither is
/// a number). Leaves the Duktape stack as it was (script_values.cpp).
double vectorComponent(duk_context* c, duk_idx_t obj, const char* name, duk_uarridx_t k);

}  // namespace gs::runtime::es
