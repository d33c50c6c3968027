// The X3D statements of the Classic VRML encoding (ISO/IEC 19776-2:2015 clause 4 and
// annex A): the header statements PROFILE, COMPONENT, UNIT and META, and IMPORT / EXPORT
// (ISO/IEC 19775-1 clause 4.4.6). The XML encoding's <head>, <IMPORT> and <EXPORT> are
// translated into the same statements (x3d_xml.cpp).
#include "parser_impl.hpp"

#include <cstdlib>

namespace gs::vrml::parsing {

namespace {

// X3D's profiles (ISO/IEC 19775-1 annexes A to F, H, L).
bool knownProfile(std::string_view p) {
  static constexpr std::string_view kProfiles[] = {
      "Core",      "Interchange", "Interactive",    "MPEG-4",
      "Immersive", "Full",        "CADInterchange", "MedicalInterchange"};
  for (std::string_view k : kProfiles)
    if (p == k) return true;
  return false;
}

}  // namespace

int Parser::x3dFieldAlias(const NodeType& type, std::string_view name) {
  switch (type.id()) {
    case NodeTypeId::Switch:
      return name == "children" ? type.findExact("choice") : -1;
    case NodeTypeId::LOD:
      return name == "children" ? type.findExact("level") : -1;
    case NodeTypeId::Collision:
      return name == "enabled" ? type.findExact("collide") : -1;
    case NodeTypeId::ComposedCubeMapTexture:
      // X3D 3's names of the six faces (X3D 4 added the "Texture" suffix).
      if (name == "back" || name == "bottom" || name == "front" || name == "left" ||
          name == "right" || name == "top")
        return type.findExact(std::string(name) + "Texture");
      return -1;
    default:
      return -1;
  }
}

bool Parser::parseX3dStatement(Scope& scope, const Token& t) {
  const std::string_view kw = t.text;
  if (kw != "PROFILE" && kw != "COMPONENT" && kw != "UNIT" && kw != "META" && kw != "IMPORT" &&
      kw != "EXPORT")
    return false;
  lex_.consume(t);
  X3dInfo scratch;
  X3dInfo& info = scope.x3d != nullptr ? *scope.x3d : scratch;
  if (scope.x3d == nullptr)
    report(Severity::warning, t.offset,
           std::string(kw) + " is only allowed at the top of an X3D file: ignored");
  if (kw == "PROFILE") {
    const Token pt = lex_.peek();
    const std::string_view profile = lex_.expectId("a profile name");
    if (!knownProfile(profile))
      report(Severity::warning, pt.offset,
             "unknown profile '" + std::string(profile) + "': read as Full");
    info.profile = profile;
  } else if (kw == "COMPONENT") {
    const Token ct = lex_.peek();
    std::string_view word = lex_.expectId("a component name:level");
    std::string name(word);
    int level = 1;
    const std::size_t colon = name.find(':');
    if (colon != std::string::npos) {
      level = std::atoi(name.c_str() + colon + 1);
      name.resize(colon);
    } else if (lex_.accept(':')) {
      level = lex_.readInt32();
    }
    if (level < 1) {
      report(Severity::warning, ct.offset, "COMPONENT " + name + ": level must be at least 1");
      level = 1;
    }
    info.components.emplace_back(std::move(name), level);
  } else if (kw == "UNIT") {
    const Token ct = lex_.peek();
    X3dUnit u;
    u.category = lex_.expectId("a unit category (length, angle, mass, force)");
    u.name = lex_.expectId("a unit name");
    u.conversionFactor = lex_.readDouble();
    if (u.category != "length" && u.category != "angle" && u.category != "mass" &&
        u.category != "force") {
      report(Severity::error, ct.offset,
             "UNIT category '" + u.category +
                 "' is none of length, angle, mass and force (X3D clause 4.3.6): ignored");
    } else if (!(u.conversionFactor > 0.0)) {
      report(Severity::error, ct.offset,
             "UNIT " + u.category + " " + u.name + ": the conversion factor must be positive");
    } else {
      info.units.push_back(std::move(u));
    }
  } else if (kw == "META") {
    std::string name, content;
    lex_.readString(name);
    lex_.readString(content);
    info.meta.emplace_back(std::move(name), std::move(content));
  } else if (kw == "IMPORT") {
    // IMPORT inlineDEF.exportedDEF [AS localDEF]
    X3dImport im;
    im.location = lex_.locationAt(t.offset);
    const Token it = lex_.peek();
    im.inlineDef = lex_.expectId("an Inline's DEF name");
    lex_.expect('.');
    im.exportedName = lex_.expectId("an exported name");
    im.localName = im.exportedName;
    if (lex_.acceptKeyword("AS")) im.localName = lex_.expectId("a local name after AS");
    const DefEntry* inl = findDef(scope, im.inlineDef);
    if (inl == nullptr || inl->node->typeId() != NodeTypeId::Inline)
      report(Severity::error, it.offset,
             "IMPORT from '" + im.inlineDef + "', which is no Inline's DEF name");
    info.imports.push_back(std::move(im));
  } else {
    // EXPORT localDEF [AS exportedDEF]
    X3dExport ex;
    ex.location = lex_.locationAt(t.offset);
    const Token et = lex_.peek();
    ex.localDef = lex_.expectId("a DEF name");
    ex.exportedName = ex.localDef;
    if (lex_.acceptKeyword("AS")) ex.exportedName = lex_.expectId("an exported name after AS");
    if (findDef(scope, ex.localDef) == nullptr)
      report(Severity::error, et.offset, "EXPORT of unknown DEF name '" + ex.localDef + "'");
    else
      info.exports.push_back(std::move(ex));
  }
  return true;
}

}  // namespace gs::vrml::parsing
