// The builder of the document the writers print (writer_model.cpp: buildDocument): what
// it knows of the Scene being written (references, IS links, the PROTO bodies instances
// copied, DEF names). Nodes and fields are writer_model.cpp's; PROTO declarations, ROUTEs
// and the X3D statements writer_statements.cpp's. Internal to gs_encodings.
#pragma once

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

namespace gs::vrml::writing::model {

using LocKey = std::tuple<std::string, int, int>;

inline LocKey keyOf(const SourceLocation& l) {
  return {l.file, l.line, l.column};
}

inline bool sameValue(const FieldValue& a, const FieldValue& b) {
  return a.storage() == b.storage();
}

inline bool carriesValue(AccessType a) {
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

  WDocument build();

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

  void warn(SourceLocation at, std::string message);
  void drop(const SourceLocation& at, const std::string& message);
  void flushDiagnostics();

  // ---- survey: references, IS links, the PROTO bodies instances copied --------------------

  void surveyType(const NodeType* t);

  void surveyValue(const FieldValue& v);

  void survey(const NodePtr& n);

  // ---- names ----

  std::unordered_map<std::string, std::string> idents_;

  // `raw` as classicIdent() writes it; a warning the first time a name changes (glTF's
  // "Cube.001").
  const std::string& ident(const std::string& raw);

  // The DEF name `n` is written with: its own (as ident() spells it), or, for a node a ROUTE
  // names that has none (the glTF importer's interpolators and Transforms), one made up
  // when `make`: "_" + its type + a number, unused by the world.
  std::unordered_map<const Node*, std::string> madeNames_;
  std::unordered_set<std::string> usedNames_;
  std::string defOf(const Node& n, bool make = false);
  std::size_t extraNumber_ = 0;

  // ---- nodes ------------------------------------------------------------------------------

  // The name the target gives field `name` of a node of `type`: X3D renamed three of
  // VRML97's fields, and X3D 4 renamed ComposedCubeMapTexture's faces.
  std::string fieldName(const Node& n, const std::string& name) const;

  // The XML encoding's containerField default of `n`'s type (X3D 3 put metadata nodes in
  // `metadata` by default, as the reader does for a 3.x file).
  std::string containerDefault(const Node& n) const;

  // The built-in type `n` started as, before a Script or shader declared its own fields.
  std::shared_ptr<const NodeType> baseType(const Node& n) const;

  // The IS connections of the PROTO body being written that name member `field` of `n`.
  std::vector<const IsConnection*> connections(const Node* n, int field) const;

  const std::string& bodyMember(int protoField) const;

  // Node values of an SFNode / MFNode field.
  std::vector<WNode> nodesOf(const FieldValue& v);

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

  WNode nodeOf(const NodePtr& np);

  void instanceOf(const Node& n, const NodeType& type, WNode& w);

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

  void plainNode(const Node& n, WNode& w);

  // ---- PROTO declarations -----------------------------------------------------------------

  std::shared_ptr<WProto> protoOf(const NodeType& t);

  // PROTO types whose instances the body being written holds and that are declared
  // neither at the top of the file nor around the body.
  std::vector<const NodeType*> nestedTypes() const;

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
  void dropRoutesToUnwritten(std::vector<WStatement>& statements);

  // A ROUTE whose DEF names were given to other nodes before the place it is written at
  // (a name DEFed twice, as castle's tricky_def_use.x3dv does).
  void checkRoute(const WRoute& r, const SourceLocation& at);
};

}  // namespace gs::vrml::writing::model
