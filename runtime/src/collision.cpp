// Collision (ISO/IEC 14772-1:1997 6.8): collideTime when the avatar meets the children or
// the proxy of a Collision node. The renderer decides the meeting (scene::walkStep);
// this sends the events.
#include "execution_state.hpp"

namespace gs::runtime {

void ExecutionModel::collided(const std::vector<vrml::Node*>& collisionNodes) {
  State& s = *s_;
  bool any = false;
  for (vrml::Node* n : collisionNodes) {
    if (n == nullptr || n->typeId() != vrml::NodeTypeId::Collision) continue;
    const int field = n->type().findExact("collideTime");
    if (field < 0) continue;
    if (!any) s.beginTimestamp();  // one timestamp for all of them
    any = true;
    NodeState& ns = s.reach(*n, false);
    s.emitOwn(ns, field, vrml::FieldValue::make<vrml::FieldType::SFTime>(now()));
  }
  if (!any) return;
  s.runCascade();
  s.initializeScripts();
}

}  // namespace gs::runtime
