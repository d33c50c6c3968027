// The X3D ECMAScript binding's host side (ISO/IEC 19777-1): X3D field values <-> objects
// of the classes of script_prelude_x3d.cpp, and the natives behind X3DScene,
// SFNode.getFieldDefinitions and getNodeName (__gsX3D, taken by that prelude).
#include "encodings/writer.hpp"
#include "script_ecmascript_internal.hpp"
#include "vrml/node_model.hpp"
#include "vrml/proto.hpp"
#include "vrml/scene.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <string_view>
#include <unordered_set>

namespace gs::runtime::es {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

constexpr std::array<const char*, 4> kX3dXyzw = {"x", "y", "z", "w"};
constexpr std::array<const char*, 4> kX3dRgba = {"r", "g", "b", "a"};

double x3dIndex(duk_context* c, duk_idx_t obj, duk_uarridx_t k) {
  duk_get_prop_index(c, obj, k);
  double v = duk_to_number(c, -1);
  duk_pop(c);
  return v;
}

// Reads an N x N matrix object (numbers 0..N*N-1, row by row) into glm's column-major M.
template <class M, int N>
M x3dMatrixAt(duk_context* c, duk_idx_t obj) {
  M m(1);
  using Scalar = typename M::value_type;
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col)
      m[col][row] =
          static_cast<Scalar>(x3dIndex(c, obj, static_cast<duk_uarridx_t>(row * N + col)));
  return m;
}

}  // namespace

// ---- FieldValue -> ECMAScript ----

void EsScript::pushX3DValue(duk_context* c, const FieldValue& v) {
  auto finish = [&](FieldType t) {
    pushProto(c, t);
    duk_set_prototype(c, -2);
  };
  auto vec = [&](FieldType t, const auto& x, int n, bool color) {
    duk_push_bare_object(c);
    for (int i = 0; i < n; ++i) {
      duk_push_number(c, static_cast<double>(x[i]));
      duk_put_prop_string(c, -2, (color ? kX3dRgba : kX3dXyzw)[static_cast<std::size_t>(i)]);
    }
    finish(t);
  };
  auto matrix = [&](FieldType t, const auto& m, int n) {
    duk_push_bare_object(c);
    for (int row = 0; row < n; ++row)
      for (int col = 0; col < n; ++col) {
        duk_push_number(c, static_cast<double>(m[col][row]));
        duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(row * n + col));
      }
    finish(t);
  };
  auto array = [&](FieldType t, const auto& a, auto&& each) {
    duk_push_bare_array(c);
    for (std::size_t i = 0; i < a.size(); ++i) {
      each(a[i]);
      duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
    }
    finish(t);
  };
  switch (v.type()) {
    case FieldType::SFDouble:
      duk_push_number(c, v.get<FieldType::SFDouble>());
      break;
    case FieldType::SFVec2d:
      vec(FieldType::SFVec2d, v.get<FieldType::SFVec2d>(), 2, false);
      break;
    case FieldType::SFVec3d:
      vec(FieldType::SFVec3d, v.get<FieldType::SFVec3d>(), 3, false);
      break;
    case FieldType::SFVec4f:
      vec(FieldType::SFVec4f, v.get<FieldType::SFVec4f>(), 4, false);
      break;
    case FieldType::SFVec4d:
      vec(FieldType::SFVec4d, v.get<FieldType::SFVec4d>(), 4, false);
      break;
    case FieldType::SFColorRGBA:
      vec(FieldType::SFColorRGBA, v.get<FieldType::SFColorRGBA>(), 4, true);
      break;
    case FieldType::SFMatrix3f:
      matrix(FieldType::SFMatrix3f, v.get<FieldType::SFMatrix3f>(), 3);
      break;
    case FieldType::SFMatrix3d:
      matrix(FieldType::SFMatrix3d, v.get<FieldType::SFMatrix3d>(), 3);
      break;
    case FieldType::SFMatrix4f:
      matrix(FieldType::SFMatrix4f, v.get<FieldType::SFMatrix4f>(), 4);
      break;
    case FieldType::SFMatrix4d:
      matrix(FieldType::SFMatrix4d, v.get<FieldType::SFMatrix4d>(), 4);
      break;
    case FieldType::MFBool: {
      const std::vector<bool>& a = v.get<FieldType::MFBool>();
      duk_push_bare_array(c);
      for (std::size_t i = 0; i < a.size(); ++i) {
        duk_push_boolean(c, a[i]);
        duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
      }
      finish(FieldType::MFBool);
      break;
    }
    case FieldType::MFDouble:
      array(FieldType::MFDouble, v.get<FieldType::MFDouble>(),
            [&](double d) { duk_push_number(c, d); });
      break;
    case FieldType::MFImage:
      array(FieldType::MFImage, v.get<FieldType::MFImage>(), [&](const vrml::SFImage& img) {
        pushValue(c, FieldValue::make<FieldType::SFImage>(img));
      });
      break;
    case FieldType::MFVec2d:
      array(FieldType::MFVec2d, v.get<FieldType::MFVec2d>(),
            [&](const glm::dvec2& x) { vec(FieldType::SFVec2d, x, 2, false); });
      break;
    case FieldType::MFVec3d:
      array(FieldType::MFVec3d, v.get<FieldType::MFVec3d>(),
            [&](const glm::dvec3& x) { vec(FieldType::SFVec3d, x, 3, false); });
      break;
    case FieldType::MFVec4f:
      array(FieldType::MFVec4f, v.get<FieldType::MFVec4f>(),
            [&](const glm::vec4& x) { vec(FieldType::SFVec4f, x, 4, false); });
      break;
    case FieldType::MFVec4d:
      array(FieldType::MFVec4d, v.get<FieldType::MFVec4d>(),
            [&](const glm::dvec4& x) { vec(FieldType::SFVec4d, x, 4, false); });
      break;
    case FieldType::MFColorRGBA:
      array(FieldType::MFColorRGBA, v.get<FieldType::MFColorRGBA>(),
            [&](const glm::vec4& x) { vec(FieldType::SFColorRGBA, x, 4, true); });
      break;
    case FieldType::MFMatrix3f:
      array(FieldType::MFMatrix3f, v.get<FieldType::MFMatrix3f>(),
            [&](const glm::mat3& m) { matrix(FieldType::SFMatrix3f, m, 3); });
      break;
    case FieldType::MFMatrix3d:
      array(FieldType::MFMatrix3d, v.get<FieldType::MFMatrix3d>(),
            [&](const glm::dmat3& m) { matrix(FieldType::SFMatrix3d, m, 3); });
      break;
    case FieldType::MFMatrix4f:
      array(FieldType::MFMatrix4f, v.get<FieldType::MFMatrix4f>(),
            [&](const glm::mat4& m) { matrix(FieldType::SFMatrix4f, m, 4); });
      break;
    case FieldType::MFMatrix4d:
      array(FieldType::MFMatrix4d, v.get<FieldType::MFMatrix4d>(),
            [&](const glm::dmat4& m) { matrix(FieldType::SFMatrix4d, m, 4); });
      break;
    default:  // not an X3D type
      duk_push_undefined(c);
      break;
  }
}

// ---- ECMAScript -> FieldValue ----

bool EsScript::toX3DSingle(duk_context* c, duk_idx_t idx, FieldType t, FieldValue& out,
                           std::string& why) {
  idx = duk_normalize_index(c, idx);
  if (t == FieldType::SFDouble) {
    duk_dup(c, idx);
    out = FieldValue::make<FieldType::SFDouble>(duk_to_number(c, -1));
    duk_pop(c);
    return true;
  }
  if (!duk_is_object(c, idx) || duk_is_function(c, idx)) {
    why = "expected " + std::string(vrml::fieldTypeName(t)) + ", got " +
          (duk_is_null_or_undefined(c, idx) ? "null or undefined" : "a value that is no object");
    return false;
  }
  std::array<double, 4> d{};
  auto comps = [&](int n, bool color) {
    for (int i = 0; i < n; ++i)
      d[static_cast<std::size_t>(i)] =
          vectorComponent(c, idx, (color ? kX3dRgba : kX3dXyzw)[static_cast<std::size_t>(i)],
                          static_cast<duk_uarridx_t>(i));
  };
  auto f = [&](std::size_t i) { return static_cast<float>(d[i]); };
  switch (t) {
    case FieldType::SFVec2d:
      comps(2, false);
      out = FieldValue::make<FieldType::SFVec2d>(glm::dvec2(d[0], d[1]));
      return true;
    case FieldType::SFVec3d:
      comps(3, false);
      out = FieldValue::make<FieldType::SFVec3d>(glm::dvec3(d[0], d[1], d[2]));
      return true;
    case FieldType::SFVec4f:
      comps(4, false);
      out = FieldValue::make<FieldType::SFVec4f>(glm::vec4(f(0), f(1), f(2), f(3)));
      return true;
    case FieldType::SFVec4d:
      comps(4, false);
      out = FieldValue::make<FieldType::SFVec4d>(glm::dvec4(d[0], d[1], d[2], d[3]));
      return true;
    case FieldType::SFColorRGBA:
      comps(4, true);
      out = FieldValue::make<FieldType::SFColorRGBA>(glm::vec4(f(0), f(1), f(2), f(3)));
      return true;
    case FieldType::SFMatrix3f:
      out = FieldValue::make<FieldType::SFMatrix3f>(x3dMatrixAt<glm::mat3, 3>(c, idx));
      return true;
    case FieldType::SFMatrix3d:
      out = FieldValue::make<FieldType::SFMatrix3d>(x3dMatrixAt<glm::dmat3, 3>(c, idx));
      return true;
    case FieldType::SFMatrix4f:
      out = FieldValue::make<FieldType::SFMatrix4f>(x3dMatrixAt<glm::mat4, 4>(c, idx));
      return true;
    case FieldType::SFMatrix4d:
      out = FieldValue::make<FieldType::SFMatrix4d>(x3dMatrixAt<glm::dmat4, 4>(c, idx));
      return true;
    default:
      why = "unsupported type";
      return false;
  }
}

// ---- Natives behind X3DScene and the SFNode additions ----

namespace {

// X3D's access type numbers (X3DConstants): initializeOnly 0, inputOnly 1, outputOnly 2,
// inputOutput 3.
int x3dAccessNumber(vrml::AccessType a) {
  switch (a) {
    case vrml::AccessType::field:
      return 0;
    case vrml::AccessType::eventIn:
      return 1;
    case vrml::AccessType::eventOut:
      return 2;
    case vrml::AccessType::exposedField:
      return 3;
  }
  return 0;
}

// What x3dFindNamed carries down: the nodes seen, and the Script whose deadline a large
// world's walk checks.
struct X3dNamedWalk {
  EsScript& self;
  duk_context* c;
  std::unordered_set<const vrml::Node*> seen;
};

// The first node DEFed `name` in file order under `nodes` (not looking inside PROTO
// instances, whose DEF names are the PROTO body's own).
vrml::NodePtr x3dFindNamed(const std::vector<vrml::NodePtr>& nodes, const std::string& name,
                           X3dNamedWalk& walk, int depth) {
  if (depth > 1024) return nullptr;
  for (const vrml::NodePtr& n : nodes) {
    if (!n || !walk.seen.insert(n.get()).second) continue;
    if ((walk.seen.size() & 4095u) == 0) walk.self.checkDeadline(walk.c);
    if (n->defName == name) return n;
    if (vrml::declaredInterface(*n) != nullptr) continue;
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const FieldValue& v = n->fieldAt(i);
      vrml::NodePtr found;
      if (v.type() == FieldType::SFNode)
        found = x3dFindNamed({v.get<FieldType::SFNode>()}, name, walk, depth + 1);
      else if (v.type() == FieldType::MFNode)
        found = x3dFindNamed(v.get<FieldType::MFNode>(), name, walk, depth + 1);
      if (found) return found;
    }
  }
  return nullptr;
}

}  // namespace

std::string x3dString(duk_context* c, duk_idx_t idx) {
  duk_size_t len = 0;
  const char* s = duk_to_lstring(c, idx, &len);
  return std::string(s, len);
}

const vrml::Scene* x3dSceneOf(EsScript& self, duk_context* c, duk_idx_t idx) {
  if (const vrml::Scene* made = self.createdSceneAt(c, idx)) return made;
  return self.context().sceneOf(self.node());
}

bool x3dInlineScene(EsScript& self, duk_context* c, duk_idx_t idx) {
  return self.createdSceneAt(c, idx) == nullptr &&
         self.context().sceneOf(self.node()) != self.context().currentScene();
}

vrml::Scene* x3dEditableSceneOf(EsScript& self, duk_context* c, duk_idx_t idx) {
  if (vrml::Scene* made = self.createdSceneAt(c, idx)) return made;
  // The world's Scene and an Inline's world are no const objects (the session and the
  // Inline loader make them): a Script edits its META statements, EXPORTs, names and ROUTEs.
  return const_cast<vrml::Scene*>(self.context().sceneOf(self.node()));
}

namespace {

// sceneInfo(scene): [specificationVersion, encoding, worldURL]. A created
// scene's worldURL is the world's, against which its URLs were resolved; an Inline's
// world's is its own.
duk_ret_t x3dSceneInfo(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  std::string version =
      scene != nullptr && !scene->x3d.version.empty() ? scene->x3d.version : "2.0";
  std::string encoding = scene != nullptr && !scene->x3d.encoding.empty() ? scene->x3d.encoding
                         : scene != nullptr                               ? "VRML"
                                                                          : "";
  std::string url =
      x3dInlineScene(self, c, 0) && scene != nullptr ? scene->url : self.context().worldUrl();
  duk_push_array(c);
  const std::string* parts[] = {&version, &encoding, &url};
  for (duk_uarridx_t i = 0; i < 3; ++i) {
    duk_push_lstring(c, parts[i]->data(), parts[i]->size());
    duk_put_prop_index(c, -2, i);
  }
  return 1;
}

duk_ret_t x3dRootNodes(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  self.pushValue(c, FieldValue::make<FieldType::MFNode>(
                        scene != nullptr ? scene->rootNodes : std::vector<vrml::NodePtr>()));
  return 1;
}

duk_ret_t x3dNamedNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  std::string name = x3dString(c, 1);
  vrml::NodePtr n;
  if (scene != nullptr)
    for (const auto& [given, node] : scene->x3d.namedNodes)
      if (given == name) n = node;
  X3dNamedWalk walk{self, c, {}};
  if (!n && scene != nullptr) n = x3dFindNamed(scene->rootNodes, name, walk, 0);
  self.pushNode(c, n);
  return 1;
}

duk_ret_t x3dCreateNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  std::string type = x3dString(c, 0);
  bool ok = !type.empty() && type.size() <= 256 &&
            !std::isdigit(static_cast<unsigned char>(type.front()));
  for (char ch : type) ok = ok && (std::isalnum(static_cast<unsigned char>(ch)) || ch == '_');
  if (!ok)
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "createNode: '%s' is not a node type name",
                 type.substr(0, 64).c_str());
  std::vector<vrml::NodePtr> made =
      self.createFromText(c, "#X3D V4.0 utf8\nPROFILE Full\n" + type + " { }\n")->rootNodes;
  if (made.empty() || !made.front())
    GS_DUK_ERROR(c, DUK_ERR_ERROR, "createNode: there is no node type '%s'", type.c_str());
  self.pushNode(c, made.front());
  return 1;
}

// The PROTO or EXTERNPROTO `scene` declares by `name` (X3DExecutionContext's
// protos and externprotos: the file's top-level declarations); null when none.
const vrml::NodeType* x3dDeclaredProto(const vrml::Scene* scene, std::string_view name) {
  if (scene == nullptr) return nullptr;
  for (const auto& t : scene->protos)
    if (t && t->proto && t->name == name) return t.get();
  return nullptr;
}

// protoDeclarations(scene): [[name, isExternProto, [url ...], [[field, access, type] ...]]
// ...] of the scene's top-level PROTO and EXTERNPROTO declarations, in file order.
duk_ret_t x3dProtoDeclarations(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  duk_push_array(c);
  if (scene == nullptr) return 1;
  duk_uarridx_t k = 0;
  for (const auto& t : scene->protos) {
    if (!t || !t->proto) continue;
    duk_push_array(c);
    duk_push_lstring(c, t->name.data(), t->name.size());
    duk_put_prop_index(c, -2, 0);
    duk_push_boolean(c, t->proto->external);
    duk_put_prop_index(c, -2, 1);
    duk_push_array(c);
    for (duk_uarridx_t u = 0; u < t->proto->urls.size(); ++u) {
      duk_push_lstring(c, t->proto->urls[u].data(), t->proto->urls[u].size());
      duk_put_prop_index(c, -2, u);
    }
    duk_put_prop_index(c, -2, 2);
    duk_push_array(c);
    for (std::size_t i = 0; i < t->fields.size(); ++i) {
      const vrml::FieldSpec& spec = t->fields[i];
      duk_push_array(c);
      duk_push_lstring(c, spec.name.data(), spec.name.size());
      duk_put_prop_index(c, -2, 0);
      duk_push_int(c, x3dAccessNumber(spec.access));
      duk_put_prop_index(c, -2, 1);
      std::string_view type = vrml::fieldTypeName(spec.type);
      duk_push_lstring(c, type.data(), type.size());
      duk_put_prop_index(c, -2, 2);
      duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
    }
    duk_put_prop_index(c, -2, 3);
    duk_put_prop_index(c, -2, k++);
  }
  return 1;
}

// createProto(scene, name): an instance of the scene's PROTO or EXTERNPROTO `name`, its
// interface at the declared defaults (19777-1 X3DExecutionContext.createProto): the
// scene's declarations written out again, with one instance, and read as createNode reads
// its node.
duk_ret_t x3dCreateProto(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const std::string name = x3dString(c, 1);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  if (x3dDeclaredProto(scene, name) == nullptr)
    GS_DUK_ERROR(c, DUK_ERR_ERROR, "createProto: the scene declares no PROTO or EXTERNPROTO '%s'",
                 name.substr(0, 64).c_str());
  vrml::Scene declarations;
  declarations.url = scene->url;
  declarations.x3d.version = scene->x3d.version.empty() ? "4.0" : scene->x3d.version;
  declarations.protos = scene->protos;
  vrml::WriteOptions options;
  options.encoding = vrml::Encoding::classic;
  std::string text = vrml::writeScene(declarations, options).text;
  text += "\n" + name + " { }\n";
  std::vector<vrml::NodePtr> made = self.createFromText(c, text)->rootNodes;
  if (made.empty() || !made.back())
    GS_DUK_ERROR(c, DUK_ERR_ERROR, "createProto: '%s' could not be instantiated",
                 name.substr(0, 64).c_str());
  self.pushNode(c, made.back());
  return 1;
}

// route(scene, add, fromNode, fromField, toNode, toField): X3DExecutionContext.addRoute /
// deleteRoute. A route added is also kept in the scene's list of them (X3dInfo::scriptRoutes,
// which X3DScene.routes lists while the route is in place).
duk_ret_t x3dRoute(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const bool add = duk_to_boolean(c, 1) != 0;
  const char* what = add ? "addRoute" : "deleteRoute";
  FieldValue from = self.requireValue(c, 2, FieldType::SFNode, what);
  FieldValue to = self.requireValue(c, 4, FieldType::SFNode, what);
  const vrml::NodePtr& a = from.get<FieldType::SFNode>();
  const vrml::NodePtr& b = to.get<FieldType::SFNode>();
  if (!a || !b) GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s: a node is NULL", what);
  std::string af = x3dString(c, 3), bf = x3dString(c, 5);
  bool ok = self.route(c, add, a, af, b, bf);
  vrml::Scene* scene = ok && add ? x3dEditableSceneOf(self, c, 0) : nullptr;
  if (scene != nullptr) {
    const auto same = [&](const vrml::Route& r) {
      return r.fromNode == a && r.fromField == af && r.toNode == b && r.toField == bf;
    };
    // The list is bounded apart from the Script's heap (the route itself is made anyway).
    auto& made = scene->x3d.scriptRoutes;
    if (made.size() < (std::size_t{1} << 16) && std::none_of(made.begin(), made.end(), same))
      made.push_back({a, af, b, bf, {}});
  }
  duk_push_boolean(c, ok);
  return 1;
}

// fieldDefinitions(node): [[name, accessType, typeName], ...] of the node's interface (a
// PROTO instance's declared one).
duk_ret_t x3dFieldDefinitions(duk_context* c) {
  EsScript& self = EsScript::of(c);
  vrml::NodePtr n = self.nodeAt(c, 0);
  duk_push_array(c);
  if (!n) return 1;
  const vrml::ProtoInstance* p = vrml::declaredInterface(*n);
  const vrml::NodeType& type = p != nullptr ? *p->type : n->type();
  for (std::size_t i = 0; i < type.fields.size(); ++i) {
    const vrml::FieldSpec& spec = type.fields[i];
    duk_push_array(c);
    duk_push_lstring(c, spec.name.data(), spec.name.size());
    duk_put_prop_index(c, -2, 0);
    duk_push_int(c, x3dAccessNumber(spec.access));
    duk_put_prop_index(c, -2, 1);
    std::string_view t = vrml::fieldTypeName(spec.type);
    duk_push_lstring(c, t.data(), t.size());
    duk_put_prop_index(c, -2, 2);
    duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
  }
  return 1;
}

// The node type constants of X3DConstants (19777-1 clause 7.9.1): each concrete node type
// of the node model by its name, numbered by its NodeTypeId, and each abstract type (X3D's
// X3D...Node names) numbered from kAbstractTypeBase. As one flat array: [name, number, ...].
constexpr int kAbstractTypeBase = 1000;
constexpr std::string_view kAbstractTypeNames[] = {
#define GS_ABSTRACT_TYPE(name) #name,
#include "vrml/node_model_types.inc"
#undef GS_ABSTRACT_TYPE
};

duk_ret_t x3dNodeTypeConstants(duk_context* c) {
  duk_push_array(c);
  duk_uarridx_t i = 0;
  const auto add = [&](std::string_view name, int number) {
    duk_push_lstring(c, name.data(), name.size());
    duk_put_prop_index(c, -2, i++);
    duk_push_int(c, number);
    duk_put_prop_index(c, -2, i++);
  };
  for (const vrml::NodeModel& m : vrml::nodeModels()) add(m.name, static_cast<int>(m.id));
  for (std::size_t t = 0; t < std::size(kAbstractTypeNames); ++t)
    add(kAbstractTypeNames[t], kAbstractTypeBase + static_cast<int>(t));
  return 1;
}

// nodeType(node): SFNode.getNodeType's numbers: the concrete type, then every abstract
// type it inherits; a PROTO instance is X3DPrototypeInstance and its first node's types.
duk_ret_t x3dNodeType(duk_context* c) {
  EsScript& self = EsScript::of(c);
  vrml::NodePtr n = self.nodeAt(c, 0);
  duk_push_array(c);
  if (!n) return 1;
  duk_uarridx_t i = 0;
  const auto add = [&](int number) {
    duk_push_int(c, number);
    duk_put_prop_index(c, -2, i++);
  };
  if (!n->protoName().empty())
    add(kAbstractTypeBase + static_cast<int>(vrml::AbstractType::X3DPrototypeInstance));
  if (n->typeId() != vrml::NodeTypeId::unknown) add(static_cast<int>(n->typeId()));
  for (std::size_t t = 0; t < std::size(kAbstractTypeNames); ++t)
    if (n->is(static_cast<vrml::AbstractType>(t))) add(kAbstractTypeBase + static_cast<int>(t));
  return 1;
}

// importedNode(scene, name): the node of the world's IMPORT `name`, or null; null for a
// scene createX3DFromString made and for an Inline's world (their IMPORTs are not
// resolved).
duk_ret_t x3dImportedNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  if (self.createdSceneAt(c, 0) != nullptr || x3dInlineScene(self, c, 0)) {
    duk_push_null(c);
    return 1;
  }
  self.pushNode(c, self.context().importedNode(x3dString(c, 1)));  // null when none
  return 1;
}

// exportedNode(scene, name): the node the scene's EXPORT ... AS `name` names (X3D 4.0
// clause 4.4.6; X3DScene.getExportedNode), or null.
duk_ret_t x3dExportedNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const vrml::Scene* scene = x3dSceneOf(self, c, 0);
  const std::string name = x3dString(c, 1);
  vrml::NodePtr found;
  if (scene != nullptr)
    for (const vrml::X3dExport& e : scene->x3d.exports)
      if (e.exportedName == name && e.node) {
        found = e.node;
        break;
      }
  self.pushNode(c, found);
  return 1;
}

// rootNode(scene, add, node): X3DScene.addRootNode / removeRootNode; whether the roots
// changed. The world's roots and an Inline's world's change through the browser (the new
// nodes are drawn and run); a created scene's list is its own (its nodes already run, as
// createVrmlFromString's do).
duk_ret_t x3dRootNode(duk_context* c) {
  EsScript& self = EsScript::of(c);
  const bool add = duk_to_boolean(c, 1) != 0;
  FieldValue v = self.requireValue(c, 2, FieldType::SFNode, add ? "addRootNode" : "removeRootNode");
  const vrml::NodePtr& n = v.get<FieldType::SFNode>();
  if (!n)
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s: the node is NULL",
                 add ? "addRootNode" : "removeRootNode");
  if (vrml::Scene* made = self.createdSceneAt(c, 0)) {
    std::vector<vrml::NodePtr>& roots = made->rootNodes;
    const auto it = std::find(roots.begin(), roots.end(), n);
    const bool changed = add ? it == roots.end() : it != roots.end();
    if (changed && add) roots.push_back(n);
    if (changed && !add) roots.erase(it);
    duk_push_boolean(c, changed);
    return 1;
  }
  if (x3dInlineScene(self, c, 0)) {
    const vrml::Scene* inlineWorld = self.context().sceneOf(self.node());
    duk_push_boolean(
        c, inlineWorld != nullptr && self.context().changeInlineRoots(*inlineWorld, n, add));
    return 1;
  }
  duk_push_boolean(c, add ? self.context().addRootNode(n) : self.context().removeRootNode(n));
  return 1;
}

duk_ret_t x3dTypeName(duk_context* c) {
  EsScript& self = EsScript::of(c);
  vrml::NodePtr n = self.nodeAt(c, 0);
  std::string s = !n ? std::string() : !n->protoName().empty() ? n->protoName() : n->typeName();
  duk_push_lstring(c, s.data(), s.size());
  return 1;
}

}  // namespace

void EsScript::pushCreatedScene(duk_context* c, std::shared_ptr<vrml::Scene> scene) {
  duk_push_global_stash(c);
  const bool x3d = duk_get_prop_string(c, -1, kSceneMakerKey) != 0;
  duk_remove(c, -2);
  if (!x3d) {  // a VRML97 Script: no X3DScene class
    duk_pop(c);
    duk_push_object(c);
    pushValue(c, FieldValue::make<FieldType::MFNode>(scene->rootNodes));
    duk_put_prop_string(c, -2, "rootNodes");
    return;
  }
  duk_call(c, 0);  // a new X3DScene object
  scenes_.push_back(std::move(scene));
  duk_push_uint(c, static_cast<duk_uint_t>(scenes_.size()));
  duk_put_prop_string(c, -2, kSceneIdKey);
}

vrml::Scene* EsScript::createdSceneAt(duk_context* c, duk_idx_t idx) {
  if (!duk_is_object(c, idx)) return nullptr;
  duk_get_prop_string(c, idx, kSceneIdKey);
  const bool has = duk_is_number(c, -1) != 0;
  const duk_uint_t id = has ? duk_get_uint(c, -1) : 0;
  duk_pop(c);
  return has && id >= 1 && id <= scenes_.size() ? scenes_[id - 1].get() : nullptr;
}

bool EsScript::wantsX3D() const {
  const vrml::NodeType& type = node_.type();
  if (type.findExact("metadata") >= 0) return true;
  for (const vrml::FieldSpec& f : type.fields)
    if (static_cast<int>(f.type) >= vrml::kVrml97FieldTypeCount) return true;
  const vrml::Scene* scene = ctx_.sceneOf(node_);
  return scene != nullptr && !scene->x3d.version.empty();
}

void EsScript::installX3DHooks(duk_context* c) {
  static constexpr NativeFunction kHooks[] = {
      {"sceneInfo", x3dSceneInfo, 1},
      {"rootNodes", x3dRootNodes, 1},
      {"namedNode", x3dNamedNode, 2},
      {"createNode", x3dCreateNode, 1},
      {"fieldDefinitions", x3dFieldDefinitions, 1},
      {"typeName", x3dTypeName, 1},
      {"nodeTypeConstants", x3dNodeTypeConstants, 0},
      {"nodeType", x3dNodeType, 1},
      {"importedNode", x3dImportedNode, 2},
      {"exportedNode", x3dExportedNode, 2},
      {"protoDeclarations", x3dProtoDeclarations, 1},
      {"rootNode", x3dRootNode, 3},
      {"createProto", x3dCreateProto, 2},
      {"route", x3dRoute, 6},
  };
  duk_push_global_object(c);
  duk_push_bare_object(c);
  putNativeFunctions(c, kHooks);
  installX3DSceneEdits(c);
  installX3DInfo(c);
  installX3DText(c);
  duk_put_prop_string(c, -2, "__gsX3D");
  duk_pop(c);
}

}  // namespace gs::runtime::es
