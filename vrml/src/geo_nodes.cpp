#include "vrml/geo_nodes.hpp"

namespace gs::vrml {

geospatial::GeoSystem geoSystemOf(const Node& node, std::string* problem) {
  const FieldValue* f = node.field("geoSystem");
  if (f == nullptr || f->type() != FieldType::MFString) return {};
  return geospatial::parseGeoSystem(f->get<FieldType::MFString>(), problem);
}

geospatial::LocalFrame geoFrameOf(const Node& node) {
  const NodePtr& origin = node.sfnode("geoOrigin");
  if (!origin || origin->unresolved || origin->typeId() != NodeTypeId::GeoOrigin) return {};
  return geospatial::originFrame(geoSystemOf(*origin),
                                 origin->get<FieldType::SFVec3d>("geoCoords", glm::dvec3(0.0)),
                                 origin->get<FieldType::SFBool>("rotateYUp", false));
}

glm::dvec3 geoToLocal(const Node& node, const glm::dvec3& geoCoords) {
  return geospatial::toLocal(geoFrameOf(node),
                             geospatial::toGeocentric(geoSystemOf(node), geoCoords));
}

glm::dmat4 geoLocationMatrix(const Node& node, const glm::dvec3& geoCoords) {
  return geospatial::locationMatrix(geoFrameOf(node), geoSystemOf(node), geoCoords);
}

}  // namespace gs::vrml
