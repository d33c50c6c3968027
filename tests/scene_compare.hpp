// Structural equality of two parsed scenes, for the tests of the X3D encodings (a world in
// XML or JSON against its Classic VRML twin, a streamed parse against a whole one).
#pragma once

#include "vrml/scene.hpp"

#include <set>
#include <string>
#include <utility>

namespace gs::test {

using vrml::FieldType;
using vrml::FieldValue;
using vrml::Node;
using vrml::NodePtr;
using vrml::Route;
using vrml::Scene;
using vrml::SourceLocation;
using vrml::X3dInfo;

/// Node types, DEF names, field values, routes, PROTO count and X3D header of two scenes;
/// their locations too when `locations`. `diff` names the first difference found.
struct Same {
  bool locations = false;
  /// Compare DEF names (and the DEF names ROUTEs name).
  bool defNames = true;
  /// A VRML97 scene against its X3D conversion: each field of a node in the first scene is
  /// compared with the field of that name in the second (X3D's `children` of Switch and
  /// LOD, `enabled` of Collision are read into VRML97's names); the X3D header and the
  /// hidden nodes are not compared.
  bool fieldsByName = false;
  std::set<std::pair<const Node*, const Node*>> seen;
  std::string diff;

  bool fail(const std::string& what) {
    if (diff.empty()) diff = what;
    return false;
  }
  static std::string where(const SourceLocation& l) {
    return l.file + ":" + std::to_string(l.line) + ":" + std::to_string(l.column);
  }
  bool nodes(const NodePtr& a, const NodePtr& b, const std::string& path) {
    if (!a || !b) return (!a && !b) || fail(path + ": NULL on one side only");
    if (!seen.insert({a.get(), b.get()}).second) return true;
    if (a->typeName() != b->typeName())
      return fail(path + ": type " + a->typeName() + " vs " + b->typeName());
    if (defNames && a->defName != b->defName)
      return fail(path + ": DEF " + a->defName + " vs " + b->defName);
    if (locations && where(a->location) != where(b->location))
      return fail(path + ": location " + where(a->location) + " vs " + where(b->location));
    if (fieldsByName) {
      for (std::size_t i = 0; i < a->fieldCount(); ++i) {
        const auto& spec = a->type().fields[i];
        const int j = b->type().findExact(spec.name);
        if (j < 0) return fail(path + "." + spec.name + ": no such X3D field");
        if (!values(a->fieldAt(i), b->fieldAt(static_cast<std::size_t>(j)), path + "." + spec.name))
          return false;
      }
      return true;
    }
    if (a->fieldCount() != b->fieldCount()) return fail(path + ": field count differs");
    for (std::size_t i = 0; i < a->fieldCount(); ++i)
      if (!values(a->fieldAt(i), b->fieldAt(i), path + "." + a->type().fields[i].name))
        return false;
    return true;
  }
  bool values(const FieldValue& a, const FieldValue& b, const std::string& path) {
    if (a.type() != b.type()) return fail(path + ": field type differs");
    if (a.type() == FieldType::SFNode)
      return nodes(a.get<FieldType::SFNode>(), b.get<FieldType::SFNode>(), path);
    if (a.type() == FieldType::MFNode) {
      const auto& x = a.get<FieldType::MFNode>();
      const auto& y = b.get<FieldType::MFNode>();
      if (x.size() != y.size()) return fail(path + ": MFNode sizes differ");
      for (std::size_t i = 0; i < x.size(); ++i)
        if (!nodes(x[i], y[i], path + "[" + std::to_string(i) + "]")) return false;
      return true;
    }
    return a.storage() == b.storage() || fail(path + ": values differ");
  }
  bool scenes(const Scene& a, const Scene& b) {
    if (a.rootNodes.size() != b.rootNodes.size())
      return fail("root count " + std::to_string(a.rootNodes.size()) + " vs " +
                  std::to_string(b.rootNodes.size()));
    for (std::size_t i = 0; i < a.rootNodes.size(); ++i)
      if (!nodes(a.rootNodes[i], b.rootNodes[i], "root" + std::to_string(i))) return false;
    if (!fieldsByName && a.hiddenNodes.size() != b.hiddenNodes.size())
      return fail("hidden count differs");
    if (a.routes.size() != b.routes.size()) return fail("route count differs");
    for (std::size_t i = 0; i < a.routes.size(); ++i) {
      const Route& x = a.routes[i];
      const Route& y = b.routes[i];
      if (x.fromField != y.fromField || x.toField != y.toField || !x.fromNode || !y.fromNode ||
          (defNames && (x.fromNode->defName != y.fromNode->defName ||
                        x.toNode->defName != y.toNode->defName)) ||
          (locations && where(x.location) != where(y.location)))
        return fail("route " + std::to_string(i) + " differs");
    }
    if (a.protos.size() != b.protos.size()) return fail("PROTO count differs");
    if (fieldsByName) return true;
    const X3dInfo& p = a.x3d;
    const X3dInfo& q = b.x3d;
    if (p.version != q.version || p.profile != q.profile || p.components != q.components ||
        p.meta != q.meta || p.units.size() != q.units.size())
      return fail("X3D header differs");
    return true;
  }
};

}  // namespace gs::test
