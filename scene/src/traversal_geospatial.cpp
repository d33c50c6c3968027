// The Geospatial component's parts of the traversal (X3D 4.0 clause 25): the Inline nodes
// that load a GeoLOD's rootUrl and child urls (scene/src/traversal.cpp chooses which show).
#include "encodings/node_types.hpp"
#include "scene/traversal.hpp"

namespace gs::scene {

const vrml::Node& SceneTraversal::geoLodInline(const vrml::Node& n, int k) {
  std::array<vrml::NodePtr, 5>& inlines = geoLodInlines_[&n];
  vrml::NodePtr& inl = inlines[static_cast<std::size_t>(k)];
  if (!inl) {
    static const std::shared_ptr<const vrml::NodeType> kInline = vrml::x3dNodeType("Inline");
    inl = std::make_shared<vrml::Node>(kInline);
    inl->location = n.location;
    inl->urlBase = n.urlBase;
    static constexpr const char* kFields[] = {"rootUrl", "child1Url", "child2Url", "child3Url",
                                              "child4Url"};
    const vrml::FieldValue* from = n.field(std::string_view(kFields[k]));
    vrml::FieldValue* to = inl->field("url");
    if (from != nullptr && to != nullptr && from->type() == to->type()) *to = *from;
  }
  return *inl;
}

}  // namespace gs::scene
