// Releasing a node graph: ~Node frees its node values from one list, so a chain of nodes
// deeper than the stack allows (a Script can build one, a node at a time) does not
// overflow it, and what other owners still hold stays whole.
#include "vrml/node.hpp"
#include "vrml/node_table.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <vector>

using namespace gs::vrml;

namespace {

/// `parent`'s children become {child}.
void adopt(Node& parent, NodePtr child) {
  parent.field("children")->get<FieldType::MFNode>() = std::vector<NodePtr>{std::move(child)};
}

}  // namespace

TEST_CASE("node release: a chain 200,000 Groups deep is freed without recursion",
          "[vrml][release]") {
  const auto group = builtInNodeType("Group");
  const auto transform = builtInNodeType("Transform");
  REQUIRE(group);
  REQUIRE(transform);
  // Recursive destruction needs about 200 bytes of stack a level at -O2, more under the
  // sanitizers: 200,000 levels are far beyond an 8 MiB stack in every build.
  NodePtr top = std::make_shared<Node>(group);
  std::weak_ptr<Node> bottom = top;
  for (int i = 0; i < 200000; ++i) {
    auto parent = std::make_shared<Node>(i % 2 == 0 ? transform : group);
    adopt(*parent, std::move(top));
    top = std::move(parent);
  }
  // An SFNode value on the way down (Shape.geometry) is released the same way.
  auto shape = std::make_shared<Node>(builtInNodeType("Shape"));
  *shape->field("geometry") = FieldValue::make<FieldType::SFNode>(top);
  top.reset();
  CHECK_FALSE(bottom.expired());
  shape.reset();
  CHECK(bottom.expired());
}

TEST_CASE("node release: a child another owner holds keeps its own children", "[vrml][release]") {
  const auto group = builtInNodeType("Group");
  auto parent = std::make_shared<Node>(group);
  auto kept = std::make_shared<Node>(group);
  auto grandchild = std::make_shared<Node>(builtInNodeType("Shape"));
  adopt(*kept, grandchild);
  adopt(*parent, kept);
  std::weak_ptr<Node> grandchildSeen = grandchild;
  grandchild.reset();
  parent.reset();
  REQUIRE(kept->mfnode("children").size() == 1);
  CHECK(kept->mfnode("children").at(0).get() == grandchildSeen.lock().get());
  kept.reset();
  CHECK(grandchildSeen.expired());
}
