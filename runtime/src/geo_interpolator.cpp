// X3D's GeoPositionInterpolator (X3D 4.0 clause 25.4.9): keyValue holds geo coordinates of
// its geoSystem; set_fraction interpolates them linearly between the keys (in the
// geoSystem's coordinates, as 4.6.8's rules for keys say: below the first key the first
// value, above the last the last) and sends geovalue_changed (those coordinates) and
// value_changed (them in local coordinates, its geoOrigin's: vrml/geo_nodes.hpp).
#include "execution_state.hpp"

#include "vrml/geo_nodes.hpp"

#include <algorithm>

namespace gs::runtime {

using vrml::FieldType;
using vrml::FieldValue;

bool ExecutionModel::State::classifyGeoInterpolator(NodeState& ns) {
  if (ns.node->typeId() != vrml::NodeTypeId::GeoPositionInterpolator) return false;
  const vrml::NodeType& type = ns.node->type();
  ns.role = NodeRole::geoInterpolator;
  ns.setFraction = type.findExact("set_fraction");
  ns.key = type.findExact("key");
  ns.keyValue = type.findExact("keyValue");
  ns.valueChanged = type.findExact("value_changed");
  ns.normalChanged = type.findExact("geovalue_changed");  // (the second output)
  return true;
}

void ExecutionModel::State::deliverGeoInterpolator(NodeState& ns, const FieldValue& value) {
  const vrml::Node& node = *ns.node;
  if (ns.key < 0 || ns.keyValue < 0 || value.type() != FieldType::SFFloat) return;
  const auto& keys = node.fieldAt(static_cast<std::size_t>(ns.key)).get<FieldType::MFFloat>();
  const auto& values =
      node.fieldAt(static_cast<std::size_t>(ns.keyValue)).get<FieldType::MFVec3d>();
  if (keys.empty() || keys.size() != values.size()) {
    if (!ns.problemReported)
      report(vrml::Severity::error, node,
             "key has " + std::to_string(keys.size()) + " values, keyValue " +
                 std::to_string(values.size()) + ": no output");
    ns.problemReported = true;
    return;
  }
  const float f = value.get<FieldType::SFFloat>();
  glm::dvec3 geo = values.front();
  if (f >= keys.back()) {
    geo = values.back();
  } else if (f > keys.front()) {
    const auto i =
        static_cast<std::size_t>(std::upper_bound(keys.begin(), keys.end(), f) - keys.begin());
    const double span = keys[i] - keys[i - 1];
    const double t = span > 0.0 ? (f - keys[i - 1]) / span : 1.0;
    geo = glm::mix(values[i - 1], values[i], t);
  }
  if (ns.normalChanged >= 0)
    emitOwn(ns, ns.normalChanged, FieldValue::make<FieldType::SFVec3d>(geo));
  if (ns.valueChanged >= 0)
    emitOwn(ns, ns.valueChanged,
            FieldValue::make<FieldType::SFVec3f>(glm::vec3(vrml::geoToLocal(node, geo))));
}

}  // namespace gs::runtime
