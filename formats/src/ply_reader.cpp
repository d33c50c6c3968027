// PLY 1.0 reader (ascii, binary_little_endian, binary_big_endian): see mesh_readers.hpp.
#include <algorithm>
#include <array>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <fast_float/fast_float.h>

#include "base/byte_order.hpp"
#include "formats/mesh_readers.hpp"

namespace gs::formats {
namespace {

enum class Type : std::uint8_t { kInt8, kUint8, kInt16, kUint16, kInt32, kUint32, kFloat, kDouble };
enum class Role : std::uint8_t { kSkip, kX, kY, kZ, kRed, kGreen, kBlue, kAlpha, kIndices };
enum class Format : std::uint8_t { kAscii, kLittle, kBig };

struct Property {
  std::string_view name;
  Type type = Type::kFloat;       // the item type for lists
  Type countType = Type::kUint8;  // lists only
  bool isList = false;
  Role role = Role::kSkip;
};

struct Element {
  std::string_view name;
  std::uint64_t count = 0;
  std::uint64_t line = 0;  // header line, for messages
  std::vector<Property> props;
};

std::optional<Type> typeFromName(std::string_view s) {
  if (s == "char" || s == "int8") return Type::kInt8;
  if (s == "uchar" || s == "uint8") return Type::kUint8;
  if (s == "short" || s == "int16") return Type::kInt16;
  if (s == "ushort" || s == "uint16") return Type::kUint16;
  if (s == "int" || s == "int32") return Type::kInt32;
  if (s == "uint" || s == "uint32") return Type::kUint32;
  if (s == "float" || s == "float32") return Type::kFloat;
  if (s == "double" || s == "float64") return Type::kDouble;
  return std::nullopt;
}

std::size_t typeSize(Type t) {
  constexpr std::size_t kSizes[] = {1, 1, 2, 2, 4, 4, 4, 8};  // in Type's order
  return kSizes[static_cast<int>(t)];
}

bool isFloat(Type t) {
  return t == Type::kFloat || t == Type::kDouble;
}

// "'token'" for messages, shortened and with control bytes replaced; "end of file" or
// `ifEmpty` for an empty token.
std::string quoted(std::string_view tok, const char* ifEmpty = "end of file") {
  if (tok.empty()) return ifEmpty;
  std::string out = "'";
  for (char c : tok.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (tok.size() > 40) out += "...";
  return out + "'";
}

[[noreturn]] void failAt(const std::string& name, std::uint64_t line, std::string_view expected,
                         const std::string& got) {
  throw InputError(name + ":" + std::to_string(line) + ": expected " + std::string(expected) +
                   ", got " + got);
}

[[noreturn]] void failBinary(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}

std::optional<std::int64_t> parseInt(std::string_view tok) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  std::int64_t v = 0;
  const auto r = std::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size() || tok.empty()) return std::nullopt;
  return v;
}

std::optional<double> parseReal(std::string_view tok) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  double v = 0;
  const auto r = fast_float::from_chars(tok.data(), tok.data() + tok.size(), v);
  if (r.ec != std::errc() || r.ptr != tok.data() + tok.size() || tok.empty()) return std::nullopt;
  return v;
}

std::uint8_t colorByte(double v, Type t) {
  if (isFloat(t)) v *= 255.0;
  if (!(v > 0.0)) return 0;  // NaN too
  return v >= 255.0 ? 255 : static_cast<std::uint8_t>(std::lround(v));
}

// Splits a header line into at most 6 words (more are counted in `count`).
struct Words {
  std::array<std::string_view, 6> w;
  std::size_t count = 0;
};

Words splitWords(std::string_view line) {
  Words out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) {
      if (out.count < out.w.size()) out.w[out.count] = line.substr(start, i - start);
      ++out.count;
    }
  }
  return out;
}

struct Header {
  Format format = Format::kAscii;
  std::vector<Element> elements;
  std::size_t bodyOffset = 0;
  std::uint64_t bodyLine = 1;  // line number of the first body line (ascii)
};

Header parseHeader(std::string_view bytes, const std::string& name) {
  Header h;
  std::size_t pos = 0;
  std::uint64_t line = 0;
  bool haveFormat = false;
  for (;;) {
    ++line;
    if (pos >= bytes.size())
      failAt(name, line, line == 1 ? "'ply'" : "'end_header'", "end of file");
    const std::size_t nl = bytes.find('\n', pos);
    std::string_view text =
        bytes.substr(pos, nl == std::string_view::npos ? std::string_view::npos : nl - pos);
    pos = nl == std::string_view::npos ? bytes.size() : nl + 1;
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    if (line == 1) {
      if (text != "ply") failAt(name, line, "'ply'", quoted(text, "an empty line"));
      continue;
    }
    const Words ws = splitWords(text);
    if (ws.count == 0) continue;
    const std::string_view key = ws.w[0];
    if (key == "comment" || key == "obj_info") continue;
    if (key == "end_header") {
      if (!haveFormat) failAt(name, line, "a 'format' line", "'end_header'");
      h.bodyOffset = pos;
      h.bodyLine = line + 1;
      return h;
    }
    if (key == "format") {
      if (ws.count != 3) failAt(name, line, "'format <type> 1.0'", quoted(text));
      if (ws.w[1] == "ascii")
        h.format = Format::kAscii;
      else if (ws.w[1] == "binary_little_endian")
        h.format = Format::kLittle;
      else if (ws.w[1] == "binary_big_endian")
        h.format = Format::kBig;
      else
        failAt(name, line, "ascii, binary_little_endian or binary_big_endian", quoted(ws.w[1]));
      if (ws.w[2] != "1.0") failAt(name, line, "version 1.0", quoted(ws.w[2]));
      haveFormat = true;
    } else if (key == "element") {
      if (ws.count != 3) failAt(name, line, "'element <name> <count>'", quoted(text));
      const auto n = parseInt(ws.w[2]);
      if (!n || *n < 0) failAt(name, line, "an element count", quoted(ws.w[2]));
      h.elements.push_back({ws.w[1], static_cast<std::uint64_t>(*n), line, {}});
    } else if (key == "property") {
      if (h.elements.empty()) failAt(name, line, "'element' before 'property'", quoted(text));
      Property p;
      if (ws.count >= 2 && ws.w[1] == "list") {
        if (ws.count != 5) failAt(name, line, "'property list <type> <type> <name>'", quoted(text));
        const auto ct = typeFromName(ws.w[2]);
        const auto it = typeFromName(ws.w[3]);
        if (!ct || isFloat(*ct)) failAt(name, line, "an integer list count type", quoted(ws.w[2]));
        if (!it) failAt(name, line, "a property type", quoted(ws.w[3]));
        p = {ws.w[4], *it, *ct, true, Role::kSkip};
      } else {
        if (ws.count != 3) failAt(name, line, "'property <type> <name>'", quoted(text));
        const auto t = typeFromName(ws.w[1]);
        if (!t) failAt(name, line, "a property type", quoted(ws.w[1]));
        p = {ws.w[2], *t, Type::kUint8, false, Role::kSkip};
      }
      h.elements.back().props.push_back(p);
    } else {
      failAt(name, line, "a header keyword", quoted(key));
    }
  }
}

// Marks the properties the reader uses and checks that the needed ones are there.
void assignRoles(Header& h, const std::string& name, bool& vertexColors, bool& faceColors) {
  bool sawVertex = false, sawFace = false;
  for (Element& e : h.elements) {
    const bool isVertex = e.name == "vertex", isFace = e.name == "face";
    if (!isVertex && !isFace) continue;
    if ((isVertex && sawVertex) || (isFace && sawFace))
      failAt(name, e.line, "one element " + std::string(e.name), "a second one");
    (isVertex ? sawVertex : sawFace) = true;
    int rgb = 0;
    bool xyz[3] = {false, false, false}, indices = false;
    for (Property& p : e.props) {
      const std::string_view n = p.name;
      if (p.isList) {
        if (isFace && !indices && (n == "vertex_indices" || n == "vertex_index")) {
          if (isFloat(p.type)) failAt(name, e.line, "an integer vertex index type", "a float");
          p.role = Role::kIndices;
          indices = true;
        }
        continue;
      }
      Role r = Role::kSkip;
      if (isVertex && n == "x") r = Role::kX;
      if (isVertex && n == "y") r = Role::kY;
      if (isVertex && n == "z") r = Role::kZ;
      if (n == "red" || n == "diffuse_red") r = Role::kRed;
      if (n == "green" || n == "diffuse_green") r = Role::kGreen;
      if (n == "blue" || n == "diffuse_blue") r = Role::kBlue;
      if (n == "alpha" || n == "diffuse_alpha") r = Role::kAlpha;
      if (r >= Role::kX && r <= Role::kZ) {
        bool& seen = xyz[static_cast<int>(r) - static_cast<int>(Role::kX)];
        if (seen) r = Role::kSkip;
        seen = true;
      }
      if (r >= Role::kRed && r <= Role::kBlue) rgb |= 1 << (static_cast<int>(r) - 4);
      p.role = r;
    }
    const bool colors = rgb == 7;
    if (!colors)
      for (Property& p : e.props)
        if (p.role >= Role::kRed && p.role <= Role::kAlpha) p.role = Role::kSkip;
    if (isVertex) {
      if (!xyz[0] || !xyz[1] || !xyz[2])
        failAt(name, e.line, "vertex properties x, y and z", "fewer");
      if (e.count > std::numeric_limits<std::uint32_t>::max())
        failAt(name, e.line, "at most 4294967295 vertices", std::to_string(e.count));
      vertexColors = colors;
    } else {
      if (!indices) failAt(name, e.line, "a face list property vertex_indices", "none");
      faceColors = colors;
    }
  }
}

// Where the vertices and triangles go: a TriangleMesh (readPly) or a PlySink (streamPly).
struct MeshOut {
  TriangleMesh mesh;
  void reserveVertices(std::uint64_t n, bool colors) {
    mesh.positions.reserve(n);
    if (colors) mesh.vertexColors.reserve(n);
  }
  void reserveTriangles(std::uint64_t n) { mesh.indices.reserve(3 * n); }
  void vertex(const glm::vec3& p, const Rgba8* color) {
    mesh.positions.push_back(p);
    if (color) mesh.vertexColors.push_back(*color);
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Rgba8* color) {
    mesh.indices.insert(mesh.indices.end(), {a, b, c});
    if (color) mesh.faceColors.push_back(*color);
  }
};

struct SinkOut {
  PlySink* sink = nullptr;
  void reserveVertices(std::uint64_t, bool) {}
  void reserveTriangles(std::uint64_t) {}
  void vertex(const glm::vec3& p, const Rgba8* color) {
    sink->vertex(p, color ? *color : Rgba8{0, 0, 0, 255});
  }
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Rgba8* color) {
    sink->triangle(a, b, c, color ? *color : Rgba8{0, 0, 0, 255});
  }
};

// The mesh being built, shared by the ascii and binary bodies.
template <typename Out>
struct Builder {
  Out out;
  std::uint64_t vertexCount = 0;  // as declared in the header
  bool vertexColors = false, faceColors = false;
  glm::vec3 pos{0.0f};
  Rgba8 color{0, 0, 0, 255};
  std::vector<std::uint32_t> poly;

  void set(Role r, double v, Type t) {
    switch (r) {
      case Role::kX:
      case Role::kY:
      case Role::kZ:
        pos[static_cast<int>(r) - static_cast<int>(Role::kX)] = static_cast<float>(v);
        break;
      case Role::kRed:
      case Role::kGreen:
      case Role::kBlue:
      case Role::kAlpha:
        color[static_cast<int>(r) - static_cast<int>(Role::kRed)] = colorByte(v, t);
        break;
      default:
        break;
    }
  }
  bool finishVertex() {  // false when a coordinate is not finite
    if (!std::isfinite(pos.x) || !std::isfinite(pos.y) || !std::isfinite(pos.z)) return false;
    out.vertex(pos, vertexColors ? &color : nullptr);
    color = {0, 0, 0, 255};
    return true;
  }
  void finishFace() {  // poly.size() >= 3 checked by the caller
    for (std::size_t k = 1; k + 1 < poly.size(); ++k)
      out.triangle(poly[0], poly[k], poly[k + 1], faceColors ? &color : nullptr);
    color = {0, 0, 0, 255};
  }
};

// The body's bytes: [p, end) in memory; with a file, fill() reads more of it.
struct Window {
  std::size_t chunk = std::size_t{1} << 20;
  const char* p = nullptr;
  const char* end = nullptr;
  std::FILE* file = nullptr;  // null: the whole body is in [p, end)
  const std::string* name = nullptr;
  std::uint64_t fileLeft = 0;  // bytes of the file after `end`
  std::string buffer;

  // Makes [p, p + n) readable; false when the input has fewer bytes left.
  bool fill(std::size_t n) {
    const auto have = static_cast<std::size_t>(end - p);
    if (have >= n) return true;
    if (!file || have + fileLeft < n) return false;
    if (have > 0) std::memmove(buffer.data(), p, have);
    if (buffer.size() < std::max(n, chunk)) buffer.resize(std::max(n, chunk));
    const std::size_t want = static_cast<std::size_t>(std::min<std::uint64_t>(
        fileLeft, std::min(buffer.size() - have, std::max(chunk, n - have))));
    if (std::fread(buffer.data() + have, 1, want, file) != want)
      throw InputError(*name + ": cannot read (the file shrank?)");
    fileLeft -= want;
    p = buffer.data();
    end = p + have + want;
    return true;
  }
  std::uint64_t remaining() const { return static_cast<std::uint64_t>(end - p) + fileLeft; }
};

// ---- ascii body ----

struct Cursor {
  Window& w;
  std::uint64_t line;       // where the scan is
  std::uint64_t tokenLine;  // of the last token read; at the end of the file, of the one before

  // The next token; valid until the next call.
  std::string_view next() {
    for (;;) {
      if (w.p == w.end && !w.fill(1)) break;
      const char c = *w.p;
      if (c == '\n')
        ++line;
      else if (c != ' ' && c != '\t' && c != '\r' && c != '\v' && c != '\f')
        break;
      ++w.p;
    }
    if (w.p != w.end) tokenLine = line;
    std::size_t n = 0;
    for (;;) {
      if (w.p + n == w.end && !w.fill(n + 1)) break;
      const char c = w.p[n];
      if (c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f') break;
      ++n;
    }
    const std::string_view tok(w.p, n);
    w.p += n;
    return tok;
  }
};

template <typename B>
void readAsciiBody(const Header& h, Window& w, const std::string& name, B& b) {
  Cursor c{w, h.bodyLine, h.bodyLine};
  for (const Element& e : h.elements) {
    if (e.props.empty()) continue;  // consumes nothing
    const bool isVertex = e.name == "vertex", isFace = e.name == "face";
    // Each instance needs at least one token and one separator per property, a face three
    // more for its indices.
    const std::uint64_t fit = w.remaining() / (2 * (e.props.size() + (isFace ? 3 : 0))) + 1;
    if (isVertex) b.out.reserveVertices(std::min(e.count, fit), b.vertexColors);
    if (isFace) b.out.reserveTriangles(std::min(e.count, fit));
    const std::string what = isVertex ? "a vertex" : isFace ? "a face" : "an element";
    for (std::uint64_t i = 0; i < e.count; ++i) {
      if (isFace) b.poly.clear();
      for (const Property& p : e.props) {
        std::string_view tok = c.next();
        if (tok.empty()) failAt(name, c.tokenLine, what + " value", "end of file");
        if (p.isList) {
          const auto n = parseInt(tok);
          if (!n || *n < 0) failAt(name, c.tokenLine, "a list count", quoted(tok));
          for (std::int64_t k = 0; k < *n; ++k) {
            tok = c.next();
            if (tok.empty()) failAt(name, c.tokenLine, "a list item", "end of file");
            if (p.role != Role::kIndices) continue;
            const auto v = parseInt(tok);
            if (!v || *v < 0 || static_cast<std::uint64_t>(*v) >= b.vertexCount)
              failAt(name, c.tokenLine, "a vertex index below " + std::to_string(b.vertexCount),
                     quoted(tok));
            b.poly.push_back(static_cast<std::uint32_t>(*v));
          }
          if (p.role == Role::kIndices && *n < 3)
            failAt(name, c.tokenLine, "at least 3 vertex indices", std::to_string(*n));
        } else if (p.role != Role::kSkip) {
          std::optional<double> v;
          if (isFloat(p.type))
            v = parseReal(tok);
          else if (const auto iv = parseInt(tok))
            v = static_cast<double>(*iv);
          if (!v)
            failAt(name, c.tokenLine, isFloat(p.type) ? "a number" : "an integer", quoted(tok));
          b.set(p.role, *v, p.type);
        }
      }
      if (isVertex && !b.finishVertex())
        failAt(name, c.tokenLine, "finite coordinates", "NaN or inf");
      if (isFace) b.finishFace();
    }
  }
}

// ---- binary body ----

template <bool kBig, typename T>
T load(const char* p) {
  T v;
  std::memcpy(&v, p, sizeof v);
  if constexpr (kBig != (std::endian::native == std::endian::big)) {
    if constexpr (sizeof(T) == 4 && std::is_floating_point_v<T>)
      v = std::bit_cast<T>(base::byteSwap(std::bit_cast<std::uint32_t>(v)));
    else if constexpr (sizeof(T) == 8 && std::is_floating_point_v<T>)
      v = std::bit_cast<T>(base::byteSwap(std::bit_cast<std::uint64_t>(v)));
    else
      v = base::byteSwap(v);
  }
  return v;
}

template <bool kBig>
double loadScalar(const char* p, Type t) {
  switch (t) {
    case Type::kInt8:
      return load<kBig, std::int8_t>(p);
    case Type::kUint8:
      return load<kBig, std::uint8_t>(p);
    case Type::kInt16:
      return load<kBig, std::int16_t>(p);
    case Type::kUint16:
      return load<kBig, std::uint16_t>(p);
    case Type::kInt32:
      return load<kBig, std::int32_t>(p);
    case Type::kUint32:
      return load<kBig, std::uint32_t>(p);
    case Type::kFloat:
      return load<kBig, float>(p);
    case Type::kDouble:
      return load<kBig, double>(p);
  }
  return 0;
}

// Integer types only (doubles hold every 32-bit integer exactly).
template <bool kBig>
std::int64_t loadInt(const char* p, Type t) {
  return static_cast<std::int64_t>(loadScalar<kBig>(p, t));
}

template <bool kBig, typename B>
void readBinaryBody(const Header& h, Window& w, const std::string& name, B& b) {
  auto need = [&](std::uint64_t n, const Element& e, std::uint64_t i) {
    if (n > w.remaining() || !w.fill(static_cast<std::size_t>(n)))
      failBinary(name, "data ends inside " + std::string(e.name) + " " + std::to_string(i) +
                           " of " + std::to_string(e.count));
  };
  for (const Element& e : h.elements) {
    std::uint64_t minBytes = 0;
    for (const Property& prop : e.props)
      minBytes += typeSize(prop.isList ? prop.countType : prop.type);
    if (minBytes == 0) continue;  // no properties: consumes nothing
    const std::uint64_t left = w.remaining();
    if (e.count > left / minBytes)
      failBinary(name, "element " + std::string(e.name) + " claims " + std::to_string(e.count) +
                           " entries of at least " + std::to_string(minBytes) + " bytes but only " +
                           std::to_string(left) + " bytes remain");
    const bool isVertex = e.name == "vertex", isFace = e.name == "face";
    if (isVertex) b.out.reserveVertices(e.count, b.vertexColors);
    if (isFace) {  // a face needs at least 3 indices
      std::uint64_t faceBytes = minBytes;
      for (const Property& prop : e.props)
        if (prop.role == Role::kIndices) faceBytes += 3 * typeSize(prop.type);
      b.out.reserveTriangles(std::min(e.count, left / faceBytes));
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      if (isFace) b.poly.clear();
      for (const Property& prop : e.props) {
        if (prop.isList) {
          need(typeSize(prop.countType), e, i);
          const std::int64_t n = loadInt<kBig>(w.p, prop.countType);
          w.p += typeSize(prop.countType);
          const std::size_t size = typeSize(prop.type);
          if (n < 0)
            failBinary(name,
                       std::string(e.name) + " " + std::to_string(i) + ": negative list count");
          if (static_cast<std::uint64_t>(n) > w.remaining() / size)
            need(std::numeric_limits<std::uint64_t>::max(), e, i);
          need(static_cast<std::uint64_t>(n) * size, e, i);
          if (prop.role == Role::kIndices) {
            if (n < 3)
              failBinary(name, "face " + std::to_string(i) +
                                   ": expected at least 3 vertex indices, got " +
                                   std::to_string(n));
            for (std::int64_t k = 0; k < n; ++k, w.p += size) {
              const std::int64_t v = loadInt<kBig>(w.p, prop.type);
              if (v < 0 || static_cast<std::uint64_t>(v) >= b.vertexCount)
                failBinary(name, "face " + std::to_string(i) + ": vertex index " +
                                     std::to_string(v) + " is out of range (" +
                                     std::to_string(b.vertexCount) + " vertices)");
              b.poly.push_back(static_cast<std::uint32_t>(v));
            }
          } else {
            w.p += static_cast<std::size_t>(n) * size;
          }
        } else {
          const std::size_t size = typeSize(prop.type);
          need(size, e, i);
          if (prop.role != Role::kSkip)
            b.set(prop.role, loadScalar<kBig>(w.p, prop.type), prop.type);
          w.p += size;
        }
      }
      if (isVertex && !b.finishVertex())
        failBinary(name, "vertex " + std::to_string(i) + " has a coordinate that is NaN or inf");
      if (isFace) b.finishFace();
    }
  }
}

// The body, after assignRoles set b's colour flags.
template <typename B>
void readBody(const Header& h, Window& w, const std::string& name, B& b) {
  for (const Element& e : h.elements)
    if (e.name == "vertex") b.vertexCount = e.count;
  if (h.format == Format::kAscii)
    readAsciiBody(h, w, name, b);
  else if (h.format == Format::kLittle)
    readBinaryBody<false>(h, w, name, b);
  else
    readBinaryBody<true>(h, w, name, b);
}

}  // namespace

TriangleMesh readPly(std::string_view bytes, const std::string& name) {
  Header h = parseHeader(bytes, name);
  Builder<MeshOut> b;
  assignRoles(h, name, b.vertexColors, b.faceColors);
  Window w;
  w.p = bytes.data() + h.bodyOffset;
  w.end = bytes.data() + bytes.size();
  readBody(h, w, name, b);
  return std::move(b.out.mesh);
}

void streamPly(const std::string& path, PlySink& sink, std::size_t chunkBytes) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path.c_str(), "rb"),
                                                       &std::fclose);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(path, ec);
  if (!file || ec) throw InputError("cannot open '" + path + "'");
  // The header: whole lines up to the one whose first word is end_header (parseHeader's
  // rule), read in pieces of at most 64 KiB, at most 16 MiB.
  std::string head;
  std::size_t scanned = 0;
  for (bool done = false; !done;) {
    if (head.size() > (std::size_t{16} << 20))
      throw InputError(path + ": the PLY header is longer than 16 MiB");
    const std::size_t at = head.size();
    const std::size_t piece = std::clamp<std::size_t>(chunkBytes, 1, 65536);
    head.resize(at + piece);
    head.resize(at + std::fread(head.data() + at, 1, piece, file.get()));
    if (head.size() >= 2 && static_cast<unsigned char>(head[0]) == 0x1f &&
        static_cast<unsigned char>(head[1]) == 0x8b)
      throw InputError(path + ": a gzip-compressed PLY cannot be streamed (gunzip it first)");
    const bool eof = head.size() == at;
    for (std::size_t nl; !done && (nl = head.find('\n', scanned)) != std::string::npos;
         scanned = nl + 1) {
      std::string_view line = std::string_view(head).substr(scanned, nl - scanned);
      if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
      done = splitWords(line).w[0] == "end_header";
    }
    if (eof) break;  // parseHeader reports what is missing
  }
  Header h = parseHeader(head, path);
  PlyLayout layout;
  for (const Element& e : h.elements) {
    if (e.name == "vertex") layout.vertexCount = e.count;
    if (e.name == "face") layout.faceCount = e.count;
  }
  Builder<SinkOut> b;
  b.out.sink = &sink;
  Window w;
  w.p = head.data() + h.bodyOffset;
  w.end = head.data() + head.size();
  w.file = file.get();
  w.name = &path;
  w.fileLeft = size > head.size() ? size - head.size() : 0;
  w.chunk = std::max<std::size_t>(1, chunkBytes);
  w.buffer.assign(w.p, w.end);  // the body's first bytes leave `head`, which the header needs
  w.p = w.buffer.data();
  w.end = w.p + w.buffer.size();
  assignRoles(h, path, b.vertexColors, b.faceColors);
  layout.vertexColors = b.vertexColors;
  layout.faceColors = b.faceColors;
  sink.begin(layout);
  readBody(h, w, path, b);
}

}  // namespace gs::formats
