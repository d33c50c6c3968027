// The PROTO declarations, ROUTEs and X3D statements (PROFILE, COMPONENT, UNIT, META,
// IMPORT, EXPORT) of the document the writers print (writer_builder.hpp), with the ROUTEs
// that name nodes left out dropped and those whose DEF names were reused checked.
#include "writer_builder.hpp"

namespace gs::vrml::writing::model {

std::shared_ptr<WProto> Builder::protoOf(const NodeType& t) {
  auto p = std::make_shared<WProto>();
  p->name = t.name;
  const ProtoDefinition& d = *t.proto;
  p->external = d.external;
  const SourceLocation at = d.location;
  for (const FieldSpec& f : t.fields)
    p->interface.push_back(declOf(f, d.external ? nullptr : &f.defaultValue, t.name, at));
  if (d.external) {
    p->urls = &d.urls;
    return p;
  }
  const ProtoDefinition* outerBody = body_;
  const NodeType* outerType = bodyType_;
  const auto outerBinding = binding_;  // the body's DEF names are its own
  const std::size_t declared = declaredInBodies_.size();
  body_ = &d;
  bodyType_ = &t;
  // PROTOs declared in this body (the parser keeps no list of them): the types of the
  // instances in it that are declared neither at the top nor around it.
  // The body's own ROUTEs (not those its instances of other PROTOs copied), mapped first
  // so that an instance routed to keeps its DEF.
  std::set<LocKey> copied;
  for (const NodeType* nt : instanceTypesIn(d)) {
    const ProtoDefinition* b = bodyOf(nt);
    if (b == nullptr || b == &d) continue;
    for (const Route& r : b->routes)
      if (r.location.line > 0) copied.insert(keyOf(r.location));
  }
  std::vector<std::pair<SourceLocation, WStatement>> routes;
  addRoutes(d.routes, copied, routes);
  for (const NodeType* nt : nestedTypes()) {
    declaredInBodies_.push_back(nt);
    WStatement s;
    s.kind = WStatement::Kind::proto;
    s.proto = protoOf(*nt);
    if (!emptyProtos_.contains(nt)) p->body.push_back(std::move(s));
  }
  for (const NodePtr& n : d.body) {
    WStatement s;
    s.node = nodeOf(n);
    if (s.node.node != nullptr) p->body.push_back(std::move(s));
  }
  const bool anyNode = std::any_of(p->body.begin(), p->body.end(), [](const WStatement& s) {
    return s.kind == WStatement::Kind::node;
  });
  for (auto& [at2, s] : routes) {
    checkRoute(s.route, at2);
    p->body.push_back(std::move(s));
  }
  dropRoutesToUnwritten(p->body);
  if (!anyNode) {
    drop(d.location, "PROTO " + t.name +
                         ": no node of its body can be written: the PROTO "
                         "and its instances are not written");
    emptyProtos_.insert(&t);
  }
  body_ = outerBody;
  bodyType_ = outerType;
  binding_ = outerBinding;
  declaredInBodies_.resize(declared);
  return p;
}

std::vector<const NodeType*> Builder::nestedTypes() const {
  std::vector<const NodeType*> out;
  for (const NodeType* t : instanceTypesIn(*body_)) {
    if (topProtos_.contains(t) || t == bodyType_ ||
        std::find(extraTop_.begin(), extraTop_.end(), t) != extraTop_.end())
      continue;
    if (std::find(declaredInBodies_.begin(), declaredInBodies_.end(), t) != declaredInBodies_.end())
      continue;
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  return out;
}

void Builder::dropRoutesToUnwritten(std::vector<WStatement>& statements) {
  std::erase_if(statements, [&](const WStatement& s) {
    if (s.kind != WStatement::Kind::route) return false;
    const WRoute& r = s.route;
    const bool gone = (r.from != nullptr && !written_.contains(r.from)) ||
                      (r.to != nullptr && !written_.contains(r.to));
    if (gone)
      drop(r.from != nullptr && !written_.contains(r.from) ? r.from->location : r.to->location,
           "ROUTE " + r.fromNode + "." + r.fromField + " TO " + r.toNode + "." + r.toField +
               ": a node it names was not written: not written");
    return gone;
  });
}

void Builder::checkRoute(const WRoute& r, const SourceLocation& at) {
  auto other = [&](const std::string& name, const Node* node) {
    if (node == nullptr) return false;
    auto b = binding_.find(name);
    return b != binding_.end() && b->second != node;
  };
  if (other(r.fromNode, r.from) || other(r.toNode, r.to))
    warn(at, "ROUTE " + r.fromNode + "." + r.fromField + " TO " + r.toNode + "." + r.toField +
                 ": a DEF name it uses names another node where it is written");
}

}  // namespace gs::vrml::writing::model
