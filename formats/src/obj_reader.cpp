// Wavefront OBJ reader (geometry only): see mesh_readers.hpp.
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fast_float/fast_float.h>

#include "formats/mesh_readers.hpp"

namespace gs::formats {
namespace {

// "'token'" for messages, shortened and with control bytes replaced.
std::string quoted(std::string_view tok) {
  if (tok.empty()) return "end of line";
  std::string out = "'";
  for (char c : tok.substr(0, 40)) out += (c >= 32 && c < 127) ? c : '?';
  if (tok.size() > 40) out += "...";
  return out + "'";
}

// The words of one line; a word starting with '#' ends the line.
struct Words {
  const char* p;
  const char* end;

  std::string_view next() {
    while (p != end && (*p == ' ' || *p == '\t' || *p == '\r' || *p == '\v' || *p == '\f')) ++p;
    if (p != end && *p == '#') p = end;
    const char* start = p;
    while (p != end && *p != ' ' && *p != '\t' && *p != '\r' && *p != '\v' && *p != '\f') ++p;
    return {start, static_cast<std::size_t>(p - start)};
  }
};

bool parseReal(std::string_view tok, float& out) {
  if (!tok.empty() && tok[0] == '+') tok.remove_prefix(1);
  const auto r = fast_float::from_chars(tok.data(), tok.data() + tok.size(), out);
  return !tok.empty() && r.ec == std::errc() && r.ptr == tok.data() + tok.size();
}

std::uint8_t colorByte(float v) {
  if (!(v > 0.0f)) return 0;  // NaN too
  return v >= 1.0f ? 255 : static_cast<std::uint8_t>(std::lround(v * 255.0f));
}

class ObjReader {
 public:
  ObjReader(std::string_view bytes, const std::string& name) : bytes_(bytes), name_(name) {}

  TriangleMesh read() {
    std::size_t pos = bytes_.starts_with("\xEF\xBB\xBF") ? 3 : 0;  // a UTF-8 byte order mark
    while (pos < bytes_.size()) {
      ++line_;
      const void* nl = std::memchr(bytes_.data() + pos, '\n', bytes_.size() - pos);
      const std::size_t stop =
          nl ? static_cast<std::size_t>(static_cast<const char*>(nl) - bytes_.data())
             : bytes_.size();
      Words w{bytes_.data() + pos, bytes_.data() + stop};
      pos = stop + 1;
      const std::string_view key = w.next();
      if (key == "v")
        vertex(w);
      else if (key == "f")
        face(w);
      // Everything else (vt, vn, g, o, s, usemtl, mtllib, l, p, comments) is ignored.
    }
    for (const auto& [index, line] : forward_)
      if (index >= mesh_.positions.size())
        fail(line, "a vertex index of at most " + std::to_string(mesh_.positions.size()),
             std::to_string(index + 1));
    return std::move(mesh_);
  }

 private:
  [[noreturn]] void fail(std::uint64_t line, const std::string& expected,
                         const std::string& got) const {
    throw InputError(name_ + ":" + std::to_string(line) + ": expected " + expected + ", got " +
                     got);
  }

  void vertex(Words& w) {
    float v[8];
    int n = 0;
    for (std::string_view tok = w.next(); !tok.empty(); tok = w.next()) {
      if (n == 7) fail(line_, "at most 7 numbers after 'v'", "more");
      if (!parseReal(tok, v[n])) fail(line_, "a number", quoted(tok));
      ++n;
    }
    if (n < 3) fail(line_, "3 coordinates after 'v'", std::to_string(n));
    if (n == 5) fail(line_, "3, 4, 6 or 7 numbers after 'v'", "5");
    if (!std::isfinite(v[0]) || !std::isfinite(v[1]) || !std::isfinite(v[2]))
      fail(line_, "finite coordinates", "NaN or inf");
    if (mesh_.positions.size() >= std::numeric_limits<std::uint32_t>::max())
      fail(line_, "at most 4294967295 vertices", "more");
    if (n >= 6) {
      if (mesh_.vertexColors.size() < mesh_.positions.size())
        mesh_.vertexColors.resize(mesh_.positions.size(), mesh_.baseColor);
      mesh_.vertexColors.push_back(
          {colorByte(v[3]), colorByte(v[4]), colorByte(v[5]), n == 7 ? colorByte(v[6]) : 255});
    } else if (!mesh_.vertexColors.empty()) {
      mesh_.vertexColors.push_back(mesh_.baseColor);
    }
    mesh_.positions.push_back({v[0], v[1], v[2]});
  }

  void face(Words& w) {
    poly_.clear();
    const std::uint64_t have = mesh_.positions.size();
    for (std::string_view tok = w.next(); !tok.empty(); tok = w.next()) {
      // i, i/t, i//n or i/t/n: only i matters.
      const std::string_view first = tok.substr(0, tok.find('/'));
      std::int64_t i = 0;
      const auto r = std::from_chars(first.data(), first.data() + first.size(), i);
      if (first.empty() || r.ec != std::errc() || r.ptr != first.data() + first.size())
        fail(line_, "a vertex index", quoted(tok));
      std::uint64_t index = 0;
      if (i > 0) {
        index = static_cast<std::uint64_t>(i) - 1;
        if (index >= std::numeric_limits<std::uint32_t>::max())
          fail(line_, "a vertex index below 4294967296", quoted(tok));
        if (index >= have) forward_.emplace_back(index, line_);  // checked at the end
      } else if (i < 0) {
        if (static_cast<std::uint64_t>(-(i + 1)) >= have)
          fail(line_, "a relative index within the " + std::to_string(have) + " vertices so far",
               quoted(tok));
        index = have - static_cast<std::uint64_t>(-(i + 1)) - 1;
      } else {
        fail(line_, "a non-zero vertex index", quoted(tok));
      }
      poly_.push_back(static_cast<std::uint32_t>(index));
    }
    if (poly_.size() < 3) fail(line_, "at least 3 vertex indices", std::to_string(poly_.size()));
    for (std::size_t k = 1; k + 1 < poly_.size(); ++k)
      mesh_.indices.insert(mesh_.indices.end(), {poly_[0], poly_[k], poly_[k + 1]});
  }

  std::string_view bytes_;
  const std::string& name_;
  std::uint64_t line_ = 0;
  TriangleMesh mesh_;
  std::vector<std::uint32_t> poly_;
  std::vector<std::pair<std::uint64_t, std::uint64_t>>
      forward_;  // indices past the vertices so far
};

}  // namespace

TriangleMesh readObj(std::string_view bytes, const std::string& name) {
  return ObjReader(bytes, name).read();
}

}  // namespace gs::formats
