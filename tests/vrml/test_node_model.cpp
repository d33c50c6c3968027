// The node model (vrml/node_model.hpp): generated from X3DUOM 4.0, checked here against
// the VRML97 node table and the abstract types every module decides classes by.
#include "encodings/node_types.hpp"
#include "encodings/parser.hpp"
#include "vrml/node_model.hpp"
#include "vrml/node_table.hpp"

#include <catch2/catch.hpp>

#include <map>
#include <string>

using namespace gs::vrml;

TEST_CASE("node model: X3D 4.0's 260 concrete nodes and the extensions", "[node_model]") {
  std::size_t x3d = 0, extensions = 0;
  for (const NodeModel& m : nodeModels()) {
    (m.extension ? extensions : x3d) += 1;
    REQUIRE(nodeModel(m.name) == &m);
    REQUIRE(nodeModel(m.id) == &m);
    CHECK(!m.component.empty());
    CHECK(m.level >= 1);
  }
  // and X3D 4.1's EnvironmentLight and X_ITE's GaussianSplats (vrml/gen/gen_node_model.py)
  CHECK(x3d == 262);
  CHECK(extensions == 3);  // OutlineGroup, QuantizedNormalVectors, Skin
  CHECK(nodeModel("NoSuchNode") == nullptr);
  CHECK(nodeModel(NodeTypeId::unknown) == nullptr);
  CHECK(abstractTypeName(AbstractType::X3DGroupingNode) == "X3DGroupingNode");
  CHECK(abstractTypeNamed("X3DBindableNode") == AbstractType::X3DBindableNode);
  CHECK(!abstractTypeNamed("X3DNoSuchNode"));
}

TEST_CASE("node model: abstract types, components and levels", "[node_model]") {
  const auto is = [](std::string_view n, AbstractType t) { return nodeModel(n)->is(t); };
  CHECK(is("Transform", AbstractType::X3DGroupingNode));
  CHECK(is("Transform", AbstractType::X3DChildNode));  // transitively
  CHECK(is("Transform", AbstractType::X3DBoundedObject));
  CHECK(!is("Shape", AbstractType::X3DGroupingNode));
  CHECK(is("Viewpoint", AbstractType::X3DBindableNode));
  CHECK(is("TimeSensor", AbstractType::X3DTimeDependentNode));
  CHECK(is("TimeSensor", AbstractType::X3DSensorNode));
  CHECK(is("TouchSensor", AbstractType::X3DPointingDeviceSensorNode));
  CHECK(is("PositionInterpolator", AbstractType::X3DInterpolatorNode));
  CHECK(is("Box", AbstractType::X3DGeometryNode));
  CHECK(is("ImageTexture", AbstractType::X3DTextureNode));
  CHECK(is("ImageTexture", AbstractType::X3DUrlObject));
  CHECK(is("SpotLight", AbstractType::X3DLightNode));
  CHECK(!is("Material", AbstractType::X3DChildNode));
  CHECK(nodeModel("Transform")->component == "Grouping");
  CHECK(nodeModel("Transform")->containerField == "children");
  CHECK(nodeModel("Material")->containerField == "material");
  CHECK(nodeModel("Collision")->component == "Navigation");
  CHECK(nodeModel("Collision")->level == 2);
  // The extensions declare their types the same way (docs/vrml-extensions.md).
  CHECK(is("OutlineGroup", AbstractType::X3DGroupingNode));
  CHECK(is("QuantizedNormalVectors", AbstractType::X3DChildNode));
  CHECK(nodeModel("OutlineGroup")->component == "GhostSpace");
}

TEST_CASE("node model: acceptableNodeTypes decide what a field takes", "[node_model]") {
  const NodeFieldModel* geometry = nodeModel("Shape")->findField("geometry");
  REQUIRE(geometry != nullptr);
  CHECK(acceptsNode(*geometry, *nodeModel("Box")));
  CHECK(!acceptsNode(*geometry, *nodeModel("Material")));
  const NodeFieldModel* source = nodeModel("Sound")->findField("source");
  REQUIRE(source != nullptr);
  CHECK(acceptsNode(*source, *nodeModel("AudioClip")));
  CHECK(acceptsNode(*source, *nodeModel("MovieTexture")));  // a concrete name in the list
  CHECK(!acceptsNode(*source, *nodeModel("ImageTexture")));
  const NodeFieldModel* children = nodeModel("OutlineGroup")->findField("children");
  REQUIRE(children != nullptr);
  CHECK(acceptsNode(*children, *nodeModel("Shape")));
  CHECK(!acceptsNode(*children, *nodeModel("Coordinate")));
}

TEST_CASE("node model: every VRML97 node is its X3D namesake with the same fields",
          "[node_model]") {
  // VRML97 names X3D changed (ISO/IEC 19775-1 annex on VRML97 compatibility).
  const std::map<std::string, std::string> renamed = {
      {"Collision.collide", "enabled"}, {"LOD.level", "children"}, {"Switch.choice", "children"}};
  std::size_t checked = 0;
  for (const NodeTableEntry& e : nodeTableEntries()) {
    const auto type = builtInNodeType(e.name);
    REQUIRE(type);
    REQUIRE(type->model != nullptr);
    CHECK(type->model->name == e.name);
    CHECK(type->model->extension == e.extension);
    for (const FieldSpec& f : type->fields) {
      const std::string key = std::string(e.name) + "." + f.name;
      const auto r = renamed.find(key);
      const NodeFieldModel* x3d =
          type->model->findField(r == renamed.end() ? std::string_view(f.name) : r->second);
      INFO(key);
      REQUIRE(x3d != nullptr);
      CHECK(x3d->type == fieldTypeName(f.type));
      ++checked;
    }
  }
  CHECK(checked > 300);
}

TEST_CASE("node model: a node's class is its type's", "[node_model]") {
  Scene s = parseVrml("#VRML V2.0 utf8\nDEF G OutlineGroup {}\nPROTO P [] { Transform {} }\nP {}\n",
                      "m.wrl");
  REQUIRE(s.rootNodes.size() == 2);
  CHECK(s.rootNodes[0]->typeId() == NodeTypeId::OutlineGroup);
  CHECK(s.rootNodes[0]->is(AbstractType::X3DGroupingNode));
  // A PROTO instance is its first body node (docs/architecture.md).
  CHECK(s.rootNodes[1]->typeId() == NodeTypeId::Transform);
}
