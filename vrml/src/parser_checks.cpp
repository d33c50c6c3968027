// Which node may go where (clause 4.6.5 "Grouping and children nodes" and the SFNode
// fields of clause 6): a Material in Group.children or a Color in Text.fontStyle is read
// but reported as a warning.
#include "parser_impl.hpp"

#include <array>
#include <cstdint>
#include <utility>

namespace gs::vrml::parsing {

namespace {

enum class NodeClass {
  any,
  children,
  geometry,
  appearance,
  material,
  texture,
  textureTransform,
  coordinate,
  color,
  normal,
  texCoord,
  fontStyle,
  audioClip,
};

constexpr std::array<std::pair<std::string_view, NodeClass>, 54> kClassOf = {{
    {"Anchor", NodeClass::children},
    {"Appearance", NodeClass::appearance},
    {"AudioClip", NodeClass::audioClip},
    {"Background", NodeClass::children},
    {"Billboard", NodeClass::children},
    {"Box", NodeClass::geometry},
    {"Collision", NodeClass::children},
    {"Color", NodeClass::color},
    {"ColorInterpolator", NodeClass::children},
    {"Cone", NodeClass::geometry},
    {"Coordinate", NodeClass::coordinate},
    {"CoordinateInterpolator", NodeClass::children},
    {"Cylinder", NodeClass::geometry},
    {"CylinderSensor", NodeClass::children},
    {"DirectionalLight", NodeClass::children},
    {"ElevationGrid", NodeClass::geometry},
    {"Extrusion", NodeClass::geometry},
    {"Fog", NodeClass::children},
    {"FontStyle", NodeClass::fontStyle},
    {"Group", NodeClass::children},
    {"ImageTexture", NodeClass::texture},
    {"IndexedFaceSet", NodeClass::geometry},
    {"IndexedLineSet", NodeClass::geometry},
    {"Inline", NodeClass::children},
    {"LOD", NodeClass::children},
    {"Material", NodeClass::material},
    {"MovieTexture", NodeClass::texture},
    {"NavigationInfo", NodeClass::children},
    {"Normal", NodeClass::normal},
    {"NormalInterpolator", NodeClass::children},
    {"OrientationInterpolator", NodeClass::children},
    {"PixelTexture", NodeClass::texture},
    {"PlaneSensor", NodeClass::children},
    {"PointLight", NodeClass::children},
    {"PointSet", NodeClass::geometry},
    {"PositionInterpolator", NodeClass::children},
    {"ProximitySensor", NodeClass::children},
    {"ScalarInterpolator", NodeClass::children},
    {"Script", NodeClass::children},
    {"Shape", NodeClass::children},
    {"Sound", NodeClass::children},
    {"Sphere", NodeClass::geometry},
    {"SphereSensor", NodeClass::children},
    {"SpotLight", NodeClass::children},
    {"Switch", NodeClass::children},
    {"Text", NodeClass::geometry},
    {"TextureCoordinate", NodeClass::texCoord},
    {"TextureTransform", NodeClass::textureTransform},
    {"TimeSensor", NodeClass::children},
    {"TouchSensor", NodeClass::children},
    {"Transform", NodeClass::children},
    {"Viewpoint", NodeClass::children},
    {"VisibilitySensor", NodeClass::children},
    {"WorldInfo", NodeClass::children},
}};

constexpr std::array<std::pair<std::string_view, NodeClass>, 15> kFieldClass = {{
    {"children", NodeClass::children},
    {"choice", NodeClass::children},
    {"level", NodeClass::children},
    {"proxy", NodeClass::children},
    {"appearance", NodeClass::appearance},
    {"material", NodeClass::material},
    {"texture", NodeClass::texture},
    {"textureTransform", NodeClass::textureTransform},
    {"geometry", NodeClass::geometry},
    {"coord", NodeClass::coordinate},
    {"color", NodeClass::color},
    {"normal", NodeClass::normal},
    {"texCoord", NodeClass::texCoord},
    {"fontStyle", NodeClass::fontStyle},
    {"source", NodeClass::audioClip},
}};

// Built-in NodeTypes live as long as the program (and per-instance Script types are
// never asked about through this cache: they are `script`, handled by the caller), so a
// small per-thread cache keyed by address is safe and spares a name search per node.
NodeClass classOf(const NodeType& t) {
  if (!t.builtIn || t.extension) return NodeClass::any;
  struct Entry {
    const NodeType* type = nullptr;
    NodeClass c = NodeClass::any;
  };
  thread_local std::array<Entry, 64> cache{};
  Entry& e = cache[(reinterpret_cast<std::uintptr_t>(&t) >> 4) & 63];
  if (e.type == &t) return e.c;
  NodeClass c = NodeClass::any;
  for (const auto& [name, k] : kClassOf)
    if (name == t.name) c = k;
  if (!t.script) e = Entry{&t, c};
  return c;
}

const char* describe(NodeClass c) {
  switch (c) {
    case NodeClass::any:
      return "any node";
    case NodeClass::children:
      return "a children node";
    case NodeClass::geometry:
      return "a geometry node";
    case NodeClass::appearance:
      return "Appearance";
    case NodeClass::material:
      return "Material";
    case NodeClass::texture:
      return "a texture node";
    case NodeClass::textureTransform:
      return "TextureTransform";
    case NodeClass::coordinate:
      return "Coordinate";
    case NodeClass::color:
      return "Color";
    case NodeClass::normal:
      return "Normal";
    case NodeClass::texCoord:
      return "TextureCoordinate";
    case NodeClass::fontStyle:
      return "FontStyle";
    case NodeClass::audioClip:
      return "AudioClip or MovieTexture";
  }
  return "?";
}

}  // namespace

bool nodeClassAllowed(const NodeType* parent, std::string_view field, const NodeType& child,
                      std::string& expected) {
  NodeClass want = NodeClass::children;
  if (parent != nullptr) {
    if (!parent->builtIn || parent->extension || parent->script) return true;
    // Field names of built-in types live as long as the program: cache by address.
    struct Entry {
      const char* name = nullptr;
      NodeClass c = NodeClass::any;
    };
    thread_local std::array<Entry, 64> cache{};
    Entry& e = cache[(reinterpret_cast<std::uintptr_t>(field.data()) >> 3) & 63];
    if (e.name == field.data()) {
      want = e.c;
    } else {
      want = NodeClass::any;
      for (const auto& [name, c] : kFieldClass)
        if (name == field) want = c;
      e = Entry{field.data(), want};
    }
  }
  if (want == NodeClass::any) return true;
  const NodeClass have = classOf(child);
  if (have == NodeClass::any || have == want) return true;
  if (want == NodeClass::audioClip && child.name == "MovieTexture") return true;
  expected = describe(want);
  return false;
}

}  // namespace gs::vrml::parsing
