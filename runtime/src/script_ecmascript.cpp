// The ECMAScript Script host: one Duktape heap per Script node, the calls the execution
// model makes (initialize, eventIns, eventsProcessed, shutdown) and the sandbox's limits
// (time budget per call through Duktape's interrupt hook, memory cap through the heap's
// allocator, native stack depth through DUK_USE_NATIVE_STACK_CHECK; cmake/Duktape.cmake).
#include "script_ecmascript_internal.hpp"

#include "base/sanitizers.hpp"
#include "base/url.hpp"

#include <pthread.h>
#include <algorithm>
#include <cassert>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string_view>

namespace {

using gs::runtime::es::HeapGuard;

// ---- Native stack: deep C recursion inside Duktape ends with a RangeError ----

// Duktape limits its C recursion by depth (1000 native calls), not by bytes: getters
// calling getters overflow an 8 MiB stack long before that (sanitizer builds sooner).
// DUK_USE_NATIVE_STACK_CHECK calls gs_duk_native_stack_check at each recursion point; it
// fails below tStackLimit: `kStackBudget` bytes under the outermost entry into Duktape on
// this thread, and never closer than `kStackReserve` to the end of the thread's stack.
#if defined(GS_ADDRESS_SANITIZER)
constexpr std::uintptr_t kStackBudget = 3u << 20;  // sanitizer frames are several times larger
constexpr std::uintptr_t kStackReserve = 1u << 20;
#else
constexpr std::uintptr_t kStackBudget = 1u << 20;
constexpr std::uintptr_t kStackReserve = 256u << 10;
#endif
thread_local std::uintptr_t tStackLimit = 0;  // 0: not inside Duktape

std::uintptr_t stackHere() {
  return reinterpret_cast<std::uintptr_t>(__builtin_frame_address(0));
}

// The lowest address of this thread's stack (0 if unknown).
std::uintptr_t threadStackLow() {
  thread_local std::uintptr_t low = [] {
    std::uintptr_t result = 0;
    pthread_attr_t attr;
    if (pthread_getattr_np(pthread_self(), &attr) == 0) {
      void* addr = nullptr;
      std::size_t size = 0;
      if (pthread_attr_getstack(&attr, &addr, &size) == 0)
        result = reinterpret_cast<std::uintptr_t>(addr);
      pthread_attr_destroy(&attr);
    }
    return result;
  }();
  return low;
}

/// Marks the outermost entry into Duktape on this thread.
class StackScope {
 public:
  StackScope() : outer_(tStackLimit == 0) {
    if (!outer_) return;
    std::uintptr_t here = stackHere();
    std::uintptr_t limit = here > kStackBudget ? here - kStackBudget : 1;
    std::uintptr_t low = threadStackLow();
    if (low != 0 && low < here && limit < low + kStackReserve)
      limit = std::min(here, low + kStackReserve);
    tStackLimit = limit;
  }
  ~StackScope() {
    if (outer_) tStackLimit = 0;
  }
  StackScope(const StackScope&) = delete;
  StackScope& operator=(const StackScope&) = delete;

 private:
  bool outer_;
};

// ---- The heap's allocator: counts bytes, refuses past the cap or the deadline ----

constexpr std::size_t kHeader = 16;  // keeps the block aligned as malloc's

std::size_t blockSize(void* ptr) {
  std::size_t size = 0;
  std::memcpy(&size, static_cast<char*>(ptr) - kHeader, sizeof size);
  return size;
}

// Whether an allocation that grows the heap by `grow` bytes may go ahead.
bool mayGrow(HeapGuard& g, std::size_t grow) {
  // Checking the clock in the allocator stops long native loops (a huge join, a
  // quadratic string build) where Duktape's interrupt does not run.
  if (g.active) {
    bool check = g.timedOut || (++g.allocTick & 63u) == 0 || grow > 65536;
    if (check && g.pastDeadline()) return false;
  }
  if (grow > g.cap || g.used > g.cap - grow) {
    g.overCap = true;
    return false;
  }
  if (g.worldUsed != nullptr && (grow > g.worldCap || *g.worldUsed > g.worldCap - grow)) {
    g.overCap = g.overWorldCap = true;
    return false;
  }
  return true;
}

// The heap's bytes and its world's change by `delta` bytes (grown or given back).
void account(HeapGuard& g, std::size_t add, std::size_t remove) {
  g.used = g.used + add - remove;
  if (g.worldUsed != nullptr) *g.worldUsed = *g.worldUsed + add - remove;
}

void* esAlloc(void* udata, duk_size_t size) {
  auto& g = *static_cast<HeapGuard*>(udata);
  if (!mayGrow(g, size + kHeader)) return nullptr;
  auto* base = static_cast<char*>(std::malloc(size + kHeader));
  if (base == nullptr) return nullptr;
  std::memcpy(base, &size, sizeof size);
  account(g, size + kHeader, 0);
  return base + kHeader;
}

void* esRealloc(void* udata, void* ptr, duk_size_t size) {
  if (ptr == nullptr) return esAlloc(udata, size);
  auto& g = *static_cast<HeapGuard*>(udata);
  std::size_t old = blockSize(ptr);
  if (size > old && !mayGrow(g, size - old)) return nullptr;
  auto* base = static_cast<char*>(std::realloc(static_cast<char*>(ptr) - kHeader, size + kHeader));
  if (base == nullptr) return nullptr;
  std::memcpy(base, &size, sizeof size);
  account(g, size, old);
  return base + kHeader;
}

void esFree(void* udata, void* ptr) {
  if (ptr == nullptr) return;
  auto& g = *static_cast<HeapGuard*>(udata);
  account(g, 0, blockSize(ptr) + kHeader);
  std::free(static_cast<char*>(ptr) - kHeader);
}

[[noreturn]] void esFatal(void*, const char* msg) {
  // Only reached through a bug of the host: every entry into Duktape is protected.
  std::fprintf(stderr, "ghostspace: fatal ECMAScript engine error: %s\n", msg ? msg : "?");
  std::abort();
}

std::string mib(std::size_t bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.4g MiB", static_cast<double>(bytes) / (1024.0 * 1024.0));
  return buf;
}

constexpr int kMaxReportedErrors = 20;

// `source` compiled (a heap loads bytecode several times faster than it compiles the
// source); empty if that failed (each heap then compiles the source).
std::string compileBytecode(const char* source, const char* name) {
  std::string out;
  duk_context* c = duk_create_heap(nullptr, nullptr, nullptr, nullptr, esFatal);
  if (c == nullptr) return out;
  duk_push_string(c, name);
  if (duk_pcompile_string_filename(c, 0, source) == 0) {
    duk_dump_function(c);
    duk_size_t size = 0;
    const void* data = duk_get_buffer(c, -1, &size);
    if (data != nullptr) out.assign(static_cast<const char*>(data), size);
  }
  duk_destroy_heap(c);
  return out;
}

// The preludes compiled once per process.
const std::string& preludeBytecode() {
  static const std::string bytecode = compileBytecode(gs::runtime::es::kPrelude, "prelude");
  return bytecode;
}
const std::string& preludeX3DBytecode() {
  static const std::string bytecode = compileBytecode(gs::runtime::es::kPreludeX3D, "prelude-x3d");
  return bytecode;
}

// Runs prelude `source` (its bytecode when there is some) in heap `c`.
void runPrelude(duk_context* c, const char* source, const char* name, const std::string& bytecode) {
  if (bytecode.empty()) {
    duk_push_string(c, name);
    duk_compile_string_filename(c, 0, source);
  } else {
    void* buf = duk_push_fixed_buffer(c, bytecode.size());
    std::memcpy(buf, bytecode.data(), bytecode.size());
    duk_load_function(c);
  }
  duk_call(c, 0);
  duk_pop(c);
}

}  // namespace

// Duktape's hooks (declared in the generated duk_config.h).
int gs_duk_exec_timeout_check(void* udata) {
  auto* g = static_cast<HeapGuard*>(udata);
  return (g != nullptr && g->active && g->pastDeadline()) ? 1 : 0;
}

int gs_duk_native_stack_check(void) {
  return (tStackLimit != 0 && stackHere() < tStackLimit) ? 1 : 0;
}

namespace gs::runtime {

namespace es {

bool HeapGuard::pastDeadline() {
  if (!timedOut && std::chrono::steady_clock::now() > deadline) timedOut = true;
  return timedOut;
}

struct EsScript::Call {
  EsScript* self = nullptr;
  const char* fn = nullptr;        // null: compile and run source_
  const char* fallback = nullptr;  // tried when there is no function `fn`
  int storeField = -1;             // an exposedField: `arg` is stored there first
  const vrml::FieldValue* arg = nullptr;
  double timestamp = 0.0;
  bool found = true;
  std::vector<std::pair<int, vrml::FieldValue>>* out = nullptr;  // collect step
  std::string* message = nullptr;                                // describe step
  int line = 0;                                                  // its line, 0: unknown
};

EsScript::EsScript(vrml::Node& node, ScriptContext& ctx, const ScriptLimits& limits)
    : node_(node), ctx_(ctx), limits_(limits), guard_(std::make_unique<HeapGuard>()) {
  guard_->self = this;
  guard_->worldUsed = &ctx_.scriptsInUse().heapBytes;
  guard_->worldCap = limits_.worldHeapBytes;
  std::size_t n = node_.fieldCount();
  dirty_.assign(n, 0);
  touched_.assign(n, 0);
  warnedMissing_.assign(n, 0);
  last_.reserve(n);
  for (std::size_t i = 0; i < n; ++i) last_.push_back(node_.fieldAt(i));
}

EsScript::~EsScript() {
  destroyHeap();
}

void EsScript::destroyHeap() {
  if (duk_ == nullptr) return;
  StackScope scope;
  guard_->active = false;
  duk_destroy_heap(duk_);
  duk_ = nullptr;
  nodes_.clear();
  scenes_.clear();
  nodeIds_.clear();
  live_.clear();
  liveSlots_.clear();
  liveStore_ = nullptr;
}

bool EsScript::resolveOwnUrl(const std::string& url, std::string& target, std::string& error) {
  const vrml::Scene* own = ctx_.sceneOf(node_);
  const std::string* base = node_.urlBase ? node_.urlBase.get()
                            : own != nullptr && own != ctx_.currentScene() && !own->url.empty()
                                ? &own->url
                                : nullptr;
  target = url;
  if (base == nullptr) return true;  // ScriptContext::fetchText resolves against the world
  target = base::resolveUrl(*base, url);
  return base::mayReference(*base, target, error);
}

EsScript& EsScript::of(duk_context* c) {
  duk_memory_functions funcs;
  duk_get_memory_functions(c, &funcs);
  return *static_cast<HeapGuard*>(funcs.udata)->self;
}

std::string EsScript::name() const {
  return node_.defName.empty() ? std::string("Script") : "Script '" + node_.defName + "'";
}

void EsScript::warn(const std::string& message) {
  ctx_.scriptDiagnostic(vrml::Severity::warning, node_.location, name() + ": " + message);
}

void EsScript::checkDeadline(duk_context* c) {
  if (guard_->active && guard_->pastDeadline())
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "execution timeout");
}

void EsScript::pushAccessor(duk_context* c, std::vector<void*>& cache, std::size_t index,
                            duk_c_function fn, duk_idx_t nargs) {
  if (cache.size() <= index) cache.resize(index + 1, nullptr);
  if (cache[index] != nullptr) {
    duk_push_heapptr(c, cache[index]);
    return;
  }
  duk_push_c_function(c, fn, nargs);
  duk_set_magic(c, -1, static_cast<duk_int_t>(index));
  cache[index] = duk_get_heapptr(c, -1);
  // Keep it reachable from the stash: the heap pointer stays valid while it is.
  duk_push_heap_stash(c);
  duk_get_prop_string(c, -1, "gsKeep");
  duk_dup(c, -3);
  duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(duk_get_length(c, -2)));
  duk_pop_2(c);
}

// ---- The Script's own fields and eventOuts as global accessor properties ----

namespace {
bool isOutput(vrml::AccessType a) {
  return a == vrml::AccessType::eventOut || a == vrml::AccessType::exposedField;
}
bool isScriptBuiltin(const vrml::NodeType& t, std::size_t i) {
  const std::string& n = t.fields[i].name;
  return i < 3 && (n == "url" || n == "directOutput" || n == "mustEvaluate");
}
}  // namespace

duk_ret_t EsScript::fieldGetter(duk_context* c) {
  EsScript& self = of(c);
  auto i = static_cast<std::size_t>(duk_get_current_magic(c));
  duk_push_heapptr(c, self.fieldStore_);
  duk_get_prop_index(c, -1, static_cast<duk_uarridx_t>(i));
  if (isOutput(self.node_.type().fields[i].access) && duk_is_object(c, -1) && !self.touched_[i]) {
    // Read as an object: it may be changed in place (v[1] = y, pos.x = 1); compared
    // with its last value when the call returns.
    self.touched_[i] = 1;
    if (!self.dirty_[i]) self.changed_.push_back(static_cast<int>(i));
  }
  return 1;
}

duk_ret_t EsScript::fieldSetter(duk_context* c) {
  EsScript& self = of(c);
  auto i = static_cast<std::size_t>(duk_get_current_magic(c));
  const vrml::FieldSpec& spec = self.node_.type().fields[i];
  vrml::FieldValue v = self.requireValue(c, 0, spec.type, spec.name.c_str());
  duk_push_heapptr(c, self.fieldStore_);
  self.pushValue(c, v);
  duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
  if (isOutput(spec.access)) {
    if (!self.dirty_[i] && !self.touched_[i]) self.changed_.push_back(static_cast<int>(i));
    self.dirty_[i] = 1;
  }
  return 0;
}

void EsScript::installFields(duk_context* c) {
  const vrml::NodeType& type = node_.type();
  duk_push_bare_array(c);
  fieldStore_ = duk_get_heapptr(c, -1);
  duk_push_heap_stash(c);
  duk_dup(c, -2);
  duk_put_prop_string(c, -2, "gsFields");
  duk_pop_2(c);
  duk_push_global_object(c);
  for (std::size_t i = 0; i < type.fields.size(); ++i) {
    const vrml::FieldSpec& spec = type.fields[i];
    if (isScriptBuiltin(type, i) || spec.access == vrml::AccessType::eventIn) continue;
    if (i > 32767) {
      warn("field '" + spec.name + "' is past the 32768th and cannot be used");
      continue;
    }
    duk_push_heapptr(c, fieldStore_);
    pushValue(c, node_.fieldAt(i));
    duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
    duk_pop(c);
    duk_push_lstring(c, spec.name.data(), spec.name.size());
    pushAccessor(c, getters_, i, fieldGetter, 0);
    pushAccessor(c, setters_, i, fieldSetter, 1);
    duk_def_prop(c, -4,
                 DUK_DEFPROP_HAVE_GETTER | DUK_DEFPROP_HAVE_SETTER | DUK_DEFPROP_SET_ENUMERABLE |
                     DUK_DEFPROP_FORCE);
  }
  duk_pop(c);
}

// ---- Loading ----

bool EsScript::load() {
  guard_->cap = limits_.heapBytes;
  // Duktape cannot recover from an allocation refused while it builds its built-in objects
  // (making the error for it needs another: it recursed until the stack ran out). A heap
  // is started only with room for them, and for a prelude, under both bounds: a VRML97
  // heap takes 0.3 MiB once set up, an X3D one 0.7 MiB.
  constexpr std::size_t kHeapStartBytes = std::size_t{1} << 20;
  const std::size_t worldLeft =
      limits_.worldHeapBytes > *guard_->worldUsed ? limits_.worldHeapBytes - *guard_->worldUsed : 0;
  guard_->overWorldCap = limits_.heapBytes >= kHeapStartBytes && worldLeft < kHeapStartBytes;
  if (limits_.heapBytes >= kHeapStartBytes && !guard_->overWorldCap)
    duk_ = duk_create_heap(esAlloc, esRealloc, esFree, guard_.get(), esFatal);
  if (duk_ == nullptr) {
    // Past the world's bound, every later Script of the world is refused too: said once.
    if (!guard_->overWorldCap || ctx_.scriptsInUse().refused++ == 0)
      ctx_.scriptDiagnostic(
          vrml::Severity::error, node_.location,
          name() + " cannot run: " +
              (guard_->overWorldCap ? "its heap would pass what " + overCapText() +
                                          "; nor do the world's later Scripts that would"
                                    : "its memory limit (" + mib(limits_.heapBytes) +
                                          ") is too small for the engine"));
    stopped_ = true;
    return false;
  }

  // The url entries: inline code, or a file / URL read by the browser (4.12.3, C.2).
  std::vector<std::string> urls;
  if (const vrml::FieldValue* u = node_.field("url");
      u != nullptr && u->type() == vrml::FieldType::MFString)
    urls = u->get<vrml::FieldType::MFString>();

  // The globals every Script sees: the SF/MF classes, Browser, print, its fields.
  struct Setup {
    EsScript* self;
    static duk_ret_t run(duk_context* c, void* udata) {
      EsScript& s = *static_cast<Setup*>(udata)->self;
      duk_push_heap_stash(c);
      duk_push_bare_array(c);
      duk_put_prop_string(c, -2, "gsKeep");
      duk_pop(c);
      duk_push_global_object(c);
      duk_del_prop_string(c, -1, "Duktape");  // GC control, finalizers, internals
      duk_pop(c);
      s.installNodeHooks(c);
      const bool x3d = s.wantsX3D();
      if (x3d) s.installX3DHooks(c);
      runPrelude(c, kPrelude, "prelude", preludeBytecode());
      // Starting a heap costs about twice as much with them: VRML97 Scripts go without.
      if (x3d) runPrelude(c, kPreludeX3D, "prelude-x3d", preludeX3DBytecode());
      s.capturePrototypes(c);
      s.installBrowser(c);
      s.installFields(c);
      return 0;
    }
  } setup{this};
  {
    StackScope scope;
    guard_->active = true;
    guard_->timedOut = false;
    guard_->deadline = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(std::max(limits_.callSeconds, 1.0)));
    duk_int_t rc = duk_safe_call(duk_, Setup::run, &setup, 0, 1);
    guard_->active = false;
    if (rc != DUK_EXEC_SUCCESS) {
      const char* msg = duk_safe_to_string(duk_, -1);
      ctx_.scriptDiagnostic(
          vrml::Severity::error, node_.location,
          name() + " cannot run: setting up its globals failed (" + std::string(msg ? msg : "?") +
              "; " + (guard_->overCap ? overCapText() : "memory limit " + mib(limits_.heapBytes)) +
              ")");
      stopped_ = true;
      destroyHeap();
      return false;
    }
    duk_pop(duk_);
  }

  for (const std::string& entry : urls) {
    const ScriptUrlEntry e = classifyScriptUrl(entry);
    std::string source, sourceName;
    if (e.kind == ScriptUrlEntry::Kind::empty) continue;
    if (e.kind == ScriptUrlEntry::Kind::java) {
      warn("url '" + entry + "' is Java, which GhostSpace does not run");
      continue;
    }
    if (e.kind == ScriptUrlEntry::Kind::inlineSource) {
      source = std::string(e.text);
      sourceName = std::string(e.scheme);
    } else {
      std::string error;
      std::string target;
      if (!resolveOwnUrl(entry, target, error)) {
        warn(error);
        continue;
      }
      if (!ctx_.fetchText(target, source, error)) {
        warn(error.empty() ? "cannot read '" + entry + "'" : error);
        continue;
      }
      sourceName = entry;
    }
    source_ = std::move(source);
    sourceName_ = std::move(sourceName);
    run(nullptr, nullptr, 0.0, "its code", false);
    if (loadFailed_) {
      loadFailed_ = false;
      continue;  // did not compile: try the next entry
    }
    source_.clear();
    source_.shrink_to_fit();
    return true;
  }
  ctx_.scriptDiagnostic(vrml::Severity::error, node_.location,
                        name() + ": no url entry holds code it can run" +
                            (urls.empty() ? std::string(" (url is empty)") : std::string()));
  stopped_ = true;
  destroyHeap();
  return false;
}

// ---- Calls ----

duk_ret_t EsScript::callTrampoline(duk_context* c, void* udata) {
  Call& call = *static_cast<Call*>(udata);
  EsScript& self = *call.self;
  if (call.out != nullptr) {  // collect the eventOuts assigned or changed in place
    std::vector<int> changed;
    changed.swap(self.changed_);
    for (int fi : changed) {
      auto i = static_cast<std::size_t>(fi);
      bool dirty = self.dirty_[i] != 0;
      self.dirty_[i] = self.touched_[i] = 0;
      const vrml::FieldSpec& spec = self.node_.type().fields[i];
      duk_push_heapptr(c, self.fieldStore_);
      duk_get_prop_index(c, -1, static_cast<duk_uarridx_t>(i));
      vrml::FieldValue v;
      std::string why;
      bool ok = self.toValue(c, -1, spec.type, v, why);
      duk_pop_2(c);
      if (!ok) {
        self.warn("eventOut '" + spec.name + "' not sent: " + why);
        continue;
      }
      if (dirty || !(v.storage() == self.last_[i].storage())) {
        self.last_[i] = v;
        call.out->emplace_back(fi, std::move(v));
      }
    }
    // Then the node fields changed in place (outer call only), so that an error reading
    // one of them leaves this call's eventOuts collected.
    if (self.depth_ == 1) self.flushLiveFields(c);
    return 0;
  }
  if (call.message != nullptr) {  // describe the error at the stack top
    int line = 0;
    if (duk_is_object(c, -1)) {
      duk_get_prop_string(c, -1, "lineNumber");
      if (duk_is_number(c, -1)) line = duk_get_int(c, -1);
      duk_pop(c);
    }
    duk_size_t len = 0;
    const char* text = duk_safe_to_lstring(c, -1, &len);
    std::string msg(text ? text : "?", std::min<duk_size_t>(len, 400));
    if (len > 400) msg += "...";
    *call.message = msg;
    call.line = line;
    return 0;
  }
  if (call.fn == nullptr) {  // the Script's global code
    duk_push_lstring(c, self.sourceName_.data(), self.sourceName_.size());
    if (duk_pcompile_lstring_filename(c, 0, self.source_.data(), self.source_.size()) != 0) {
      self.loadFailed_ = true;
      duk_throw(c);
    }
    duk_call(c, 0);
    return 0;
  }
  if (call.storeField >= 0) {
    duk_push_heapptr(c, self.fieldStore_);
    self.pushValue(c, *call.arg);
    duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(call.storeField));
    duk_pop(c);
  }
  if (!duk_get_global_string(c, call.fn) || !duk_is_function(c, -1)) {
    duk_pop(c);
    if (call.fallback == nullptr || !duk_get_global_string(c, call.fallback) ||
        !duk_is_function(c, -1)) {
      call.found = false;
      return 0;
    }
  }
  if (call.arg != nullptr) {
    self.pushValue(c, *call.arg);
    duk_push_number(c, call.timestamp);
    duk_call(c, 2);
  } else {
    duk_call(c, 0);
  }
  return 0;
}

void EsScript::reportError(const char* what) {
  // The error is at the stack top.
  if (++errorCount_ > kMaxReportedErrors) {
    duk_pop(duk_);
    return;
  }
  std::string message;
  Call call;
  call.self = this;
  call.message = &message;
  if (duk_safe_call(duk_, callTrampoline, &call, 1, 1) != DUK_EXEC_SUCCESS)
    message = "an error that cannot be described";
  duk_pop(duk_);
  // "Script 'S': TypeError: ... (javascript: line 3, in eventIn 'go')"
  std::string from = sourceName_.ends_with(":") ? sourceName_ : "'" + sourceName_ + "'";
  if (call.line > 0) from += " line " + std::to_string(call.line);
  std::string text = name() + ": " + message + " (" + from + ", in " + what + ")";
  if (errorCount_ == kMaxReportedErrors) text += " (further errors of this Script are not shown)";
  ctx_.scriptDiagnostic(vrml::Severity::error, node_.location, text);
}

void EsScript::stop(const std::string& why) {
  if (stopped_) return;
  stopped_ = true;
  ctx_.scriptDiagnostic(vrml::Severity::error, node_.location,
                        name() + " stopped: " + why + "; the world goes on without it");
}

bool EsScript::run(const char* fn, const vrml::FieldValue* arg, double timestamp, const char* what,
                   bool sendEvents, const char* fallback, int storeField) {
  if (stopped_ || duk_ == nullptr) return true;
  StackScope scope;
  bool outer = depth_ == 0;
  if (outer) {
    guard_->active = true;
    guard_->timedOut = false;
    guard_->overCap = false;
    guard_->deadline = std::chrono::steady_clock::now() +
                       std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                           std::chrono::duration<double>(limits_.callSeconds));
  }
  ++depth_;
  Call call;
  call.self = this;
  call.fn = fn;
  call.arg = arg;
  call.timestamp = timestamp;
  call.fallback = fallback;
  call.storeField = storeField;
  duk_int_t rc = duk_safe_call(duk_, callTrampoline, &call, 0, 1);
  auto limitHit = [this] { return guard_->timedOut || guard_->overCap; };
  if (rc != DUK_EXEC_SUCCESS && !limitHit()) {
    reportError(what);
  } else {
    duk_pop(duk_);
  }
  std::vector<std::pair<int, vrml::FieldValue>> out;
  if (!limitHit() && !loadFailed_ && (!changed_.empty() || (depth_ == 1 && hasLiveFields()))) {
    Call collect;
    collect.self = this;
    collect.out = &out;
    if (duk_safe_call(duk_, callTrampoline, &collect, 0, 1) != DUK_EXEC_SUCCESS && !limitHit())
      reportError(what);
    else
      duk_pop(duk_);
  }
  --depth_;
  if (outer) {
    forgetLiveFields();  // left by a limit or an error while they were sent
    guard_->active = false;
    assert(duk_get_top(duk_) == 0 && "a call left values on the Duktape stack");
  }
  if (guard_->timedOut) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%g s", limits_.callSeconds);
    stop(std::string(what) + " ran longer than the time limit of " + buf +
         " (ScriptLimits::callSeconds, --script-time-limit)");
  } else if (guard_->overCap) {
    stop(std::string(what) + " needed more memory than " + overCapText());
  }
  if (stopped_) {
    if (depth_ == 0) destroyHeap();
    return true;
  }
  if (sendEvents)
    for (auto& [i, v] : out) ctx_.emitScriptEvent(node_, i, std::move(v));
  return call.found;
}

void EsScript::initialize(double timestamp) {
  run("initialize", nullptr, timestamp, "initialize()", true);
}

std::string EsScript::overCapText() const {
  if (guard_->overWorldCap)
    return "the Scripts of its world may use together: " + mib(limits_.worldHeapBytes) +
           " (ScriptLimits::worldHeapBytes; they use " + mib(*guard_->worldUsed) + ")";
  return "the limit of " + mib(limits_.heapBytes) +
         " (ScriptLimits::heapBytes, --script-memory-limit)";
}

bool EsScript::route(duk_context* c, bool add, const vrml::NodePtr& from,
                     const std::string& eventOut, const vrml::NodePtr& to,
                     const std::string& eventIn) {
  std::size_t& routes = ctx_.scriptsInUse().routes;
  if (!add) {
    const bool removed = ctx_.deleteRoute(from, eventOut, to, eventIn);
    if (removed && routes > 0) --routes;
    return removed;
  }
  // A route in place already is not added again (true, and not counted).
  if (ctx_.hasRoute(from, eventOut, to, eventIn)) return true;
  if (routes >= limits_.addedRoutes)
    GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR,
                 "addRoute: the Scripts of this world added %lu routes, the limit "
                 "(ScriptLimits::addedRoutes)",
                 static_cast<unsigned long>(routes));
  const bool added = ctx_.addRoute(from, eventOut, to, eventIn);
  if (added) ++routes;
  return added;
}

std::shared_ptr<vrml::Scene> EsScript::createFromText(duk_context* c, const std::string& text,
                                                      const std::string& url) {
  std::string refused;
  try {
    return ctx_.createSceneFromString(text, &node_, url);
  } catch (const ScriptLimitError& e) {
    refused = e.what();
  }
  GS_DUK_ERROR(c, DUK_ERR_RANGE_ERROR, "%s", refused.c_str());
  return nullptr;  // not reached: GS_DUK_ERROR throws
}

void EsScript::eventsProcessed(double timestamp) {
  run("eventsProcessed", nullptr, timestamp, "eventsProcessed()", true);
}

// The X3D prelude's dispatcher of browser callbacks (addBrowserCallback,
// addBrowserListener), called with X3DConstants' event number; absent in VRML97 Scripts.
constexpr const char* kBrowserEventFunction = "__gsBrowserEvent";
constexpr int kShutdownEvent = 3;  // X3DConstants.SHUTDOWN_EVENT

void EsScript::browserEvent(BrowserEvent event, double timestamp) {
  const vrml::FieldValue number =
      vrml::FieldValue::make<vrml::FieldType::SFInt32>(static_cast<std::int32_t>(event));
  run(kBrowserEventFunction, &number, timestamp,
      event == BrowserEvent::initialized ? "a browser callback (INITIALIZED_EVENT)"
                                         : "a browser callback (INITIALIZED_ERROR)",
      true);
}

void EsScript::shutdown(double timestamp) {
  const vrml::FieldValue event = vrml::FieldValue::make<vrml::FieldType::SFInt32>(kShutdownEvent);
  run(kBrowserEventFunction, &event, timestamp, "a browser callback (SHUTDOWN_EVENT)", true);
  run("shutdown", nullptr, timestamp, "shutdown()", true);
  // 4.12.3: the last call (the world that held the Script was unloaded): the heap goes, so
  // any later call does nothing (stopped() stays false: no error or limit stopped it).
  if (depth_ == 0) destroyHeap();
}

void EsScript::eventIn(int field, const vrml::FieldValue& value, double timestamp) {
  if (stopped_ || duk_ == nullptr) return;
  if (field < 0 || static_cast<std::size_t>(field) >= node_.fieldCount()) return;
  auto i = static_cast<std::size_t>(field);
  const vrml::FieldSpec& spec = node_.type().fields[i];
  if (spec.access != vrml::AccessType::eventIn && spec.access != vrml::AccessType::exposedField)
    return;
  if (value.type() != spec.type) {
    warn("eventIn '" + spec.name + "' ignored: it is " +
         std::string(vrml::fieldTypeName(spec.type)) + ", the event " +
         std::string(vrml::fieldTypeName(value.type())));
    return;
  }
  std::string what = "eventIn '" + spec.name + "'";
  bool exposed = spec.access == vrml::AccessType::exposedField;
  std::string fallback = "set_" + spec.name;
  // An exposedField takes the value, then its function (x, or set_x) runs.
  if (exposed) last_[i] = value;
  bool found = run(spec.name.c_str(), &value, timestamp, what.c_str(), true,
                   exposed ? fallback.c_str() : nullptr, exposed ? field : -1);
  if (!found && !warnedMissing_[i]) {
    warnedMissing_[i] = 1;
    warn("no function for eventIn '" + spec.name + "': its events are ignored");
  }
}

void putNativeFunctions(duk_context* c, std::span<const NativeFunction> functions) {
  for (const NativeFunction& f : functions) {
    duk_push_c_function(c, f.fn, f.nargs);
    duk_put_prop_string(c, -2, f.name);
  }
}

}  // namespace es

ScriptFactory ecmascriptFactory() {
  return [](vrml::Node& script, ScriptContext& ctx,
            const ScriptLimits& limits) -> std::unique_ptr<ScriptInstance> {
    if (!script.type().script) return nullptr;
    auto instance = std::make_unique<es::EsScript>(script, ctx, limits);
    if (!instance->load()) return nullptr;
    return instance;
  };
}

}  // namespace gs::runtime
