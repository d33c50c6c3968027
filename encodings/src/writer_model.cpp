// The document the writers print (writer_impl.hpp), made from a parsed Scene. The parser
// expanded every PROTO instance and flattened ROUTEs to instance interfaces onto body
// members (proto.hpp, scene.hpp); this folds both back: an instance is written as its
// PROTO's name with the interface values it was given (ProtoInstance::values), a ROUTE end
// on a body member is mapped through the instances' IS links to the interface member, and
// the ROUTEs each instance copied from its PROTO's body are recognised by their source
// location and left to the PROTO. Statements keep their order among the root nodes by
// their source locations.
#include "encodings/node_types.hpp"
#include "vrml/node_table.hpp"
#include "vrml/proto.hpp"
#include "writer_impl.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

namespace gs::vrml::writing {

namespace {

using LocKey = std::tuple<std::string, int, int>;

LocKey keyOf(const SourceLocation& l) {
  return {l.file, l.line, l.column};
}

bool sameValue(const FieldValue& a, const FieldValue& b) {
  return a.storage() == b.storage();
}

bool carriesValue(AccessType a) {
  return a == AccessType::field || a == AccessType::exposedField;
}

class Builder {
 public:
  Builder(const Scene& scene, const WriteOptions& options, Diagnostics& diagnostics)
      : scene_(scene), diag_(diagnostics) {
    x3dIn_ = !scene.x3d.version.empty();
    x3dOut_ = options.encoding != Encoding::vrml97;
    version_ = x3dIn_ ? scene.x3d.version : options.x3dVersionForVrml97;
    x3d3Out_ = x3dOut_ && version_.starts_with('3');
    // ISO/IEC 14772-1 and 19776-2 allow PROTO statements in a node's body (nodeBodyElement);
    // the XML reader moves them after the node's children.
    protosInBodies_ = options.encoding == Encoding::vrml97 || options.encoding == Encoding::classic;
  }

  WDocument build() {
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

 private:
  const Scene& scene_;
  Diagnostics& diag_;
  bool x3dIn_ = false, x3dOut_ = false, x3d3Out_ = false;
  std::string version_;
  std::unordered_set<const NodeType*> topProtos_;
  std::unordered_set<const Node*> surveyed_;
  std::unordered_set<const NodeType*> surveyedTypes_;
  std::vector<const ProtoDefinition*> allBodies_;
  std::vector<const NodeType*> extraTop_;  // PROTOs declared in nodes, used outside bodies
  std::unordered_map<const NodeType*, const Node*> extraParent_;  // -> node of 1st instance
  const Node* surveyParent_ = nullptr;  // the node whose field survey() is in
  bool protosInBodies_ = false;         // the encoding has PROTO statements in node bodies
  std::unordered_map<const Node*, std::vector<const NodeType*>> bodyProtos_;
  int bodyDepth_ = 0;
  std::size_t rootIndex_ = 0;                                  // the root being surveyed
  std::unordered_map<const NodeType*, std::size_t> firstUse_;  // PROTO -> first root using it
  // (body member node, field index) -> (instance node, interface member)
  std::unordered_multimap<const Node*, std::tuple<int, const Node*, int>> links_;
  std::unordered_map<const Node*, int> references_;
  std::unordered_set<const Node*> written_;
  std::unordered_map<std::string, const Node*> binding_;  // DEF name -> node, as written so far
  // Aggregated diagnostics: message -> (count, first place).
  std::map<std::string, std::pair<int, SourceLocation>> dropped_;
  std::vector<std::string> droppedOrder_;
  std::deque<FieldValue> owned_;
  // The PROTO body being written, with the PROTO types declared around it.
  const ProtoDefinition* body_ = nullptr;
  const NodeType* bodyType_ = nullptr;
  std::vector<const NodeType*> declaredInBodies_;

  void warn(SourceLocation at, std::string message) {
    if (at.file.empty()) at.file = scene_.url;
    diag_.warning(std::move(at), std::move(message));
  }
  void drop(const SourceLocation& at, const std::string& message) {
    auto [it, added] = dropped_.try_emplace(message, 0, at);
    if (added) droppedOrder_.push_back(message);
    ++it->second.first;
  }
  void flushDiagnostics() {
    for (const std::string& m : droppedOrder_) {
      const auto& [count, at] = dropped_[m];
      warn(at, count > 1 ? m + " (" + std::to_string(count) + " times)" : m);
    }
  }

  // ---- survey: references, IS links, the PROTO bodies instances copied --------------------

  void surveyType(const NodeType* t) {
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

  void surveyValue(const FieldValue& v) {
    if (v.type() == FieldType::SFNode) survey(v.get<FieldType::SFNode>());
    if (v.type() == FieldType::MFNode)
      for (const NodePtr& c : v.get<FieldType::MFNode>()) survey(c);
  }

  void survey(const NodePtr& n) {
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

  // ---- names ----

  std::unordered_map<std::string, std::string> idents_;

  // `raw` as classicIdent() writes it; a warning the first time a name changes (glTF's
  // "Cube.001").
  const std::string& ident(const std::string& raw) {
    auto [it, added] = idents_.try_emplace(raw);
    if (!added) return it->second;
    it->second = classicIdent(raw);
    if (it->second != raw && !raw.empty())
      warn({}, "the name '" + raw + "' is no identifier of the Classic encoding: written as '" +
                   it->second + "'");
    return it->second;
  }

  // The DEF name `n` is written with: its own (as ident() spells it), or, for a node a ROUTE
  // names that has none (the glTF importer's interpolators and Transforms), one made up
  // when `make`: "_" + its type + a number, unused by the world.
  std::unordered_map<const Node*, std::string> madeNames_;
  std::unordered_set<std::string> usedNames_;
  std::string defOf(const Node& n, bool make = false) {
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
  std::size_t extraNumber_ = 0;

  // ---- nodes ------------------------------------------------------------------------------

  // The name the target gives field `name` of a node of `type`: X3D renamed three of
  // VRML97's fields, and X3D 4 renamed ComposedCubeMapTexture's faces.
  std::string fieldName(const Node& n, const std::string& name) const {
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

  // The XML encoding's containerField default of `n`'s type (X3D 3 put metadata nodes in
  // `metadata` by default, as the reader does for a 3.x file).
  std::string containerDefault(const Node& n) const {
    const NodeModel* m = n.type().model;
    if (m == nullptr) return {};
    if (x3d3Out_ && n.is(AbstractType::X3DMetadataObject)) return "metadata";
    return std::string(m->containerField);
  }

  // The built-in type `n` started as, before a Script or shader declared its own fields.
  std::shared_ptr<const NodeType> baseType(const Node& n) const {
    return x3dIn_ ? x3dNodeType(n.typeName()) : builtInNodeType(n.typeName());
  }

  // The IS connections of the PROTO body being written that name member `field` of `n`.
  std::vector<const IsConnection*> connections(const Node* n, int field) const {
    std::vector<const IsConnection*> out;
    if (body_ == nullptr) return out;
    for (const IsConnection& c : body_->connections)
      if (c.node.get() == n && c.nodeField == field) out.push_back(&c);
    return out;
  }

  const std::string& bodyMember(int protoField) const {
    return bodyType_->fields[static_cast<std::size_t>(protoField)].name;
  }

  // Node values of an SFNode / MFNode field.
  std::vector<WNode> nodesOf(const FieldValue& v) {
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

  // A value the VRML97 target can hold: X3D's field types become their nearest VRML97
  // type (field.hpp toNearestVrml97), with a diagnostic.
  const FieldValue* targetValue(const FieldValue& v, const std::string& what,
                                const SourceLocation& at) {
    if (x3dOut_ || static_cast<int>(v.type()) < kVrml97FieldTypeCount) return &v;
    drop(at, what + ": X3D field type " + std::string(fieldTypeName(v.type())) +
                 " has no VRML97 form: written as " +
                 std::string(fieldTypeName(nearestVrml97Type(v.type()))));
    owned_.push_back(toNearestVrml97(v));
    return &owned_.back();
  }
  FieldType targetType(FieldType t) const { return x3dOut_ ? t : nearestVrml97Type(t); }

  WDecl declOf(const FieldSpec& f, const FieldValue* value, const std::string& owner,
               const SourceLocation& at) {
    WDecl d;
    d.access = f.access;
    d.type = targetType(f.type);
    d.name = f.name;
    if (value != nullptr && carriesValue(f.access)) {
      if (f.type == FieldType::SFNode || f.type == FieldType::MFNode) {
        d.value = value;
        d.nodes = nodesOf(*value);
      } else {
        d.value = targetValue(*value, owner + "." + f.name, at);
      }
    }
    return d;
  }

  WNode nodeOf(const NodePtr& np) {
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

  void instanceOf(const Node& n, const NodeType& type, WNode& w) {
    w.instance = true;
    w.typeName = type.name;
    const ProtoInstance* p = declaredInterface(n);
    // An instance without a DEF of its own carries its body's first node's DEF name.
    if (const ProtoDefinition* b = bodyOf(&type);
        p != nullptr && b != nullptr && !b->body.empty() && b->body.front()->defName == n.defName &&
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

  WField valueField(const std::string& name, const FieldValue& v, const std::string& owner,
                    const SourceLocation& at) {
    WField wf;
    wf.name = name;
    wf.type = v.type();
    if (v.type() == FieldType::SFNode || v.type() == FieldType::MFNode) {
      wf.value = &v;
      wf.nodes = nodesOf(v);
    } else {
      wf.value = targetValue(v, owner + "." + name, at);
      wf.type = wf.value->type();
    }
    return wf;
  }

  void plainNode(const Node& n, WNode& w) {
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
          const AccessType member =
              bodyType_->fields[static_cast<std::size_t>(c->protoField)].access;
          if (k >= 0 &&
              vrml97->fields[static_cast<std::size_t>(k)].access != AccessType::exposedField &&
              vrml97->fields[static_cast<std::size_t>(k)].access != member) {
            drop(n.location, "IS of " + n.typeName() + "." + f.name + " (a " +
                                 std::string(accessTypeName(
                                     vrml97->fields[static_cast<std::size_t>(k)].access)) +
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

  // ---- PROTO declarations -----------------------------------------------------------------

  std::shared_ptr<WProto> protoOf(const NodeType& t) {
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

  // PROTO types whose instances the body being written holds and that are declared
  // neither at the top of the file nor around the body.
  std::vector<const NodeType*> nestedTypes() const {
    std::vector<const NodeType*> out;
    for (const NodeType* t : instanceTypesIn(*body_)) {
      if (topProtos_.contains(t) || t == bodyType_ ||
          std::find(extraTop_.begin(), extraTop_.end(), t) != extraTop_.end())
        continue;
      if (std::find(declaredInBodies_.begin(), declaredInBodies_.end(), t) !=
          declaredInBodies_.end())
        continue;
      if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
    }
    return out;
  }

  // ---- ROUTEs and X3D statements ----------------------------------------------------------

  std::unordered_set<const Node*> routed_;
  bool failedQuietly_ = false;                       // routeEnd() said why it failed
  std::unordered_set<const NodeType*> emptyProtos_;  // VRML97: every body node left out

  // The DEF name and member a ROUTE end names: an instance's interface member when `node`
  // is a body member an instance linked, else the node's own DEF name and the field.
  bool routeEnd(const NodePtr& node, const std::string& field, std::string& name,
                std::string& member, const Node*& named) {
    if (!node) return false;
    const int i = node->type().findField(field);
    auto [a, b] = links_.equal_range(node.get());
    for (auto it = a; it != b; ++it) {
      const auto& [nodeField, inst, protoField] = it->second;
      if (nodeField != i) continue;
      const ProtoInstance* p = declaredInterface(*inst);
      if (p == nullptr) continue;
      name = defOf(*inst, true);
      member = p->type->fields[static_cast<std::size_t>(protoField)].name;
      routed_.insert(inst);
      named = inst;
      return true;
    }
    if (!x3dOut_ && x3dIn_ && instanceType(*node) == nullptr) {
      // A field X3D added to a VRML97 node (or an X3D node) has no VRML97 event.
      const auto vrml97 = builtInNodeType(node->typeName());
      const NodeType& t = node->type();
      const bool user = t.userFields && vrml97 && i >= static_cast<int>(vrml97->fields.size());
      if (!user &&
          (!vrml97 || i < 0 || vrml97->findExact(t.fields[static_cast<std::size_t>(i)].name) < 0)) {
        drop(node->location, "ROUTE end " + node->typeName() + "." + field +
                                 " has no VRML97 form: ROUTE not written");
        failedQuietly_ = true;
        return false;
      }
    }
    name = defOf(*node, true);
    member = instanceType(*node) != nullptr ? field : fieldName(*node, field);
    routed_.insert(node.get());
    named = node.get();
    return true;
  }

  void addRoutes(const std::vector<Route>& routes, const std::set<LocKey>& copied,
                 std::vector<std::pair<SourceLocation, WStatement>>& out) {
    std::set<std::tuple<std::string, std::string, std::string, std::string, LocKey>> done;
    for (const Route& r : routes) {
      if (r.location.line > 0 && copied.contains(keyOf(r.location))) continue;
      WStatement s;
      s.kind = WStatement::Kind::route;
      WRoute& w = s.route;
      failedQuietly_ = false;
      if (!routeEnd(r.fromNode, r.fromField, w.fromNode, w.fromField, w.from) ||
          !routeEnd(r.toNode, r.toField, w.toNode, w.toField, w.to)) {
        if (failedQuietly_) continue;  // already said
        warn(r.location, "ROUTE " + r.fromField + " TO " + r.toField +
                             ": an end has no DEF name to write: not written");
        continue;
      }
      if (!done.emplace(w.fromNode, w.fromField, w.toNode, w.toField, keyOf(r.location)).second)
        continue;  // one ROUTE to an interface member several body members are IS to
      out.emplace_back(r.location, std::move(s));
    }
  }

  void addX3dStatements(std::vector<std::pair<SourceLocation, WStatement>>& out) {
    const X3dInfo& x = scene_.x3d;
    for (const X3dImport& im : x.imports) {
      if (!x3dOut_) {
        warn(im.location,
             "IMPORT " + im.inlineDef + "." + im.exportedName + " has no VRML97 form: not written");
        continue;
      }
      WStatement s;
      s.kind = WStatement::Kind::import;
      s.a = ident(im.inlineDef);
      s.b = ident(im.exportedName);
      s.c = ident(im.localName);
      out.emplace_back(im.location, std::move(s));
    }
    for (const X3dExport& ex : x.exports) {
      if (!x3dOut_) {
        warn(ex.location, "EXPORT " + ex.localDef + " has no VRML97 form: not written");
        continue;
      }
      WStatement s;
      s.kind = WStatement::Kind::exported;
      s.a = ident(ex.localDef);
      s.b = ident(ex.exportedName);
      out.emplace_back(ex.location, std::move(s));
    }
    for (const X3dImportedRoute& r : x.importedRoutes) {
      if (!x3dOut_) {
        warn(r.location, "ROUTE through an IMPORTed node has no VRML97 form: not written");
        continue;
      }
      WStatement s;
      s.kind = WStatement::Kind::route;
      WRoute& w = s.route;
      bool ok = true;
      if (r.fromImport.empty()) {
        ok = routeEnd(r.fromNode, r.fromField, w.fromNode, w.fromField, w.from);
      } else {
        w.fromNode = ident(r.fromImport);
        w.fromField = r.fromField;
      }
      if (r.toImport.empty()) {
        ok = ok && routeEnd(r.toNode, r.toField, w.toNode, w.toField, w.to);
      } else {
        w.toNode = ident(r.toImport);
        w.toField = r.toField;
      }
      if (!ok) {
        warn(r.location, "ROUTE through an IMPORTed node: an end has no DEF name: not written");
        continue;
      }
      out.emplace_back(r.location, std::move(s));
    }
  }

  // ROUTEs to or from nodes that were left out (an X3D node in a .wrl, or one inside it).
  void dropRoutesToUnwritten(std::vector<WStatement>& statements) {
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

  // A ROUTE whose DEF names were given to other nodes before the place it is written at
  // (a name DEFed twice, as castle's tricky_def_use.x3dv does).
  void checkRoute(const WRoute& r, const SourceLocation& at) {
    auto other = [&](const std::string& name, const Node* node) {
      if (node == nullptr) return false;
      auto b = binding_.find(name);
      return b != binding_.end() && b->second != node;
    };
    if (other(r.fromNode, r.from) || other(r.toNode, r.to))
      warn(at, "ROUTE " + r.fromNode + "." + r.fromField + " TO " + r.toNode + "." + r.toField +
                   ": a DEF name it uses names another node where it is written");
  }
};

}  // namespace

WDocument buildDocument(const Scene& scene, const WriteOptions& options, Diagnostics& diagnostics) {
  Builder b(scene, options, diagnostics);
  return b.build();
}

}  // namespace gs::vrml::writing
