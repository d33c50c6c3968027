// The traversal's depth guard (scene::kMaxWalkDepth): a node graph a Script made with a
// node among its own descendants, or a chain deeper than any file, is walked to the
// limit and reported once, never followed until the stack runs out.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;
namespace vrml = gs::vrml;

namespace {

std::size_t depthErrors(const SceneTraversal& t) {
  std::size_t n = 0;
  for (const vrml::Diagnostic& d : t.diagnostics().items)
    n += d.message.find("deeper than 512 nodes") != std::string::npos;
  return n;
}

void setChildren(vrml::Node& parent, vrml::NodePtr child) {
  const int children = parent.type().findField("children");
  REQUIRE(children >= 0);
  parent.setField(
      static_cast<std::size_t>(children),
      vrml::FieldValue::make<vrml::FieldType::MFNode>(std::vector<vrml::NodePtr>{child}));
}

}  // namespace

TEST_CASE("a node among its own descendants is walked to the depth limit, said once", "[scene]") {
  auto scene = std::make_shared<vrml::Scene>(vrml::parseVrml(R"(#X3D V4.0 utf8
DEF A Group { children [ Shape { geometry Box { } } DEF B Transform { } ] }
)",
                                                             "cycle.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  const vrml::NodePtr a = scene->rootNodes.at(0);
  const vrml::NodePtr b = a->mfnode("children").at(1);
  setChildren(*b, a);  // as a Script's B.children = new MFNode(A) does
  SceneTraversal t(scene);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  // The Box is met once per turn of the cycle (two levels), down to the limit.
  CHECK(frame.shapes.size() == gs::scene::kMaxWalkDepth / 2);
  CHECK(depthErrors(t) == 1);
  t.collect(t.boundViewpointCamera(), frame);  // the next frame: said once only
  CHECK(depthErrors(t) == 1);
  b->setField(static_cast<std::size_t>(b->type().findField("children")),
              vrml::FieldValue::make<vrml::FieldType::MFNode>(
                  std::vector<vrml::NodePtr>{}));  // the cycle freed
}

TEST_CASE("a chain of groups deeper than the limit is drawn down to it", "[scene]") {
  auto scene = std::make_shared<vrml::Scene>(
      vrml::parseVrml("#X3D V4.0 utf8\nDEF TOP Group { }\n", "chain.x3dv"));
  vrml::NodePtr below =
      vrml::parseVrml("#X3D V4.0 utf8\nShape { geometry Box { } }\n", "leaf.x3dv").rootNodes.at(0);
  // 3,000 Groups above the Shape, made as a Script makes them.
  for (int i = 0; i < 3000; ++i) {
    vrml::NodePtr g = vrml::parseVrml("#X3D V4.0 utf8\nGroup { }\n", "g.x3dv").rootNodes.at(0);
    setChildren(*g, below);
    below = g;
  }
  setChildren(*scene->rootNodes.at(0), below);
  SceneTraversal t(scene);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  CHECK(frame.shapes.empty());  // the Shape lies 3,002 levels down
  CHECK(depthErrors(t) == 1);
}
