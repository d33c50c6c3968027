#include "runtime_fixture.hpp"

#include <catch2/catch.hpp>

#include <functional>
#include <unordered_set>

namespace gs::test {

vrml::Node& RunningWorld::node(const std::string& name) const {
  vrml::Node* found = nullptr;
  std::unordered_set<const vrml::Node*> seen;  // a field may name an ancestor
  std::function<void(const vrml::NodePtr&)> visit = [&](const vrml::NodePtr& n) {
    if (!n || found || !seen.insert(n.get()).second) return;
    if (n->defName == name) {
      found = n.get();
      return;
    }
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const vrml::FieldValue& v = n->fieldAt(i);
      if (v.type() == vrml::FieldType::SFNode) visit(v.get<vrml::FieldType::SFNode>());
      if (v.type() == vrml::FieldType::MFNode)
        for (const vrml::NodePtr& c : v.get<vrml::FieldType::MFNode>()) visit(c);
    }
  };
  for (const vrml::NodePtr& n : scene->rootNodes) visit(n);
  for (const vrml::NodePtr& n : scene->hiddenNodes) visit(n);
  REQUIRE(found != nullptr);
  return *found;
}

int RunningWorld::field(const vrml::Node& n, const std::string& fieldName) {
  const int i = n.type().findField(fieldName);
  REQUIRE(i >= 0);
  return i;
}

void RunningWorld::send(const std::string& name, const std::string& fieldName,
                        vrml::FieldValue value) {
  vrml::Node& n = node(name);
  REQUIRE(model->postEvent(n, field(n, fieldName), std::move(value)));
  model->processEvents();
}

}  // namespace gs::test
