#include "runtime/trace.hpp"

#include <cstdio>

namespace gs::runtime {

using vrml::FieldType;

namespace {

void number(std::string& out, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  out += buf;
}

void vec(std::string& out, const float* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (i) out += ' ';
    number(out, v[i]);
  }
}

void vec(std::string& out, const double* v, int n) {
  for (int i = 0; i < n; ++i) {
    if (i) out += ' ';
    number(out, v[i]);
  }
}

// A matrix row by row, as X3D writes it (glm stores it column by column).
template <class M, int N>
void matrix(std::string& out, const M& m) {
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col) {
      if (row != 0 || col != 0) out += ' ';
      number(out, m[col][row]);
    }
}

void time(std::string& out, double t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.3f", t);
  out += buf;
}

void nodeName(std::string& out, const vrml::NodePtr& n) {
  out += n ? traceNodeName(*n) : "NULL";
}

template <class V, class F>
void list(std::string& out, const std::vector<V>& values, F one) {
  out += '[';
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i) out += ", ";
    one(values[i]);
  }
  out += ']';
}

void jsonString(std::string& out, const std::string& s) {
  out += '"';
  for (char c : s) {
    if (c == '"' || c == '\\') {
      out += '\\';
      out += c;
    } else if (static_cast<unsigned char>(c) < 0x20) {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(c));
      out += buf;
    } else {
      out += c;
    }
  }
  out += '"';
}

// The X3D types (fieldValueText's second half).
void x3dValueText(std::string& out, const vrml::FieldValue& v) {
  switch (v.type()) {
    case FieldType::SFDouble:
      number(out, v.get<FieldType::SFDouble>());
      break;
    case FieldType::SFVec2d:
      vec(out, &v.get<FieldType::SFVec2d>().x, 2);
      break;
    case FieldType::SFVec3d:
      vec(out, &v.get<FieldType::SFVec3d>().x, 3);
      break;
    case FieldType::SFVec4f:
      vec(out, &v.get<FieldType::SFVec4f>().x, 4);
      break;
    case FieldType::SFVec4d:
      vec(out, &v.get<FieldType::SFVec4d>().x, 4);
      break;
    case FieldType::SFColorRGBA:
      vec(out, &v.get<FieldType::SFColorRGBA>().x, 4);
      break;
    case FieldType::SFMatrix3f:
      matrix<glm::mat3, 3>(out, v.get<FieldType::SFMatrix3f>());
      break;
    case FieldType::SFMatrix3d:
      matrix<glm::dmat3, 3>(out, v.get<FieldType::SFMatrix3d>());
      break;
    case FieldType::SFMatrix4f:
      matrix<glm::mat4, 4>(out, v.get<FieldType::SFMatrix4f>());
      break;
    case FieldType::SFMatrix4d:
      matrix<glm::dmat4, 4>(out, v.get<FieldType::SFMatrix4d>());
      break;
    case FieldType::MFBool:
      list(out, v.get<FieldType::MFBool>(), [&](bool b) { out += b ? "TRUE" : "FALSE"; });
      break;
    case FieldType::MFDouble:
      list(out, v.get<FieldType::MFDouble>(), [&](double x) { number(out, x); });
      break;
    case FieldType::MFImage:
      list(out, v.get<FieldType::MFImage>(), [&](const vrml::SFImage& im) {
        out += std::to_string(im.width) + ' ' + std::to_string(im.height) + ' ' +
               std::to_string(im.components) + " ...";
      });
      break;
    case FieldType::MFVec2d:
      list(out, v.get<FieldType::MFVec2d>(), [&](const glm::dvec2& x) { vec(out, &x.x, 2); });
      break;
    case FieldType::MFVec3d:
      list(out, v.get<FieldType::MFVec3d>(), [&](const glm::dvec3& x) { vec(out, &x.x, 3); });
      break;
    case FieldType::MFVec4f:
    case FieldType::MFColorRGBA: {
      const auto& l = v.type() == FieldType::MFVec4f ? v.get<FieldType::MFVec4f>()
                                                     : v.get<FieldType::MFColorRGBA>();
      list(out, l, [&](const glm::vec4& x) { vec(out, &x.x, 4); });
      break;
    }
    case FieldType::MFVec4d:
      list(out, v.get<FieldType::MFVec4d>(), [&](const glm::dvec4& x) { vec(out, &x.x, 4); });
      break;
    case FieldType::MFMatrix3f:
      list(out, v.get<FieldType::MFMatrix3f>(),
           [&](const glm::mat3& m) { matrix<glm::mat3, 3>(out, m); });
      break;
    case FieldType::MFMatrix3d:
      list(out, v.get<FieldType::MFMatrix3d>(),
           [&](const glm::dmat3& m) { matrix<glm::dmat3, 3>(out, m); });
      break;
    case FieldType::MFMatrix4f:
      list(out, v.get<FieldType::MFMatrix4f>(),
           [&](const glm::mat4& m) { matrix<glm::mat4, 4>(out, m); });
      break;
    case FieldType::MFMatrix4d:
      list(out, v.get<FieldType::MFMatrix4d>(),
           [&](const glm::dmat4& m) { matrix<glm::dmat4, 4>(out, m); });
      break;
    default:
      break;
  }
}

}  // namespace

std::string fieldValueText(const vrml::FieldValue& v) {
  std::string out;
  switch (v.type()) {
    case FieldType::SFBool:
      out = v.get<FieldType::SFBool>() ? "TRUE" : "FALSE";
      break;
    case FieldType::SFColor:
      vec(out, &v.get<FieldType::SFColor>().x, 3);
      break;
    case FieldType::SFFloat:
      number(out, v.get<FieldType::SFFloat>());
      break;
    case FieldType::SFImage: {
      const vrml::SFImage& im = v.get<FieldType::SFImage>();
      out = std::to_string(im.width) + ' ' + std::to_string(im.height) + ' ' +
            std::to_string(im.components);
      for (std::uint32_t p : im.pixels) {
        char buf[16];
        std::snprintf(buf, sizeof buf, " 0x%X", p);
        out += buf;
      }
      break;
    }
    case FieldType::SFInt32:
      out = std::to_string(v.get<FieldType::SFInt32>());
      break;
    case FieldType::SFNode:
      nodeName(out, v.get<FieldType::SFNode>());
      break;
    case FieldType::SFRotation:
      vec(out, &v.get<FieldType::SFRotation>().x, 4);
      break;
    case FieldType::SFString:
      jsonString(out, v.get<FieldType::SFString>());
      break;
    case FieldType::SFTime:
      time(out, v.get<FieldType::SFTime>());
      break;
    case FieldType::SFVec2f:
      vec(out, &v.get<FieldType::SFVec2f>().x, 2);
      break;
    case FieldType::SFVec3f:
      vec(out, &v.get<FieldType::SFVec3f>().x, 3);
      break;
    case FieldType::MFColor:
    case FieldType::MFVec3f: {
      const auto& l = v.type() == FieldType::MFColor ? v.get<FieldType::MFColor>()
                                                     : v.get<FieldType::MFVec3f>();
      list(out, l, [&](const glm::vec3& x) { vec(out, &x.x, 3); });
      break;
    }
    case FieldType::MFFloat:
      list(out, v.get<FieldType::MFFloat>(), [&](float x) { number(out, x); });
      break;
    case FieldType::MFInt32:
      list(out, v.get<FieldType::MFInt32>(), [&](std::int32_t x) { out += std::to_string(x); });
      break;
    case FieldType::MFNode:
      list(out, v.get<FieldType::MFNode>(), [&](const vrml::NodePtr& n) { nodeName(out, n); });
      break;
    case FieldType::MFRotation:
      list(out, v.get<FieldType::MFRotation>(),
           [&](const vrml::Rotation& r) { vec(out, &r.x, 4); });
      break;
    case FieldType::MFString:
      list(out, v.get<FieldType::MFString>(), [&](const std::string& s) { jsonString(out, s); });
      break;
    case FieldType::MFTime:
      list(out, v.get<FieldType::MFTime>(), [&](double t) { time(out, t); });
      break;
    case FieldType::MFVec2f:
      list(out, v.get<FieldType::MFVec2f>(), [&](const glm::vec2& x) { vec(out, &x.x, 2); });
      break;
    default:
      x3dValueText(out, v);
      break;
  }
  return out;
}

std::string traceNodeName(const vrml::Node& node) {
  return node.defName.empty() ? node.typeName() : node.defName;
}

std::string traceJson(const TraceEvent& e) {
  std::string out = "{\"time\":";
  time(out, e.timestamp);
  out += ",\"node\":";
  jsonString(out, e.node ? traceNodeName(*e.node) : std::string());
  out += ",\"field\":";
  std::string field;
  if (e.node && e.field >= 0) {
    const vrml::FieldSpec& spec = e.node->type().fields[static_cast<std::size_t>(e.field)];
    field = spec.name;  // an exposedField's event is its eventOut x_changed (4.10.3)
    if (spec.access == vrml::AccessType::exposedField) field += "_changed";
  }
  jsonString(out, field);
  out += ",\"value\":";
  jsonString(out, e.value ? fieldValueText(*e.value) : std::string());
  out += '}';
  return out;
}

}  // namespace gs::runtime
