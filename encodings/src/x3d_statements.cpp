// The X3D statements of the Classic VRML encoding (ISO/IEC 19776-2:2015 clause 4 and
// annex A): the header statements PROFILE, COMPONENT, UNIT and META, and IMPORT / EXPORT
// (ISO/IEC 19775-1 clause 4.4.6). The XML encoding's <head>, <IMPORT> and <EXPORT> are
// translated into the same statements (x3d_xml.cpp).
#include "parser_impl.hpp"
#include "vrml/node_support.hpp"

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
    case NodeTypeId::Layer:  // X3D 3's name of `pickable` (X3D 4.0 clause 35.3.1)
    case NodeTypeId::LayoutLayer:
      return name == "isPickable" ? type.findExact("pickable") : -1;
    case NodeTypeId::LoadSensor:  // X3D 3's name of `children` (X3D 4.0 clause 9.4.3)
      return name == "watchList" ? type.findExact("children") : -1;
    case NodeTypeId::ParticleSystem:  // X3D 3's names of `color` and `texCoord` (clause 40.4.7)
      if (name == "colorRamp") return type.findExact("color");
      return name == "texCoordRamp" ? type.findExact("texCoord") : -1;
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
    // A component asked for that is not (fully) implemented: one diagnostic naming it;
    // the rest of the world loads (its nodes are read all the same).
    if (!knownComponent(name)) {
      report(Severity::warning, ct.offset, "unknown component '" + name + "'");
    } else if (const auto missing = unimplementedNodes(name, level); !missing.empty()) {
      std::string list;
      for (std::size_t i = 0; i < missing.size() && i < 6; ++i)
        list += (i ? ", " : "") + std::string(missing[i]);
      if (missing.size() > 6) list += " and " + std::to_string(missing.size() - 6) + " more";
      report(Severity::warning, ct.offset,
             "COMPONENT " + name + ":" + std::to_string(level) +
                 " is not fully supported: " + list + " read but not drawn or run");
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
      if (u.category == "length") ctx_.units.length = u.conversionFactor;
      if (u.category == "angle") ctx_.units.angle = u.conversionFactor;
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
    else
      im.inlineNode = inl->node;
    info.imports.push_back(std::move(im));
  } else {
    // EXPORT localDEF [AS exportedDEF]
    X3dExport ex;
    ex.location = lex_.locationAt(t.offset);
    const Token et = lex_.peek();
    ex.localDef = lex_.expectId("a DEF name");
    ex.exportedName = ex.localDef;
    if (lex_.acceptKeyword("AS")) ex.exportedName = lex_.expectId("an exported name after AS");
    const DefEntry* local = findDef(scope, ex.localDef);
    if (local == nullptr) {
      report(Severity::error, et.offset, "EXPORT of unknown DEF name '" + ex.localDef + "'");
    } else {
      ex.node = local->node;
      info.exports.push_back(std::move(ex));
    }
  }
  return true;
}

void Parser::applyAngleUnit(const FieldSpec& spec, FieldValue& v) const {
  const auto f = static_cast<float>(ctx_.units.angle);
  switch (spec.type) {
    case FieldType::SFRotation:
      v.get<FieldType::SFRotation>().w *= f;
      return;
    case FieldType::MFRotation:
      for (Rotation& r : v.get<FieldType::MFRotation>()) r.w *= f;
      return;
    default:
      break;
  }
  // Fields X3D measures in angle base units (ISO/IEC 19775-1 table 4.4 "Standard units").
  static constexpr std::string_view kAngleFields[] = {
      "fieldOfView", "creaseAngle", "skyAngle", "groundAngle", "beamWidth", "cutOffAngle",
      "diskAngle",   "minAngle",    "maxAngle", "startAngle",  "endAngle"};
  bool angle = false;
  for (std::string_view a : kAngleFields) angle = angle || spec.name == a;
  if (!angle) return;
  if (spec.type == FieldType::SFFloat)
    v.get<FieldType::SFFloat>() *= f;
  else if (spec.type == FieldType::MFFloat)
    for (float& x : v.get<FieldType::MFFloat>()) x *= f;
}

NodePtr Parser::applyLengthUnit(const NodePtr& n) const {
  if (ctx_.units.length == 1.0 || !n || !n->is(AbstractType::X3DChildNode)) return n;
  static const std::shared_ptr<const NodeType> kTransform = x3dNodeType("Transform");
  auto t = std::make_shared<Node>(kTransform);
  t->location = n->location;
  const auto f = static_cast<float>(ctx_.units.length);
  t->fieldAt(static_cast<std::size_t>(kTransform->findExact("scale"))) =
      FieldValue::make<FieldType::SFVec3f>(glm::vec3(f));
  t->fieldAt(static_cast<std::size_t>(kTransform->findExact("children"))) =
      FieldValue::make<FieldType::MFNode>(std::vector<NodePtr>{n});
  return t;
}

}  // namespace gs::vrml::parsing
