// The animations of a world (session/animations.hpp).
#include "session/animations.hpp"

#include <unordered_set>

namespace gs::session {
namespace {

using vrml::FieldType;
using vrml::FieldValue;

void send(runtime::ExecutionModel& model, vrml::Node& node, std::string_view field,
          FieldValue value) {
  const int i = node.type().findExact(field);
  if (i >= 0) model.postEvent(node, i, std::move(value));
}

}  // namespace

std::vector<vrml::Node*> namedTimeSensors(const vrml::Scene& scene, std::size_t limit) {
  std::vector<vrml::Node*> out;
  std::unordered_set<const vrml::Node*> seen;
  std::vector<vrml::Node*> stack;
  for (auto it = scene.rootNodes.rbegin(); it != scene.rootNodes.rend(); ++it)
    if (*it) stack.push_back(it->get());
  while (!stack.empty() && out.size() < limit) {
    vrml::Node* n = stack.back();
    stack.pop_back();
    if (!seen.insert(n).second) continue;
    if (n->typeId() == vrml::NodeTypeId::TimeSensor && !n->defName.empty()) out.push_back(n);
    // Children pushed last first, so that they come out in file order.
    for (std::size_t f = n->fieldCount(); f-- > 0;) {
      const FieldValue& v = n->fieldAt(f);
      if (v.type() == FieldType::SFNode) {
        if (const vrml::NodePtr& c = v.get<FieldType::SFNode>()) stack.push_back(c.get());
      } else if (v.type() == FieldType::MFNode) {
        const auto& kids = v.get<FieldType::MFNode>();
        for (auto c = kids.rbegin(); c != kids.rend(); ++c)
          if (*c) stack.push_back(c->get());
      }
    }
  }
  return out;
}

bool animationActive(const vrml::Node& sensor) {
  const FieldValue* v = sensor.field("isActive");
  return v != nullptr && v->type() == FieldType::SFBool && v->get<FieldType::SFBool>();
}

void startAnimation(runtime::ExecutionModel& model, vrml::Node& sensor,
                    const std::vector<vrml::Node*>& others, bool exclusive) {
  const double now = model.now();
  if (exclusive)
    for (vrml::Node* o : others)
      if (o != &sensor && animationActive(*o))
        send(model, *o, "stopTime", FieldValue::make<FieldType::SFTime>(now));
  if (animationActive(sensor)) {
    send(model, sensor, "stopTime", FieldValue::make<FieldType::SFTime>(now));
    model.processEvents();
  }
  send(model, sensor, "loop", FieldValue::make<FieldType::SFBool>(true));
  send(model, sensor, "startTime", FieldValue::make<FieldType::SFTime>(now));
  model.processEvents();
}

void stopAnimation(runtime::ExecutionModel& model, vrml::Node& sensor) {
  send(model, sensor, "stopTime", FieldValue::make<FieldType::SFTime>(model.now()));
  model.processEvents();
}

}  // namespace gs::session
