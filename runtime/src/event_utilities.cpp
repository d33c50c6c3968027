// The X3D Event Utilities component (X3D 4.0 clause 30): BooleanFilter, BooleanToggle,
// BooleanTrigger, IntegerTrigger, TimeTrigger (X3DTriggerNode), BooleanSequencer and
// IntegerSequencer (X3DSequencerNode). Field indices are found once, when the node is
// classified; events go out through emitOwn like every other node's.
#include "execution_state.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string_view>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

std::optional<EventUtilityKind> eventUtilityKind(vrml::NodeTypeId id) {
  using vrml::NodeTypeId;
  switch (id) {
    case NodeTypeId::BooleanFilter:
      return EventUtilityKind::booleanFilter;
    case NodeTypeId::BooleanToggle:
      return EventUtilityKind::booleanToggle;
    case NodeTypeId::BooleanTrigger:
      return EventUtilityKind::booleanTrigger;
    case NodeTypeId::IntegerTrigger:
      return EventUtilityKind::integerTrigger;
    case NodeTypeId::TimeTrigger:
      return EventUtilityKind::timeTrigger;
    case NodeTypeId::BooleanSequencer:
      return EventUtilityKind::booleanSequencer;
    case NodeTypeId::IntegerSequencer:
      return EventUtilityKind::integerSequencer;
    default:
      return std::nullopt;
  }
}

/// The index of the largest key <= fraction; 0 below the first key (and for NaN).
std::size_t stepIndex(const std::vector<float>& key, float fraction) {
  if (key.empty() || !(fraction >= key.front())) return 0;
  const auto it = std::upper_bound(key.begin(), key.end(), fraction);
  return static_cast<std::size_t>(it - key.begin()) - 1;
}

/// Number of values in an MFBool / MFInt32 keyValue; 0 for any other type.
std::size_t keyValueCount(const FieldValue& v) {
  if (v.type() == FieldType::MFBool) return v.get<FieldType::MFBool>().size();
  if (v.type() == FieldType::MFInt32) return v.get<FieldType::MFInt32>().size();
  return 0;
}

/// keyValue[i] as the matching single-valued field (SFBool / SFInt32).
FieldValue keyValueAt(const FieldValue& v, std::size_t i) {
  if (v.type() == FieldType::MFBool)
    return FieldValue::make<FieldType::SFBool>(static_cast<bool>(v.get<FieldType::MFBool>()[i]));
  return FieldValue::make<FieldType::SFInt32>(v.get<FieldType::MFInt32>()[i]);
}

}  // namespace

bool ExecutionModel::State::classifyEventUtility(NodeState& ns) {
  const vrml::NodeType& type = ns.node->type();
  const auto kind = eventUtilityKind(type.id());
  if (!kind) return false;
  ns.role = NodeRole::eventUtility;
  ns.utility = std::make_unique<EventUtilityFields>();
  EventUtilityFields& f = *ns.utility;
  f.kind = *kind;
  auto idx = [&](std::string_view name) { return type.findExact(name); };
  switch (*kind) {
    case EventUtilityKind::booleanFilter:
      f.input = idx("set_boolean");
      f.out = {idx("inputTrue"), idx("inputFalse"), idx("inputNegate")};
      break;
    case EventUtilityKind::booleanToggle:
      f.input = idx("set_boolean");
      f.value = idx("toggle");
      break;
    case EventUtilityKind::booleanTrigger:
      f.input = idx("set_triggerTime");
      f.out[0] = idx("triggerTrue");
      break;
    case EventUtilityKind::integerTrigger:
      f.input = idx("set_boolean");
      f.value = idx("integerKey");
      f.out[0] = idx("triggerValue");
      break;
    case EventUtilityKind::timeTrigger:
      f.input = idx("set_boolean");
      f.out[0] = idx("triggerTime");
      break;
    case EventUtilityKind::booleanSequencer:
    case EventUtilityKind::integerSequencer:
      f.input = idx("set_fraction");
      f.next = idx("next");
      f.previous = idx("previous");
      f.key = idx("key");
      f.keyValue = idx("keyValue");
      f.out[0] = idx("value_changed");
      break;
  }
  return true;
}

void ExecutionModel::State::deliverEventUtility(NodeState& ns, int field, FieldValue value) {
  EventUtilityFields& f = *ns.utility;
  vrml::Node& node = *ns.node;
  const auto at = [&](int i) -> const FieldValue& {
    return node.fieldAt(static_cast<std::size_t>(i));
  };
  switch (f.kind) {
    case EventUtilityKind::booleanFilter: {
      // 30.4.1: TRUE -> inputTrue TRUE, FALSE -> inputFalse FALSE; inputNegate !value.
      const bool b = value.get<FieldType::SFBool>();
      emitOwn(ns, b ? f.out[0] : f.out[1], FieldValue::make<FieldType::SFBool>(b));
      emitOwn(ns, f.out[2], FieldValue::make<FieldType::SFBool>(!b));
      return;
    }
    case EventUtilityKind::booleanToggle:
      // 30.4.3: set_boolean TRUE negates toggle; FALSE is ignored.
      if (f.value < 0 || !value.get<FieldType::SFBool>()) return;
      if (at(f.value).type() != FieldType::SFBool) return;
      emitOwn(ns, f.value,
              FieldValue::make<FieldType::SFBool>(!at(f.value).get<FieldType::SFBool>()));
      return;
    case EventUtilityKind::booleanTrigger:
      // 30.4.4: any set_triggerTime -> triggerTrue TRUE.
      emitOwn(ns, f.out[0], FieldValue::make<FieldType::SFBool>(true));
      return;
    case EventUtilityKind::integerTrigger:
      // 30.4.5: set_boolean TRUE -> triggerValue = integerKey.
      if (f.value < 0 || !value.get<FieldType::SFBool>()) return;
      if (at(f.value).type() != FieldType::SFInt32) return;
      emitOwn(ns, f.out[0], at(f.value));
      return;
    case EventUtilityKind::timeTrigger:
      // 30.4.7: set_boolean -> triggerTime = the current time.
      emitOwn(ns, f.out[0], FieldValue::make<FieldType::SFTime>(model.now()));
      return;
    case EventUtilityKind::booleanSequencer:
    case EventUtilityKind::integerSequencer:
      break;
  }
  // X3DSequencerNode (30.3.1): a step function of key / keyValue, and next / previous.
  if (f.keyValue < 0 || f.out[0] < 0) return;
  const FieldValue& keyValue = at(f.keyValue);
  const std::size_t n = keyValueCount(keyValue);
  if (n == 0) return;
  std::size_t i = 0;
  if (field == f.input) {
    if (f.key < 0) return;
    const std::vector<float>& key = at(f.key).get<FieldType::MFFloat>();
    if (key.size() != n) {
      if (!ns.problemReported)
        report(vrml::Severity::error, node,
               "keyValue has " + std::to_string(n) + " values for " + std::to_string(key.size()) +
                   " keys; no output");
      ns.problemReported = true;
      return;
    }
    i = stepIndex(key, value.get<FieldType::SFFloat>());
  } else {
    // next / previous TRUE step cyclically from the value last sent (before any: the
    // first value for next, the last for previous).
    if (!value.get<FieldType::SFBool>()) return;
    const bool forward = field == f.next;
    if (f.index < 0 || static_cast<std::size_t>(f.index) >= n)
      i = forward ? 0 : n - 1;
    else
      i = forward ? (static_cast<std::size_t>(f.index) + 1) % n
                  : (static_cast<std::size_t>(f.index) + n - 1) % n;
  }
  f.index = static_cast<int>(i);
  emitOwn(ns, f.out[0], keyValueAt(keyValue, i));
}

}  // namespace gs::runtime
