// VRML field values <-> ECMAScript values (annex C.6): numbers, strings and booleans for
// the scalar types, objects of the prelude's SF/MF classes for the others, and SFNode
// objects whose properties are the node's fields.
#include "script_ecmascript_internal.hpp"
#include "vrml/proto.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>
#include <type_traits>

namespace gs::runtime::es {

using vrml::FieldType;
using vrml::FieldValue;

namespace {

duk_idx_t dupTop(duk_context* c, duk_idx_t idx) {
  duk_dup(c, idx);
  return -1;
}

constexpr std::array<const char*, vrml::kFieldTypeCount> kClassNames = {
    nullptr, "SFColor", nullptr, "SFImage", nullptr, "SFNode", "SFRotation", nullptr, nullptr,
    "SFVec2f", "SFVec3f", "MFColor", "MFFloat", "MFInt32", "MFNode", "MFRotation", "MFString",
    "MFTime", "MFVec2f", "MFVec3f",
    // X3D types (ISO/IEC 19777-1; script_prelude_x3d.cpp): SFDouble is a number.
    nullptr, "SFVec2d", "SFVec3d", "SFVec4f", "SFVec4d", "SFColorRGBA", "SFMatrix3f", "SFMatrix3d",
    "SFMatrix4f", "SFMatrix4d", "MFBool", "MFDouble", "MFImage", "MFVec2d", "MFVec3d", "MFVec4f",
    "MFVec4d", "MFColorRGBA", "MFMatrix3f", "MFMatrix3d", "MFMatrix4f", "MFMatrix4d"};

const char* typeOf(duk_context* c, duk_idx_t idx) {
  switch (duk_get_type(c, idx)) {
    case DUK_TYPE_UNDEFINED:
      return "undefined";
    case DUK_TYPE_NULL:
      return "null";
    case DUK_TYPE_BOOLEAN:
      return "a boolean";
    case DUK_TYPE_NUMBER:
      return "a number";
    case DUK_TYPE_STRING:
      return "a string";
    case DUK_TYPE_OBJECT:
      return duk_is_function(c, idx) ? "a function" : "an object";
    default:
      return "a value of another type";
  }
}

void putNumber(duk_context* c, const char* name, double v) {
  duk_push_number(c, v);
  duk_put_prop_string(c, -2, name);
}

}  // namespace

double vectorComponent(duk_context* c, duk_idx_t obj, const char* name, duk_uarridx_t k) {
  duk_get_prop_string(c, obj, name);
  if (duk_is_undefined(c, -1)) {
    duk_pop(c);
    duk_get_prop_index(c, obj, k);
  }
  double v = duk_to_number(c, -1);
  duk_pop(c);
  return v;
}

void EsScript::pushProto(duk_context* c, FieldType t) {
  void* proto = protos_[static_cast<std::size_t>(t)];
  if (proto == nullptr) {
    duk_push_undefined(c);  // a class this heap does not have: a bare object
    return;
  }
  duk_push_heapptr(c, proto);
}

void EsScript::capturePrototypes(duk_context* c) {
  protos_.assign(vrml::kFieldTypeCount, nullptr);
  duk_push_heap_stash(c);
  duk_push_array(c);  // keeps the prototypes alive if a Script overwrites the classes
  for (std::size_t i = 0; i < kClassNames.size(); ++i) {
    if (kClassNames[i] == nullptr) continue;
    duk_get_global_string(c, kClassNames[i]);
    if (duk_is_undefined(c, -1)) {  // an X3D class in a heap without them (wantsX3D)
      duk_pop(c);
      continue;
    }
    duk_get_prop_string(c, -1, "prototype");
    protos_[i] = duk_get_heapptr(c, -1);
    duk_put_prop_index(c, -3, static_cast<duk_uarridx_t>(i));
    duk_pop(c);
  }
  duk_put_prop_string(c, -2, "gsProtos");
  duk_push_bare_object(c);
  nodeCache_ = duk_get_heapptr(c, -1);
  duk_put_prop_string(c, -2, "gsNodes");
  // The node fields read as objects in a call (script_live_fields.cpp), and the prelude's
  // wrapper of their MF arrays, taken out of the global object.
  duk_push_bare_array(c);
  liveStore_ = duk_get_heapptr(c, -1);
  duk_put_prop_string(c, -2, "gsLive");
  duk_get_global_string(c, "__gsLiveMF");
  duk_put_prop_string(c, -2, "gsLiveMF");
  duk_pop(c);
  duk_push_global_object(c);
  duk_del_prop_string(c, -1, "__gsLiveMF");
  duk_pop(c);
}

// ---- FieldValue -> ECMAScript ----

void EsScript::pushValue(duk_context* c, const FieldValue& v) {
  // Objects are filled while they have no prototype (no inherited setter that a Script
  // put on a prototype runs), then given their class.
  auto finish = [&](FieldType t) {
    pushProto(c, t);
    duk_set_prototype(c, -2);
  };
  auto vec3 = [&](FieldType t, const glm::vec3& x, const char* a, const char* b, const char* d) {
    duk_push_bare_object(c);
    putNumber(c, a, x.x);
    putNumber(c, b, x.y);
    putNumber(c, d, x.z);
    finish(t);
  };
  auto vec2 = [&](const glm::vec2& x) {
    duk_push_bare_object(c);
    putNumber(c, "x", x.x);
    putNumber(c, "y", x.y);
    finish(FieldType::SFVec2f);
  };
  auto rotation = [&](const vrml::Rotation& r) {
    duk_push_bare_object(c);
    putNumber(c, "x", r.x);
    putNumber(c, "y", r.y);
    putNumber(c, "z", r.z);
    putNumber(c, "angle", r.w);
    finish(FieldType::SFRotation);
  };
  auto array = [&](FieldType t, std::size_t n, auto&& each) {
    duk_push_bare_array(c);
    for (std::size_t i = 0; i < n; ++i) {
      each(i);
      duk_put_prop_index(c, -2, static_cast<duk_uarridx_t>(i));
    }
    finish(t);
  };
  switch (v.type()) {
    case FieldType::SFBool:
      duk_push_boolean(c, v.get<FieldType::SFBool>());
      break;
    case FieldType::SFColor:
      vec3(FieldType::SFColor, v.get<FieldType::SFColor>(), "r", "g", "b");
      break;
    case FieldType::SFFloat:
      duk_push_number(c, v.get<FieldType::SFFloat>());
      break;
    case FieldType::SFImage: {
      const vrml::SFImage& img = v.get<FieldType::SFImage>();
      duk_push_bare_object(c);
      putNumber(c, "x", img.width);
      putNumber(c, "y", img.height);
      putNumber(c, "comp", img.components);
      array(FieldType::MFInt32, img.pixels.size(),
            [&](std::size_t i) { duk_push_number(c, img.pixels[i]); });
      duk_put_prop_string(c, -2, "array");
      finish(FieldType::SFImage);
      break;
    }
    case FieldType::SFInt32:
      duk_push_int(c, v.get<FieldType::SFInt32>());
      break;
    case FieldType::SFNode:
      pushNode(c, v.get<FieldType::SFNode>());
      break;
    case FieldType::SFRotation:
      rotation(v.get<FieldType::SFRotation>());
      break;
    case FieldType::SFString: {
      const std::string& s = v.get<FieldType::SFString>();
      duk_push_lstring(c, s.data(), s.size());
      break;
    }
    case FieldType::SFTime:
      duk_push_number(c, v.get<FieldType::SFTime>());
      break;
    case FieldType::SFVec2f:
      vec2(v.get<FieldType::SFVec2f>());
      break;
    case FieldType::SFVec3f:
      vec3(FieldType::SFVec3f, v.get<FieldType::SFVec3f>(), "x", "y", "z");
      break;
    case FieldType::MFColor: {
      const auto& a = v.get<FieldType::MFColor>();
      array(FieldType::MFColor, a.size(),
            [&](std::size_t i) { vec3(FieldType::SFColor, a[i], "r", "g", "b"); });
      break;
    }
    case FieldType::MFFloat: {
      const auto& a = v.get<FieldType::MFFloat>();
      array(FieldType::MFFloat, a.size(), [&](std::size_t i) { duk_push_number(c, a[i]); });
      break;
    }
    case FieldType::MFInt32: {
      const auto& a = v.get<FieldType::MFInt32>();
      array(FieldType::MFInt32, a.size(), [&](std::size_t i) { duk_push_int(c, a[i]); });
      break;
    }
    case FieldType::MFNode: {
      const auto& a = v.get<FieldType::MFNode>();
      array(FieldType::MFNode, a.size(), [&](std::size_t i) { pushNode(c, a[i]); });
      break;
    }
    case FieldType::MFRotation: {
      const auto& a = v.get<FieldType::MFRotation>();
      array(FieldType::MFRotation, a.size(), [&](std::size_t i) { rotation(a[i]); });
      break;
    }
    case FieldType::MFString: {
      const auto& a = v.get<FieldType::MFString>();
      array(FieldType::MFString, a.size(),
            [&](std::size_t i) { duk_push_lstring(c, a[i].data(), a[i].size()); });
      break;
    }
    case FieldType::MFTime: {
      const auto& a = v.get<FieldType::MFTime>();
      array(FieldType::MFTime, a.size(), [&](std::size_t i) { duk_push_number(c, a[i]); });
      break;
    }
    case FieldType::MFVec2f: {
      const auto& a = v.get<FieldType::MFVec2f>();
      array(FieldType::MFVec2f, a.size(), [&](std::size_t i) { vec2(a[i]); });
      break;
    }
    case FieldType::MFVec3f: {
      const auto& a = v.get<FieldType::MFVec3f>();
      array(FieldType::MFVec3f, a.size(),
            [&](std::size_t i) { vec3(FieldType::SFVec3f, a[i], "x", "y", "z"); });
      break;
    }
    default:  // an X3D type: the X3D classes (script_x3d.cpp)
      pushX3DValue(c, v);
      break;
  }
}

// ---- ECMAScript -> FieldValue ----

bool EsScript::toValue(duk_context* c, duk_idx_t idx, FieldType t, FieldValue& out,
                       std::string& why) {
  idx = duk_normalize_index(c, idx);
  auto needObject = [&]() {
    if (duk_is_object(c, idx) && !duk_is_function(c, idx)) return true;
    why =
        std::string("expected ") + std::string(vrml::fieldTypeName(t)) + ", got " + typeOf(c, idx);
    return false;
  };
  auto number = [&]() {
    duk_dup(c, idx);
    double d = duk_to_number(c, -1);
    duk_pop(c);
    return d;
  };
  switch (t) {
    case FieldType::SFBool:
      out = FieldValue::make<FieldType::SFBool>(duk_to_boolean(c, dupTop(c, idx)) != 0);
      duk_pop(c);
      return true;
    case FieldType::SFFloat:
      out = FieldValue::make<FieldType::SFFloat>(static_cast<float>(number()));
      return true;
    case FieldType::SFTime:
      out = FieldValue::make<FieldType::SFTime>(number());
      return true;
    case FieldType::SFInt32: {
      duk_dup(c, idx);
      std::int32_t i = duk_to_int32(c, -1);
      duk_pop(c);
      out = FieldValue::make<FieldType::SFInt32>(i);
      return true;
    }
    case FieldType::SFString: {
      duk_dup(c, idx);
      duk_size_t len = 0;
      const char* s = duk_to_lstring(c, -1, &len);
      out = FieldValue::make<FieldType::SFString>(std::string(s, len));
      duk_pop(c);
      return true;
    }
    case FieldType::SFVec2f:
      if (!needObject()) return false;
      out = FieldValue::make<FieldType::SFVec2f>(
          glm::vec2(static_cast<float>(vectorComponent(c, idx, "x", 0)),
                    static_cast<float>(vectorComponent(c, idx, "y", 1))));
      return true;
    case FieldType::SFVec3f:
    case FieldType::SFColor: {
      if (!needObject()) return false;
      bool color = t == FieldType::SFColor;
      glm::vec3 v(static_cast<float>(vectorComponent(c, idx, color ? "r" : "x", 0)),
                  static_cast<float>(vectorComponent(c, idx, color ? "g" : "y", 1)),
                  static_cast<float>(vectorComponent(c, idx, color ? "b" : "z", 2)));
      out =
          color ? FieldValue::make<FieldType::SFColor>(v) : FieldValue::make<FieldType::SFVec3f>(v);
      return true;
    }
    case FieldType::SFRotation:
      if (!needObject()) return false;
      out = FieldValue::make<FieldType::SFRotation>(
          vrml::Rotation(static_cast<float>(vectorComponent(c, idx, "x", 0)),
                         static_cast<float>(vectorComponent(c, idx, "y", 1)),
                         static_cast<float>(vectorComponent(c, idx, "z", 2)),
                         static_cast<float>(vectorComponent(c, idx, "angle", 3))));
      return true;
    case FieldType::SFNode: {
      if (duk_is_null_or_undefined(c, idx)) {
        out = FieldValue::make<FieldType::SFNode>(vrml::NodePtr());
        return true;
      }
      bool isNode = false;
      vrml::NodePtr n = nodeAt(c, idx, &isNode);
      if (!isNode) {
        why = std::string("expected SFNode, got ") + typeOf(c, idx);
        return false;
      }
      out = FieldValue::make<FieldType::SFNode>(std::move(n));
      return true;
    }
    case FieldType::SFImage: {
      if (!needObject()) return false;
      vrml::SFImage img;
      auto intProp = [&](const char* name) {
        duk_get_prop_string(c, idx, name);
        double d = duk_to_number(c, -1);
        duk_pop(c);
        return d;
      };
      double w = intProp("x"), h = intProp("y"), comp = intProp("comp");
      if (!(w >= 0 && h >= 0 && comp >= 0 && comp <= 4) || w != std::floor(w) ||
          h != std::floor(h)) {
        why = "SFImage needs whole x, y >= 0 and comp 0..4";
        return false;
      }
      duk_get_prop_string(c, idx, "array");
      duk_size_t n = duk_is_object(c, -1) ? duk_get_length(c, -1) : 0;
      if (w * h != static_cast<double>(n)) {
        duk_pop(c);
        why = "SFImage has " + std::to_string(n) + " pixels in array, x * y is " +
              std::to_string(static_cast<long long>(w * h));
        return false;
      }
      if (n > limits_.heapBytes / 4) {
        duk_pop(c);
        why = "SFImage larger than the Script's memory limit";
        return false;
      }
      img.width = static_cast<int>(w);
      img.height = static_cast<int>(h);
      img.components = static_cast<int>(comp);
      img.pixels.reserve(n);
      for (duk_size_t i = 0; i < n; ++i) {
        if ((i & 4095u) == 4095u) checkDeadline(c);
        duk_get_prop_index(c, -1, static_cast<duk_uarridx_t>(i));
        img.pixels.push_back(duk_to_uint32(c, -1));
        duk_pop(c);
      }
      duk_pop(c);
      out = FieldValue::make<FieldType::SFImage>(std::move(img));
      return true;
    }
    default:
      break;
  }
  if (static_cast<int>(t) >= vrml::kVrml97FieldTypeCount && !vrml::isMultiValued(t))
    return toX3DSingle(c, idx, t, out, why);  // script_x3d.cpp
  return toMF(c, idx, t, out, why);
}

bool EsScript::toMF(duk_context* c, duk_idx_t idx, FieldType t, FieldValue& out, std::string& why) {
  FieldType et = vrml::elementType(t);
  out = FieldValue(t);
  if (duk_is_null_or_undefined(c, idx)) return true;  // empty
  bool list = duk_is_array(c, idx) != 0;
  duk_size_t n = list ? duk_get_length(c, idx) : 1;
  auto fill = [&](auto& vec, auto tag) {
    constexpr FieldType ST = decltype(tag)::value;
    // The value lives outside the Script's heap: at most as many bytes as the heap's limit
    // (a Script's array of holes costs it almost nothing).
    using Element = typename std::decay_t<decltype(vec)>::value_type;
    std::size_t maxElements = std::max<std::size_t>(1024, limits_.heapBytes / sizeof(Element));
    if (n > maxElements) {
      why = std::string(vrml::fieldTypeName(t)) + " of " + std::to_string(n) +
            " values is larger than the Script's limit of " + std::to_string(maxElements);
      return false;
    }
    vec.reserve(n);
    FieldValue e;
    for (duk_size_t i = 0; i < n; ++i) {
      if ((i & 4095u) == 4095u) checkDeadline(c);
      if (list) {
        duk_get_prop_index(c, idx, static_cast<duk_uarridx_t>(i));
      } else {
        duk_dup(c, idx);
      }
      if (duk_is_undefined(c, -1)) {  // a hole (v.length = 10): the type's default
        e = FieldValue(ST);
      } else if (!toValue(c, -1, ST, e, why)) {
        duk_pop(c);
        if (list) why = "value " + std::to_string(i) + ": " + why;
        return false;
      }
      duk_pop(c);
      vec.push_back(std::move(e.template get<ST>()));
    }
    return true;
  };
  switch (et) {
    case FieldType::SFColor:
      return fill(out.get<FieldType::MFColor>(),
                  std::integral_constant<FieldType, FieldType::SFColor>());
    case FieldType::SFFloat:
      return fill(out.get<FieldType::MFFloat>(),
                  std::integral_constant<FieldType, FieldType::SFFloat>());
    case FieldType::SFInt32:
      return fill(out.get<FieldType::MFInt32>(),
                  std::integral_constant<FieldType, FieldType::SFInt32>());
    case FieldType::SFNode:
      return fill(out.get<FieldType::MFNode>(),
                  std::integral_constant<FieldType, FieldType::SFNode>());
    case FieldType::SFRotation:
      return fill(out.get<FieldType::MFRotation>(),
                  std::integral_constant<FieldType, FieldType::SFRotation>());
    case FieldType::SFString:
      return fill(out.get<FieldType::MFString>(),
                  std::integral_constant<FieldType, FieldType::SFString>());
    case FieldType::SFTime:
      return fill(out.get<FieldType::MFTime>(),
                  std::integral_constant<FieldType, FieldType::SFTime>());
    case FieldType::SFVec2f:
      return fill(out.get<FieldType::MFVec2f>(),
                  std::integral_constant<FieldType, FieldType::SFVec2f>());
    case FieldType::SFVec3f:
      return fill(out.get<FieldType::MFVec3f>(),
                  std::integral_constant<FieldType, FieldType::SFVec3f>());
    // X3D's MF types
    case FieldType::SFBool:
      return fill(out.get<FieldType::MFBool>(),
                  std::integral_constant<FieldType, FieldType::SFBool>());
    case FieldType::SFDouble:
      return fill(out.get<FieldType::MFDouble>(),
                  std::integral_constant<FieldType, FieldType::SFDouble>());
    case FieldType::SFImage:
      return fill(out.get<FieldType::MFImage>(),
                  std::integral_constant<FieldType, FieldType::SFImage>());
    case FieldType::SFVec2d:
      return fill(out.get<FieldType::MFVec2d>(),
                  std::integral_constant<FieldType, FieldType::SFVec2d>());
    case FieldType::SFVec3d:
      return fill(out.get<FieldType::MFVec3d>(),
                  std::integral_constant<FieldType, FieldType::SFVec3d>());
    case FieldType::SFVec4f:
      return fill(out.get<FieldType::MFVec4f>(),
                  std::integral_constant<FieldType, FieldType::SFVec4f>());
    case FieldType::SFVec4d:
      return fill(out.get<FieldType::MFVec4d>(),
                  std::integral_constant<FieldType, FieldType::SFVec4d>());
    case FieldType::SFColorRGBA:
      return fill(out.get<FieldType::MFColorRGBA>(),
                  std::integral_constant<FieldType, FieldType::SFColorRGBA>());
    case FieldType::SFMatrix3f:
      return fill(out.get<FieldType::MFMatrix3f>(),
                  std::integral_constant<FieldType, FieldType::SFMatrix3f>());
    case FieldType::SFMatrix3d:
      return fill(out.get<FieldType::MFMatrix3d>(),
                  std::integral_constant<FieldType, FieldType::SFMatrix3d>());
    case FieldType::SFMatrix4f:
      return fill(out.get<FieldType::MFMatrix4f>(),
                  std::integral_constant<FieldType, FieldType::SFMatrix4f>());
    case FieldType::SFMatrix4d:
      return fill(out.get<FieldType::MFMatrix4d>(),
                  std::integral_constant<FieldType, FieldType::SFMatrix4d>());
    default:
      why = "unsupported type";
      return false;
  }
}

FieldValue EsScript::requireValue(duk_context* c, duk_idx_t idx, FieldType t, const char* what) {
  FieldValue v;
  std::string why;
  if (!toValue(c, idx, t, v, why)) {
    std::string msg = std::string(what) + ": " + why;
    // Errors are C++ exceptions (DUK_USE_CPP_EXCEPTIONS): the strings are destroyed.
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s", msg.c_str());
  }
  return v;
}

// ---- SFNode objects ----

duk_ret_t EsScript::nodeFieldGetter(duk_context* c) {
  EsScript& self = of(c);
  auto i = static_cast<std::size_t>(duk_get_current_magic(c));
  duk_push_this(c);
  vrml::NodePtr n = self.nodeAt(c, -1);
  if (!n || i >= n->fieldCount() || n->type().fields[i].access == vrml::AccessType::eventIn)
    return 0;  // undefined
  self.pushNodeField(c, n, i);
  return 1;
}

duk_ret_t EsScript::nodeFieldSetter(duk_context* c) {
  EsScript& self = of(c);
  auto i = static_cast<std::size_t>(duk_get_current_magic(c));
  duk_push_this(c);
  vrml::NodePtr n = self.nodeAt(c, -1);
  if (!n || i >= n->fieldCount()) return 0;
  const vrml::FieldSpec& spec = n->type().fields[i];
  if (spec.access != vrml::AccessType::eventIn && spec.access != vrml::AccessType::exposedField) {
    std::string msg = spec.name + " of " + n->typeName() + " is " +
                      std::string(vrml::accessTypeName(spec.access)) + ": it cannot be written";
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s", msg.c_str());
  }
  FieldValue v = self.requireValue(c, 0, spec.type, spec.name.c_str());
  self.sendChangedLiveFields(c, *n, i);  // what the Script changed in place before, first
  self.assignedNodeField(c, n, i, v);
  // 4.12.4: sent to the node as an event at the current timestamp.
  self.ctx_.sendEvent(*n, static_cast<int>(i), std::move(v));
  return 0;
}

// A PROTO instance shows its declared interface (clause 4.8.3): reading a member reads
// the body member IS-connected to it; writing one sends the event to every body member
// IS-connected to it.
duk_ret_t EsScript::protoFieldGetter(duk_context* c) {
  EsScript& self = of(c);
  const int i = duk_get_current_magic(c);
  duk_push_this(c);
  vrml::NodePtr n = self.nodeAt(c, -1);
  const vrml::ProtoInstance* p = n ? vrml::declaredInterface(*n) : nullptr;
  if (p == nullptr || i < 0 || static_cast<std::size_t>(i) >= p->type->fields.size() ||
      p->type->fields[static_cast<std::size_t>(i)].access == vrml::AccessType::eventIn)
    return 0;  // undefined
  const FieldValue* v = p->value(i);
  if (v == nullptr || v->type() != p->type->fields[static_cast<std::size_t>(i)].type) return 0;
  self.pushValue(c, *v);
  return 1;
}

duk_ret_t EsScript::protoFieldSetter(duk_context* c) {
  EsScript& self = of(c);
  const int i = duk_get_current_magic(c);
  duk_push_this(c);
  vrml::NodePtr n = self.nodeAt(c, -1);
  const vrml::ProtoInstance* p = n ? vrml::declaredInterface(*n) : nullptr;
  if (p == nullptr || i < 0 || static_cast<std::size_t>(i) >= p->type->fields.size()) return 0;
  const vrml::FieldSpec& spec = p->type->fields[static_cast<std::size_t>(i)];
  if (spec.access != vrml::AccessType::eventIn && spec.access != vrml::AccessType::exposedField) {
    std::string msg = spec.name + " of " + p->type->name + " is " +
                      std::string(vrml::accessTypeName(spec.access)) + ": it cannot be written";
    GS_DUK_ERROR(c, DUK_ERR_TYPE_ERROR, "%s", msg.c_str());
  }
  FieldValue v = self.requireValue(c, 0, spec.type, spec.name.c_str());
  for (const vrml::InstanceLink& k : p->linksOf(i)) {
    if (k.nodeAccess != vrml::AccessType::eventIn && k.nodeAccess != vrml::AccessType::exposedField)
      continue;
    if (const vrml::NodePtr body = k.node.lock()) self.ctx_.sendEvent(*body, k.nodeField, v);
  }
  return 0;
}

void EsScript::pushNode(duk_context* c, const vrml::NodePtr& n) {
  if (!n) {
    duk_push_null(c);
    return;
  }
  if (auto it = nodeIds_.find(n.get()); it != nodeIds_.end()) {
    duk_push_heapptr(c, nodeCache_);
    duk_get_prop_index(c, -1, it->second);
    duk_remove(c, -2);
    return;
  }
  auto id = static_cast<std::uint32_t>(nodes_.size());
  duk_push_bare_object(c);
  duk_push_uint(c, id);
  duk_put_prop_string(c, -2, kNodeIdKey);
  const vrml::ProtoInstance* instance = vrml::declaredInterface(*n);
  const vrml::NodeType& type = instance != nullptr ? *instance->type : n->type();
  auto define = [&](const std::string& key, std::size_t i) {
    duk_push_lstring(c, key.data(), key.size());
    if (instance != nullptr) {
      pushAccessor(c, protoGetters_, i, protoFieldGetter, 0);
      pushAccessor(c, protoSetters_, i, protoFieldSetter, 1);
    } else {
      pushAccessor(c, nodeGetters_, i, nodeFieldGetter, 0);
      pushAccessor(c, nodeSetters_, i, nodeFieldSetter, 1);
    }
    duk_def_prop(c, -4,
                 DUK_DEFPROP_HAVE_GETTER | DUK_DEFPROP_HAVE_SETTER | DUK_DEFPROP_SET_ENUMERABLE |
                     DUK_DEFPROP_FORCE);
  };
  for (std::size_t i = 0; i < type.fields.size() && i <= 32767; ++i) {
    const vrml::FieldSpec& spec = type.fields[i];
    define(spec.name, i);
    if (spec.access == vrml::AccessType::exposedField) {
      define("set_" + spec.name, i);
      define(spec.name + "_changed", i);
    }
  }
  pushProto(c, FieldType::SFNode);
  duk_set_prototype(c, -2);
  duk_push_heapptr(c, nodeCache_);
  duk_dup(c, -2);
  duk_put_prop_index(c, -2, id);
  duk_pop(c);
  // Registered once the object is complete (an error above leaves nothing behind).
  nodes_.push_back(n);
  nodeIds_.emplace(n.get(), id);
}

vrml::NodePtr EsScript::nodeAt(duk_context* c, duk_idx_t idx, bool* isNode) {
  if (isNode != nullptr) *isNode = false;
  if (!duk_is_object(c, idx)) return nullptr;
  duk_get_prop_string(c, idx, kNodeIdKey);
  bool has = duk_is_number(c, -1) != 0;
  duk_uint_t id = has ? duk_get_uint(c, -1) : 0;
  duk_pop(c);
  if (!has || id >= nodes_.size()) return nullptr;
  if (isNode != nullptr) *isNode = true;
  return nodes_[id];
}

void EsScript::installNodeHooks(duk_context* c) {
  struct Hooks {
    static duk_ret_t fromString(duk_context* cx) {
      EsScript& self = of(cx);
      duk_size_t len = 0;
      const char* text = duk_require_lstring(cx, 0, &len);
      std::size_t maxText =
          std::max<std::size_t>(65536, self.limits_.heapBytes / 64);  // as Browser's
      if (len > maxText)
        GS_DUK_ERROR(cx, DUK_ERR_RANGE_ERROR, "SFNode: the VRML text is longer than %lu bytes",
                     static_cast<unsigned long>(maxText));
      std::string body(text, len);
      // In an X3D world the text is X3D (its nodes and fields), as the world's version.
      const vrml::Scene* world = self.ctx_.sceneOf(self.node_);
      if (world != nullptr && !world->x3d.version.empty() && !body.starts_with("#X3D") &&
          !body.starts_with("#VRML"))
        body = "#X3D V" + world->x3d.version + " utf8\n" + body;
      std::vector<vrml::NodePtr> nodes = self.createFromText(cx, body)->rootNodes;
      if (nodes.empty() || !nodes.front())
        GS_DUK_ERROR(cx, DUK_ERR_ERROR, "SFNode: the VRML text holds no node");
      self.pushNode(cx, nodes.front());
      return 1;
    }
    static duk_ret_t nodeName(duk_context* cx) {
      EsScript& self = of(cx);
      vrml::NodePtr n = self.nodeAt(cx, 0);
      std::string s =
          !n ? std::string("NULL")
             : (n->defName.empty() ? "" : "DEF " + n->defName + " ") + n->typeName() + " { }";
      duk_push_lstring(cx, s.data(), s.size());
      return 1;
    }
  };
  duk_push_global_object(c);
  duk_push_c_function(c, Hooks::fromString, 1);
  duk_put_prop_string(c, -2, "__gsNodeFromString");
  duk_push_c_function(c, Hooks::nodeName, 1);
  duk_put_prop_string(c, -2, "__gsNodeName");
  duk_pop(c);
}

}  // namespace gs::runtime::es
