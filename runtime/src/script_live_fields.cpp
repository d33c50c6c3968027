// A node's fields as live values in a Script (script_ecmascript_internal.hpp,
// pushNodeField): X_ITE's scripts build geometry in place (coord.point.push(p),
// color.length = n; color[i].setHSV(...)), which copies of the values would lose.
#include "script_ecmascript_internal.hpp"

namespace gs::runtime::es {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

/// Whether a value of type `t` is an object a Script can change in place.
bool isObjectValued(FieldType t) {
  switch (t) {
    case FieldType::SFBool:
    case FieldType::SFInt32:
    case FieldType::SFFloat:
    case FieldType::SFDouble:
    case FieldType::SFTime:
    case FieldType::SFString:
    case FieldType::SFNode:  // one object per node already
      return false;
    default:
      return true;
  }
}

bool writable(vrml::AccessType a) {
  return a == vrml::AccessType::exposedField || a == vrml::AccessType::eventIn;
}

/// Pushes `v` as pushValue does, an MF array wrapped by the prelude's __gsLiveMF.
void pushLiveObject(EsScript& self, duk_context* c, const FieldValue& v) {
  self.pushValue(c, v);
  if (!vrml::isMultiValued(v.type())) return;
  duk_push_heap_stash(c);
  duk_get_prop_string(c, -1, "gsLiveMF");
  duk_remove(c, -2);
  if (!duk_is_function(c, -1)) {
    duk_pop(c);
    return;
  }
  duk_dup(c, -2);
  duk_call(c, 1);
  duk_remove(c, -2);
}

}  // namespace

void EsScript::pushNodeField(duk_context* c, const vrml::NodePtr& n, std::size_t i) {
  const FieldValue& v = n->fieldAt(i);
  if (!isObjectValued(v.type()) || liveStore_ == nullptr) {
    pushValue(c, v);
    return;
  }
  const auto key = std::make_pair(static_cast<const vrml::Node*>(n.get()), i);
  if (auto it = liveSlots_.find(key); it != liveSlots_.end()) {
    duk_push_heapptr(c, liveStore_);
    duk_get_prop_index(c, -1, it->second);
    duk_remove(c, -2);
    return;
  }
  pushLiveObject(*this, c, v);
  const auto slot = static_cast<std::uint32_t>(live_.size());
  duk_push_heapptr(c, liveStore_);
  duk_dup(c, -2);
  duk_put_prop_index(c, -2, slot);
  duk_pop(c);
  live_.push_back({n, i, std::nullopt});
  liveSlots_.emplace(key, slot);
}

void EsScript::assignedNodeField(duk_context* c, const vrml::NodePtr& n, std::size_t i,
                                 const FieldValue& v) {
  if (!isObjectValued(v.type()) || liveStore_ == nullptr) return;
  const auto key = std::make_pair(static_cast<const vrml::Node*>(n.get()), i);
  const auto found = liveSlots_.find(key);
  const auto slot =
      found != liveSlots_.end() ? found->second : static_cast<std::uint32_t>(live_.size());
  // The object stored first (this may throw into the Script), then the records.
  pushLiveObject(*this, c, v);
  duk_push_heapptr(c, liveStore_);
  duk_dup(c, -2);
  duk_put_prop_index(c, -2, slot);
  duk_pop_2(c);
  if (found != liveSlots_.end()) {
    live_[slot].assigned = v;
    return;
  }
  live_.push_back({n, i, v});
  liveSlots_.emplace(key, slot);
}

bool EsScript::liveSlotValue(duk_context* c, std::size_t slot, FieldType t, FieldValue& v,
                             std::string& why) {
  duk_push_heapptr(c, liveStore_);
  duk_get_prop_index(c, -1, static_cast<duk_uarridx_t>(slot));
  const bool ok = toValue(c, -1, t, v, why);
  duk_pop_2(c);
  return ok;
}

void EsScript::sendChangedLiveFields(duk_context* c, const vrml::Node& n, std::size_t except) {
  if (liveStore_ == nullptr) return;
  // The slots first: toValue may run the Script's code (valueOf, getters), which may read
  // more live fields (live_ grows: no reference into it is held across the call; the map
  // is not iterated while it may grow).
  std::vector<std::uint32_t> slots;
  for (auto it = liveSlots_.lower_bound({&n, 0}); it != liveSlots_.end() && it->first.first == &n;
       ++it)
    if (it->first.second != except) slots.push_back(it->second);
  for (const std::uint32_t slot : slots) {
    const vrml::NodePtr node = live_[slot].node;
    const std::size_t field = live_[slot].field;
    const vrml::FieldSpec& spec = node->type().fields[field];
    if (!writable(spec.access)) continue;
    FieldValue v;
    std::string why;
    const bool ok = liveSlotValue(c, slot, spec.type, v, why);
    if (!ok || slot >= live_.size()) continue;  // flushLiveFields reports it at the call's end
    LiveField& f = live_[slot];
    const FieldValue& before = f.assigned ? *f.assigned : node->fieldAt(field);
    if (v.storage() == before.storage()) continue;
    f.assigned = v;  // flushLiveFields sends it again only if it changes again
    ctx_.sendEvent(*node, static_cast<int>(field), std::move(v));
  }
}

void EsScript::flushLiveFields(duk_context* c) {
  std::vector<LiveField> live;
  live.swap(live_);
  liveSlots_.clear();
  for (std::size_t slot = 0; slot < live.size(); ++slot) {
    LiveField& f = live[slot];
    const vrml::FieldSpec& spec = f.node->type().fields[f.field];
    if (!writable(spec.access)) continue;  // a read eventOut or initializeOnly field
    FieldValue v;
    std::string why;
    const bool ok = liveSlotValue(c, slot, spec.type, v, why);
    if (!ok) {
      warn(spec.name + " of " + f.node->typeName() + " changed in place but not sent: " + why);
      continue;
    }
    const FieldValue& before = f.assigned ? *f.assigned : f.node->fieldAt(f.field);
    if (v.storage() == before.storage()) continue;
    ctx_.sendEvent(*f.node, static_cast<int>(f.field), std::move(v));
  }
  duk_push_heapptr(c, liveStore_);
  duk_push_uint(c, 0);
  duk_put_prop_string(c, -2, "length");
  duk_pop(c);
}

void EsScript::forgetLiveFields() {
  live_.clear();
  liveSlots_.clear();
  if (duk_ == nullptr || liveStore_ == nullptr) return;
  duk_push_heapptr(duk_, liveStore_);
  duk_push_uint(duk_, 0);
  duk_put_prop_string(duk_, -2, "length");
  duk_pop(duk_);
}

}  // namespace gs::runtime::es
