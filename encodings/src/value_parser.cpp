// Field values of the 20 VRML97 field types (clause 5, annex A.4 grammar) and the 22 X3D
// types (ISO/IEC 19776-2 clause 5, the Classic VRML encoding of each).
#include "parser_impl.hpp"

#include <algorithm>

namespace gs::vrml::parsing {

namespace {
template <FieldType T>
constexpr std::size_t idx() {
  return static_cast<std::size_t>(T);
}
}  // namespace

bool Parser::readBool() {
  const Token t = lex_.peek();
  if (t.kind == Tok::id) {
    if (t.text == "TRUE") {
      lex_.consume(t);
      return true;
    }
    if (t.text == "FALSE") {
      lex_.consume(t);
      return false;
    }
  }
  lex_.failExpected(t.offset, "TRUE or FALSE");
}

glm::vec2 Parser::readVec2() {
  const float x = lex_.readFloat();
  const float y = lex_.readFloat();
  return {x, y};
}

glm::vec3 Parser::readVec3() {
  const float x = lex_.readFloat();
  const float y = lex_.readFloat();
  const float z = lex_.readFloat();
  return {x, y, z};
}

glm::vec4 Parser::readRotation() {
  const float x = lex_.readFloat();
  const float y = lex_.readFloat();
  const float z = lex_.readFloat();
  const float a = lex_.readFloat();
  return {x, y, z, a};
}

void Parser::readImage(SFImage& image) {
  const std::size_t start = lex_.offset();
  const std::int32_t w = lex_.readInt32();
  const std::int32_t h = lex_.readInt32();
  const std::int32_t c = lex_.readInt32();
  if (w < 0 || h < 0 || c < 0 || c > 4)
    lex_.fail(start, "invalid SFImage size " + std::to_string(w) + " x " + std::to_string(h) +
                         " with " + std::to_string(c) + " components");
  const std::uint64_t n = static_cast<std::uint64_t>(w) * static_cast<std::uint64_t>(h);
  // Each pixel takes at least two bytes ("0 "): never reserve more than the input holds.
  if (n > (lex_.remaining() + 1) / 2) {
    lex_.markEnd();  // more text might hold the pixels
    lex_.fail(start, "SFImage of " + std::to_string(w) + " x " + std::to_string(h) + " needs " +
                         std::to_string(n) + " pixels but only " +
                         std::to_string(lex_.remaining()) + " bytes of input remain");
  }
  image.width = w;
  image.height = h;
  image.components = c;
  image.pixels.clear();
  image.pixels.reserve(static_cast<std::size_t>(n));
  for (std::uint64_t i = 0; i < n; ++i)
    image.pixels.push_back(static_cast<std::uint32_t>(lex_.readInt32()));
}

// An MF value: one element, or `[ elements ]` (clause 5.1).
template <class T, class F>
void Parser::readList(std::vector<T>& v, F&& one) {
  v.clear();
  if (!lex_.accept('[')) {
    v.push_back(one());
    return;
  }
  while (lex_.peekChar() != ']') v.push_back(one());
  lex_.setOffset(lex_.offset() + 1);
}

// An MF value whose elements are N floats (MFFloat, MFVec2f, MFVec3f, MFColor,
// MFRotation). The elements go to a scratch buffer that lives as long as the parser, and
// the result is allocated once, at its exact size.
template <int N, class T>
void Parser::readFloatList(std::vector<T>& v, std::vector<T>& scratch) {
  v.clear();
  if (!lex_.accept('[')) {
    if constexpr (N == 1) {
      v.push_back(lex_.readFloat());
    } else {
      T one;
      for (int i = 0; i < N; ++i) one[i] = lex_.readFloat();
      v.push_back(one);
    }
    return;
  }
  scratch.clear();
  lex_.readFloatsUntilBracket<N>(scratch);
  v.assign(scratch.begin(), scratch.end());
}

void Parser::readInt32List(std::vector<std::int32_t>& v) {
  v.clear();
  if (!lex_.accept('[')) {
    v.push_back(lex_.readInt32());
    return;
  }
  intScratch_.clear();
  lex_.readInt32sUntilBracket(intScratch_);
  v.assign(intScratch_.begin(), intScratch_.end());
}

namespace {

// N doubles (an X3D SFVec2d/3d/4d).
template <class V, int N>
V readDoubles(Lexer& lex) {
  V v{};
  for (int i = 0; i < N; ++i) v[i] = lex.readDouble();
  return v;
}

// An X3D matrix written row by row (X3D clause 5.3.10), stored column-major (glm).
template <class M, int N, bool Double>
M readMatrix(Lexer& lex) {
  M m(0);
  for (int row = 0; row < N; ++row)
    for (int col = 0; col < N; ++col) {
      if constexpr (Double)
        m[col][row] = lex.readDouble();
      else
        m[col][row] = lex.readFloat();
    }
  return m;
}

}  // namespace

// The X3D types (parseValue's second half).
void Parser::parseX3dValue(FieldType t, FieldValue& out) {
  auto& st = out.storage();
  auto vec4f = [this] {
    glm::vec4 v;
    for (int i = 0; i < 4; ++i) v[i] = lex_.readFloat();
    return v;
  };
  switch (t) {
    case FieldType::SFDouble:
      st.emplace<idx<FieldType::SFDouble>()>(lex_.readDouble());
      return;
    case FieldType::SFVec2d:
      st.emplace<idx<FieldType::SFVec2d>()>(readDoubles<glm::dvec2, 2>(lex_));
      return;
    case FieldType::SFVec3d:
      st.emplace<idx<FieldType::SFVec3d>()>(readDoubles<glm::dvec3, 3>(lex_));
      return;
    case FieldType::SFVec4f:
      st.emplace<idx<FieldType::SFVec4f>()>(vec4f());
      return;
    case FieldType::SFVec4d:
      st.emplace<idx<FieldType::SFVec4d>()>(readDoubles<glm::dvec4, 4>(lex_));
      return;
    case FieldType::SFColorRGBA:
      st.emplace<idx<FieldType::SFColorRGBA>()>(vec4f());
      return;
    case FieldType::SFMatrix3f:
      st.emplace<idx<FieldType::SFMatrix3f>()>(readMatrix<glm::mat3, 3, false>(lex_));
      return;
    case FieldType::SFMatrix3d:
      st.emplace<idx<FieldType::SFMatrix3d>()>(readMatrix<glm::dmat3, 3, true>(lex_));
      return;
    case FieldType::SFMatrix4f:
      st.emplace<idx<FieldType::SFMatrix4f>()>(readMatrix<glm::mat4, 4, false>(lex_));
      return;
    case FieldType::SFMatrix4d:
      st.emplace<idx<FieldType::SFMatrix4d>()>(readMatrix<glm::dmat4, 4, true>(lex_));
      return;
    case FieldType::MFBool:
      readList(st.emplace<idx<FieldType::MFBool>()>().get(), [this] { return readBool(); });
      return;
    case FieldType::MFDouble:
      readList(st.emplace<idx<FieldType::MFDouble>()>(), [this] { return lex_.readDouble(); });
      return;
    case FieldType::MFImage:
      readList(st.emplace<idx<FieldType::MFImage>()>(), [this] {
        SFImage image;
        readImage(image);
        return image;
      });
      return;
    case FieldType::MFVec2d:
      readList(st.emplace<idx<FieldType::MFVec2d>()>(),
               [this] { return readDoubles<glm::dvec2, 2>(lex_); });
      return;
    case FieldType::MFVec3d:
      readList(st.emplace<idx<FieldType::MFVec3d>()>(),
               [this] { return readDoubles<glm::dvec3, 3>(lex_); });
      return;
    case FieldType::MFVec4f:
      readFloatList<4>(st.emplace<idx<FieldType::MFVec4f>()>(), vec4Scratch_);
      return;
    case FieldType::MFVec4d:
      readList(st.emplace<idx<FieldType::MFVec4d>()>(),
               [this] { return readDoubles<glm::dvec4, 4>(lex_); });
      return;
    case FieldType::MFColorRGBA:
      readFloatList<4>(st.emplace<idx<FieldType::MFColorRGBA>()>(), vec4Scratch_);
      return;
    case FieldType::MFMatrix3f:
      readList(st.emplace<idx<FieldType::MFMatrix3f>()>(),
               [this] { return readMatrix<glm::mat3, 3, false>(lex_); });
      return;
    case FieldType::MFMatrix3d:
      readList(st.emplace<idx<FieldType::MFMatrix3d>()>(),
               [this] { return readMatrix<glm::dmat3, 3, true>(lex_); });
      return;
    case FieldType::MFMatrix4f:
      readList(st.emplace<idx<FieldType::MFMatrix4f>()>(),
               [this] { return readMatrix<glm::mat4, 4, false>(lex_); });
      return;
    case FieldType::MFMatrix4d:
      readList(st.emplace<idx<FieldType::MFMatrix4d>()>(),
               [this] { return readMatrix<glm::dmat4, 4, true>(lex_); });
      return;
    default:
      return;
  }
}

NodePtr Parser::parseSFNode(Scope& scope, int depth, int& height, const NodeType* parent,
                            std::string_view field) {
  const std::size_t offset = lex_.offset();
  int h = 0;
  NodePtr n = parseNodeStatement(scope, depth + 1, h, true);
  if (n) {
    height = std::max(height, h);
    if (parent != nullptr) checkNodeClass(parent, field, n, offset);
  }
  return n;
}

void Parser::parseValue(FieldType t, FieldValue& out, Scope& scope, int depth, int& height,
                        const NodeType* parent, std::string_view field) {
  auto& st = out.storage();
  switch (t) {
    case FieldType::SFBool:
      st.emplace<idx<FieldType::SFBool>()>(readBool());
      return;
    case FieldType::SFColor:
      st.emplace<idx<FieldType::SFColor>()>(readVec3());
      return;
    case FieldType::SFFloat:
      st.emplace<idx<FieldType::SFFloat>()>(lex_.readFloat());
      return;
    case FieldType::SFImage: {
      SFImage image;
      readImage(image);
      st.emplace<idx<FieldType::SFImage>()>(std::move(image));
      return;
    }
    case FieldType::SFInt32:
      st.emplace<idx<FieldType::SFInt32>()>(lex_.readInt32());
      return;
    case FieldType::SFNode: {
      NodePtr n = parseSFNode(scope, depth, height, parent, field);
      st.emplace<idx<FieldType::SFNode>()>(std::move(n));
      return;
    }
    case FieldType::SFRotation:
      st.emplace<idx<FieldType::SFRotation>()>(readRotation());
      return;
    case FieldType::SFString: {
      std::string s;
      lex_.readString(s);
      st.emplace<idx<FieldType::SFString>()>(std::move(s));
      return;
    }
    case FieldType::SFTime:
      st.emplace<idx<FieldType::SFTime>()>(lex_.readDouble());
      return;
    case FieldType::SFVec2f:
      st.emplace<idx<FieldType::SFVec2f>()>(readVec2());
      return;
    case FieldType::SFVec3f:
      st.emplace<idx<FieldType::SFVec3f>()>(readVec3());
      return;
    case FieldType::MFColor:
      readFloatList<3>(st.emplace<idx<FieldType::MFColor>()>(), vec3Scratch_);
      return;
    case FieldType::MFFloat:
      readFloatList<1>(st.emplace<idx<FieldType::MFFloat>()>(), floatScratch_);
      return;
    case FieldType::MFInt32:
      readInt32List(st.emplace<idx<FieldType::MFInt32>()>());
      return;
    case FieldType::MFNode: {
      auto& v = st.emplace<idx<FieldType::MFNode>()>();
      if (!lex_.accept('[')) {
        // A single node; NULL is read leniently as an empty list.
        NodePtr n = parseSFNode(scope, depth, height, parent, field);
        if (n) v.push_back(std::move(n));
        return;
      }
      while (lex_.peekChar() != ']') {
        if (lex_.atEnd()) lex_.failExpected(lex_.offset(), "a node or ']'");
        // PROTO, EXTERNPROTO and ROUTE statements among the nodes of an MFNode value (X3D's
        // Classic VRML grammar, ISO/IEC 19776-2 A.3; castle and OpenVRML read them in
        // VRML97 too): they belong to the enclosing scope.
        if (const Token stmt = lex_.peek(); stmt.kind == Tok::id && !tableMode_) {
          if (stmt.text == "PROTO") {
            parseProto(scope);
            continue;
          }
          if (stmt.text == "EXTERNPROTO") {
            parseExternProto(scope);
            continue;
          }
          if (stmt.text == "ROUTE") {
            parseRoute(scope);
            continue;
          }
        }
        NodePtr n = parseSFNode(scope, depth, height, parent, field);
        if (n) v.push_back(std::move(n));
      }
      lex_.setOffset(lex_.offset() + 1);
      return;
    }
    case FieldType::MFRotation:
      readFloatList<4>(st.emplace<idx<FieldType::MFRotation>()>(), vec4Scratch_);
      return;
    case FieldType::MFString:
      readList(st.emplace<idx<FieldType::MFString>()>(), [this] {
        std::string s;
        lex_.readString(s);
        return s;
      });
      return;
    case FieldType::MFTime:
      readList(st.emplace<idx<FieldType::MFTime>()>(), [this] { return lex_.readDouble(); });
      return;
    case FieldType::MFVec2f:
      readFloatList<2>(st.emplace<idx<FieldType::MFVec2f>()>(), vec2Scratch_);
      return;
    case FieldType::MFVec3f:
      readFloatList<3>(st.emplace<idx<FieldType::MFVec3f>()>(), vec3Scratch_);
      return;
    default:
      parseX3dValue(t, out);
      return;
  }
}

}  // namespace gs::vrml::parsing
