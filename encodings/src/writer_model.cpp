// The document the writers print (writer_impl.hpp), made from a parsed Scene. The parser
// expanded every PROTO instance and flattened ROUTEs to instance interfaces onto body
// members (proto.hpp, scene.hpp); this folds both back: an instance is written as its
// PROTO's name with the interface values it was given (ProtoInstance::values), a ROUTE end
// on a body member is mapped through the instances' IS links to the interface member, and
// the ROUTEs each instance copied from its PROTO's body are recognised by their source
// location and left to the PROTO. Statements keep their order among the root nodes by
// their source locations.
#include "writer_builder.hpp"

namespace gs::vrml::writing {

namespace model {

WDocument Builder::build() {
  WDocument doc;
  doc.x3d = x3dOut_;
  if (x3dOut_) {
    doc.version = version_;
    doc.profile = x3dIn_ ? scene_.x3d.profile : "Immersive";
    doc.components = scene_.x3d.components;
    doc.meta = scene_.x3d.meta;
  } else if (x3dIn_) {
    if (!scene_.x3d.profile.empty() || !scene_.x3d.components.empty())
      warn({}, "the PROFILE and COMPONENT statements have no VRML97 form: not written");
    for (const auto& [name, content] : scene_.x3d.meta)
      warn({}, "META \"" + name + "\" \"" + content + "\" has no VRML97 form: not written");
  }
  // Length and angle units were applied to the values when read (a scaled Transform
  // around each root, angles in radians): written so, without the UNIT. Mass and force
  // are only recorded (no physics here): kept.
  for (const X3dUnit& u : scene_.x3d.units) {
    if (x3dOut_ && u.category != "length" && u.category != "angle") {
      doc.units.push_back(u);
      continue;
    }
    warn({}, "UNIT " + u.category + " " + u.name + " is not written: " +
                 (x3dOut_ ? "the values were converted to base units (metres, radians) when "
                            "read, and are written so"
                          : "VRML97 has no UNIT statement"));
  }
  for (const auto& p : scene_.protos) topProtos_.insert(p.get());
  // (extraTop_ types are declared at the top too once written.)
  for (const NodePtr& n : scene_.rootNodes) {
    survey(n);
    if (n) ++rootIndex_;
  }
  for (const auto& p : scene_.protos) surveyType(p.get());

  // ROUTEs are mapped first (an instance routed to keeps its DEF). Then every statement
  // takes its place among the root nodes by source location (before the first root that
  // follows it), and PROTOs and roots are built in that order, so that a USE in a PROTO
  // interface finds the DEF it named before it.
  std::vector<std::pair<SourceLocation, WStatement>> others;
  std::set<LocKey> copied;  // ROUTEs the instances copied from their PROTOs' bodies
  for (const ProtoDefinition* d : allBodies_)
    for (const Route& r : d->routes)
      if (r.location.line > 0) copied.insert(keyOf(r.location));
  addRoutes(scene_.routes, copied, others);
  addX3dStatements(others);
  const std::size_t firstProto = others.size();
  std::vector<const NodeType*> protos;
  for (const auto& p : scene_.protos) protos.push_back(p.get());
  for (const NodeType* t : extraTop_) {
    // In the body of the node that holds the first instance, where the Classic encodings
    // can say it (the file had it in a node); else at the top.
    const Node* parent = extraParent_[t];
    if (protosInBodies_ && parent != nullptr && instanceType(*parent) == nullptr)
      bodyProtos_[parent].push_back(t);
    else
      protos.push_back(t);
  }
  for (const NodeType* p : protos) {
    WStatement s;
    s.kind = WStatement::Kind::proto;
    others.emplace_back(p->proto ? p->proto->location : SourceLocation{}, std::move(s));
  }
  std::vector<const NodePtr*> roots;
  for (const NodePtr& n : scene_.rootNodes)
    if (n) roots.push_back(&n);
  auto before = [](const SourceLocation& a, const SourceLocation& b) {
    return a.file == b.file && a.line > 0 && b.line > 0 &&
           std::pair(a.line, a.column) < std::pair(b.line, b.column);
  };
  std::vector<std::pair<std::size_t, std::size_t>> order;  // (root index, statement)
  for (std::size_t i = 0; i < others.size(); ++i) {
    const SourceLocation& at = others[i].first;
    std::size_t r = 0;
    if (at.line > 0) {
      r = roots.size();
      for (std::size_t k = 0; k < roots.size(); ++k)
        if (before(at, (*roots[k])->location)) {
          r = k;
          break;
        }
      // A PROTO goes before the first root that holds an instance of it (X3D allows
      // PROTO statements in MFNode values: it may be inside that root).
      if (i >= firstProto)
        if (auto it = firstUse_.find(protos[i - firstProto]);
            it != firstUse_.end() && it->second < r) {
          r = it->second;
          warn(at, "PROTO " + protos[i - firstProto]->name +
                       " was declared inside a node: written before that root node");
        }
      if (i >= firstProto + scene_.protos.size())
        warn(at, "PROTO " + protos[i - firstProto]->name +
                     " was declared inside a node: written at the top of the file");
    } else if (i < firstProto) {
      r = roots.size();
    }
    order.emplace_back(r, i);
  }
  std::stable_sort(order.begin(), order.end(), [&](const auto& a, const auto& b) {
    if (a.first != b.first) return a.first < b.first;
    // PROTOs the file declared inside nodes first: a top-level PROTO may use them.
    const bool ea = a.second >= firstProto + scene_.protos.size();
    const bool eb = b.second >= firstProto + scene_.protos.size();
    if (ea != eb) return ea;
    const SourceLocation& x = others[a.second].first;
    const SourceLocation& y = others[b.second].first;
    return std::pair(x.line, x.column) < std::pair(y.line, y.column);
  });
  auto emit = [&](std::size_t i) {
    WStatement& s = others[i].second;
    if (s.kind == WStatement::Kind::route) checkRoute(s.route, others[i].first);
    if (i >= firstProto) {
      s.proto = protoOf(*protos[i - firstProto]);
      if (emptyProtos_.contains(protos[i - firstProto])) return;
    }
    doc.statements.push_back(std::move(s));
  };
  std::size_t next = 0;
  for (std::size_t r = 0; r <= roots.size(); ++r) {
    while (next < order.size() && order[next].first <= r) emit(order[next++].second);
    if (r == roots.size()) break;
    WStatement s;
    s.node = nodeOf(*roots[r]);
    if (s.node.node != nullptr) doc.statements.push_back(std::move(s));
  }
  dropRoutesToUnwritten(doc.statements);
  flushDiagnostics();
  doc.owned = std::move(owned_);
  return doc;
}

void Builder::warn(SourceLocation at, std::string message) {
  if (at.file.empty()) at.file = scene_.url;
  diag_.warning(std::move(at), std::move(message));
}

void Builder::drop(const SourceLocation& at, const std::string& message) {
  auto [it, added] = dropped_.try_emplace(message, 0, at);
  if (added) droppedOrder_.push_back(message);
  ++it->second.first;
}

void Builder::flushDiagnostics() {
  for (const std::string& m : droppedOrder_) {
    const auto& [count, at] = dropped_[m];
    warn(at, count > 1 ? m + " (" + std::to_string(count) + " times)" : m);
  }
}

void Builder::surveyType(const NodeType* t) {
  if (t == nullptr || !t->proto) return;
  firstUse_.try_emplace(t, rootIndex_);
  // A PROTO whose instances are outside every PROTO body but that the file declared
  // inside a node (X3D allows PROTO statements in MFNode values; Scene::protos lists
  // only those at the top): written at the top, before the root node it was in.
  if (bodyDepth_ == 0 && !topProtos_.contains(t) &&
      std::find(extraTop_.begin(), extraTop_.end(), t) == extraTop_.end()) {
    extraTop_.push_back(t);
    extraParent_[t] = surveyParent_;
  }
  if (!surveyedTypes_.insert(t).second) return;
  // Interface defaults are written where the declaration is; bodies in their own scope.
  const ProtoDefinition& d = *t->proto;
  for (const FieldSpec& f : t->fields) surveyValue(f.defaultValue);
  ++bodyDepth_;
  if (d.external) {
    if (d.resolved) surveyType(d.resolved.get());
  } else {
    allBodies_.push_back(&d);
    for (const NodePtr& n : d.body) survey(n);
  }
  --bodyDepth_;
}

void Builder::surveyValue(const FieldValue& v) {
  if (v.type() == FieldType::SFNode) survey(v.get<FieldType::SFNode>());
  if (v.type() == FieldType::MFNode)
    for (const NodePtr& c : v.get<FieldType::MFNode>()) survey(c);
}

void Builder::survey(const NodePtr& n) {
  if (!n) return;
  ++references_[n.get()];
  if (!n->defName.empty()) usedNames_.insert(n->defName);
  if (!surveyed_.insert(n.get()).second) return;
  const Node* parent = surveyParent_;
  if (const ProtoInstance* p = declaredInterface(*n)) {
    surveyType(p->type.get());
    for (const InstanceLink& k : p->links)
      if (const NodePtr b = k.node.lock())
        links_.emplace(b.get(), std::tuple(k.nodeField, n.get(), k.protoField));
    surveyParent_ = n.get();
    for (const FieldValue& v : p->values) surveyValue(v);
    surveyParent_ = parent;
    return;
  }
  surveyType(instanceType(*n));
  surveyParent_ = n.get();
  for (std::size_t i = 0; i < n->fieldCount(); ++i) surveyValue(n->fieldAt(i));
  surveyParent_ = parent;
}

const std::string& Builder::ident(const std::string& raw) {
  auto [it, added] = idents_.try_emplace(raw);
  if (!added) return it->second;
  it->second = classicIdent(raw);
  if (it->second != raw && !raw.empty())
    warn({}, "the name '" + raw + "' is no identifier of the Classic encoding: written as '" +
                 it->second + "'");
  return it->second;
}

std::string Builder::defOf(const Node& n, bool make) {
  if (!n.defName.empty()) return ident(n.defName);
  if (auto it = madeNames_.find(&n); it != madeNames_.end()) return it->second;
  if (!make) return {};
  std::string name;
  do {
    name = "_" + n.typeName() + "_" + std::to_string(madeNames_.size() + 1 + extraNumber_++);
  } while (usedNames_.contains(name));
  usedNames_.insert(name);
  madeNames_.emplace(&n, name);
  return name;
}

std::string Builder::fieldName(const Node& n, const std::string& name) const {
  if (!x3dOut_) return name;
  switch (n.typeId()) {
    case NodeTypeId::Switch:
      return name == "choice" ? "children" : name;
    case NodeTypeId::LOD:
      return name == "level" ? "children" : name;
    case NodeTypeId::Collision:
      return name == "collide" ? "enabled" : name;
    case NodeTypeId::ComposedCubeMapTexture:
      // X3D 3 named the faces without "Texture" (castle-model-viewer 4.2 reads only those).
      if (x3d3Out_ && name.ends_with("Texture")) return name.substr(0, name.size() - 7);
      return name;
    default:
      return name;
  }
}

std::string Builder::containerDefault(const Node& n) const {
  const NodeModel* m = n.type().model;
  if (m == nullptr) return {};
  if (x3d3Out_ && n.is(AbstractType::X3DMetadataObject)) return "metadata";
  return std::string(m->containerField);
}

std::shared_ptr<const NodeType> Builder::baseType(const Node& n) const {
  return x3dIn_ ? x3dNodeType(n.typeName()) : builtInNodeType(n.typeName());
}

std::vector<const IsConnection*> Builder::connections(const Node* n, int field) const {
  std::vector<const IsConnection*> out;
  if (body_ == nullptr) return out;
  for (const IsConnection& c : body_->connections)
    if (c.node.get() == n && c.nodeField == field) out.push_back(&c);
  return out;
}

const std::string& Builder::bodyMember(int protoField) const {
  return bodyType_->fields[static_cast<std::size_t>(protoField)].name;
}

std::vector<WNode> Builder::nodesOf(const FieldValue& v) {
  std::vector<WNode> out;
  auto one = [&](const NodePtr& c) {
    if (!c) return;
    WNode w = nodeOf(c);
    if (w.node != nullptr) out.push_back(std::move(w));
  };
  if (v.type() == FieldType::SFNode) one(v.get<FieldType::SFNode>());
  if (v.type() == FieldType::MFNode)
    for (const NodePtr& c : v.get<FieldType::MFNode>()) one(c);
  return out;
}

WNode Builder::nodeOf(const NodePtr& np) {
  const Node& n = *np;
  WNode w;
  if (written_.contains(&n) && !defOf(n).empty()) {
    w.node = &n;
    w.use = true;
    w.def = defOf(n);
    const NodeType* it = instanceType(n);
    w.instance = it != nullptr;
    w.typeName = it != nullptr ? it->name : n.typeName();
    if (it == nullptr) w.containerDefault = containerDefault(n);
    if (auto b = binding_.find(w.def); b != binding_.end() && b->second != &n)
      drop(n.location, "a USE of this node (DEF " + n.defName +
                           "): that DEF name was given to another node in between: the "
                           "file read back will USE that one");
    return w;
  }
  const NodeType* itype = instanceType(n);
  if (itype != nullptr && emptyProtos_.contains(itype)) {
    drop(n.location, "instance of " + itype->name + " not written (its PROTO was not)");
    return w;
  }
  if (itype == nullptr && !x3dOut_ && x3dIn_ && !builtInNodeType(n.typeName())) {
    drop(n.location, "X3D node " + n.typeName() + " has no VRML97 form: not written");
    return w;
  }
  written_.insert(&n);
  w.node = &n;
  w.def = defOf(n);
  if (!w.def.empty()) binding_[w.def] = &n;  // (an instance's DEF may be cleared below)
  if (itype != nullptr) {
    instanceOf(n, *itype, w);
  } else {
    plainNode(n, w);
  }
  return w;
}

void Builder::instanceOf(const Node& n, const NodeType& type, WNode& w) {
  w.instance = true;
  w.typeName = type.name;
  const ProtoInstance* p = declaredInterface(n);
  // An instance without a DEF of its own carries its body's first node's DEF name.
  if (const ProtoDefinition* b = bodyOf(&type); p != nullptr && b != nullptr && !b->body.empty() &&
                                                b->body.front()->defName == n.defName &&
                                                references_[&n] <= 1 && !routed_.contains(&n)) {
    if (auto it = binding_.find(w.def); it != binding_.end() && it->second == &n)
      binding_.erase(it);
    w.def.clear();
  }
  for (std::size_t m = 0; m < type.fields.size(); ++m) {
    const FieldSpec& f = type.fields[m];
    // IS inside a PROTO body: the member's links lead to body members the enclosing
    // body connected.
    std::string is;
    if (p == nullptr) {
      for (const IsConnection* c : connections(&n, static_cast<int>(m)))
        is = bodyMember(c->protoField);
    } else if (body_ != nullptr) {
      for (const InstanceLink& k : p->linksOf(static_cast<int>(m))) {
        const NodePtr b = k.node.lock();
        for (const IsConnection* c : connections(b.get(), k.nodeField))
          is = bodyMember(c->protoField);
        if (!is.empty()) break;
      }
    }
    if (!is.empty()) {
      WField wf;
      wf.name = f.name;
      wf.type = f.type;
      wf.isMember = is;
      wf.isAccess = f.access;
      w.fields.push_back(std::move(wf));
      continue;
    }
    if (!carriesValue(f.access)) continue;
    const FieldValue& v = p != nullptr ? p->values[m] : n.fieldAt(m);
    if (sameValue(v, f.defaultValue)) continue;
    w.fields.push_back(valueField(f.name, v, type.name, n.location));
  }
}

void Builder::plainNode(const Node& n, WNode& w) {
  if (auto it = bodyProtos_.find(&n); it != bodyProtos_.end())
    for (const NodeType* t : it->second) {
      auto p = protoOf(*t);
      if (!emptyProtos_.contains(t)) w.protos.push_back(std::move(p));
    }
  const NodeType& type = n.type();
  w.typeName = n.typeName();
  w.containerDefault = containerDefault(n);
  const auto base = baseType(n);
  const std::size_t userStart = type.userFields && base
                                    ? std::min(base->fields.size(), type.fields.size())
                                    : type.fields.size();
  std::shared_ptr<const NodeType> vrml97;
  if (!x3dOut_ && x3dIn_) vrml97 = builtInNodeType(n.typeName());
  for (std::size_t i = 0; i < type.fields.size(); ++i) {
    const FieldSpec& f = type.fields[i];
    const auto is = connections(&n, static_cast<int>(i));
    const bool user = i >= userStart;
    const FieldValue& v = n.fieldAt(i);
    const bool valued = carriesValue(f.access) && (user || !sameValue(v, f.defaultValue));
    if (!user && vrml97 && vrml97->findExact(f.name) < 0 && (valued || !is.empty())) {
      drop(n.location,
           "X3D field " + n.typeName() + "." + f.name + " has no VRML97 form: not written");
      continue;
    }
    if (user) {
      WDecl d = declOf(f, is.empty() ? &v : nullptr, n.typeName(), n.location);
      if (!x3dOut_ && type.script && d.access == AccessType::exposedField) {
        // VRML97 Scripts have no exposedField (clause 6.40): a field, without its events.
        drop(n.location, "Script inputOutput " + f.name +
                             " has no VRML97 form: written as a field (its events are lost)");
        d.access = AccessType::field;
      }
      if (!is.empty()) d.isMember = bodyMember(is.front()->protoField);
      w.decls.push_back(std::move(d));
      continue;
    }
    for (const IsConnection* c : is) {
      // VRML97 connects a node's field only to a field of the interface (clause 4.8.3,
      // table 4.4); X3D made many of them inputOutput.
      if (vrml97 && !user) {
        const int k = vrml97->findExact(f.name);
        const AccessType member = bodyType_->fields[static_cast<std::size_t>(c->protoField)].access;
        if (k >= 0 &&
            vrml97->fields[static_cast<std::size_t>(k)].access != AccessType::exposedField &&
            vrml97->fields[static_cast<std::size_t>(k)].access != member) {
          drop(n.location,
               "IS of " + n.typeName() + "." + f.name + " (a " +
                   std::string(accessTypeName(vrml97->fields[static_cast<std::size_t>(k)].access)) +
                   " in VRML97) to " + std::string(accessTypeName(member)) + " " +
                   bodyMember(c->protoField) + ": not written");
          continue;
        }
      }
      WField wf;
      wf.name = fieldName(n, f.name);
      if (c->nodeAccess == AccessType::eventIn && f.access == AccessType::exposedField)
        wf.name = "set_" + wf.name;
      else if (c->nodeAccess == AccessType::eventOut && f.access == AccessType::exposedField)
        wf.name += "_changed";
      wf.type = f.type;
      wf.isMember = bodyMember(c->protoField);
      wf.isAccess = c->nodeAccess;
      w.fields.push_back(std::move(wf));
    }
    if (!is.empty() || !valued) continue;
    w.fields.push_back(valueField(fieldName(n, f.name), v, n.typeName(), n.location));
  }
}

}  // namespace model

WDocument buildDocument(const Scene& scene, const WriteOptions& options, Diagnostics& diagnostics) {
  model::Builder b(scene, options, diagnostics);
  return b.build();
}

}  // namespace gs::vrml::writing
