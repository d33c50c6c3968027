// Helpers shared by the splat scene readers (reader_support.hpp).
#include "reader_support.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <limits>

#include "base/byte_order.hpp"

namespace gs::splats::detail {

void fail(std::string_view name, const std::string& what) {
  throw FormatError(std::string(name) + ": " + what);
}

void checkCount(std::string_view name, std::uint64_t count, std::uint64_t recordBytes,
                std::uint64_t have, const char* what) {
  if (count > kMaxSplats)
    fail(name, std::to_string(count) + " splats exceed the limit of " + std::to_string(kMaxSplats));
  // count <= 2^28 and recordBytes is small for every caller; still guard the product.
  if (recordBytes != 0 && count > std::numeric_limits<std::uint64_t>::max() / recordBytes)
    fail(name, "size of " + std::string(what) + " overflows");
  const std::uint64_t need = count * recordBytes;
  if (need > have)
    fail(name, "expected " + std::to_string(need) + " bytes of " + what + ", got " +
                   std::to_string(have));
}

float toFloat(double v) {
  constexpr double kMax = std::numeric_limits<float>::max();
  return std::isnan(v) ? std::numeric_limits<float>::quiet_NaN()
                       : static_cast<float>(std::clamp(v, -kMax, kMax));
}

int shDegreeForRest(std::size_t restPerChannel) {
  for (int d = 0; d <= kMaxShDegree; ++d)
    if (restPerChannel == static_cast<std::size_t>(shCoefficients(d) - 1)) return d;
  return -1;
}

glm::quat unitQuat(float w, float x, float y, float z) {
  const float len = std::sqrt(w * w + x * x + y * y + z * z);
  if (!(len > 0.0f) || !std::isfinite(len)) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  return glm::quat(w / len, x / len, y / len, z / len);
}

void allocate(GaussianCloud& cloud, std::size_t count, int degree) {
  cloud.shDegree = degree;
  cloud.resize(count);
}

void setChannelMajorRest(GaussianCloud& cloud, std::size_t i, const float* rest) {
  const std::size_t n = static_cast<std::size_t>(cloud.shRestPerSplat());
  glm::vec3* out = cloud.shRest.data() + i * n;
  for (std::size_t k = 0; k < n; ++k) out[k] = glm::vec3(rest[k], rest[n + k], rest[2 * n + k]);
}

std::size_t plyTypeSize(PlyType t) {
  switch (t) {
    case PlyType::i8:
    case PlyType::u8:
      return 1;
    case PlyType::i16:
    case PlyType::u16:
      return 2;
    case PlyType::i32:
    case PlyType::u32:
    case PlyType::f32:
      return 4;
    case PlyType::f64:
      return 8;
  }
  return 1;
}

int PlyElement::find(std::string_view property) const {
  for (std::size_t i = 0; i < properties.size(); ++i)
    if (properties[i].name == property) return static_cast<int>(i);
  return -1;
}

const PlyElement* PlyHeader::find(std::string_view element) const {
  for (const PlyElement& e : elements)
    if (e.name == element) return &e;
  return nullptr;
}

namespace {

bool parseType(std::string_view word, PlyType& t) {
  struct Name {
    std::string_view a, b;
    PlyType t;
  };
  static constexpr Name kNames[] = {
      {"char", "int8", PlyType::i8},      {"uchar", "uint8", PlyType::u8},
      {"short", "int16", PlyType::i16},   {"ushort", "uint16", PlyType::u16},
      {"int", "int32", PlyType::i32},     {"uint", "uint32", PlyType::u32},
      {"float", "float32", PlyType::f32}, {"double", "float64", PlyType::f64}};
  for (const Name& n : kNames)
    if (word == n.a || word == n.b) {
      t = n.t;
      return true;
    }
  return false;
}

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const std::size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

}  // namespace

bool parsePlyHeader(std::string_view bytes, PlyHeader& header, std::string& error) {
  header = PlyHeader{};
  const std::string_view text = bytes.substr(0, std::min<std::size_t>(bytes.size(), 1u << 20));
  if (text.substr(0, 3) != "ply" || text.size() < 4 || (text[3] != '\n' && text[3] != '\r')) {
    error = "not a PLY file (no 'ply' line)";
    return false;
  }
  bool haveFormat = false;
  std::size_t pos = 0;
  bool first = true;
  while (true) {
    const std::size_t end = text.find('\n', pos);
    if (end == std::string_view::npos) {
      error = "missing end_header";
      return false;
    }
    std::string_view line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos = end + 1;
    if (first) {
      first = false;
      continue;  // "ply"
    }
    const std::vector<std::string_view> w = words(line);
    if (w.empty() || w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "end_header") break;
    if (w[0] == "format") {
      if (w.size() < 2) {
        error = "bad format line";
        return false;
      }
      if (w[1] == "ascii")
        header.format = PlyFormat::ascii;
      else if (w[1] == "binary_little_endian")
        header.format = PlyFormat::binaryLittleEndian;
      else if (w[1] == "binary_big_endian")
        header.format = PlyFormat::binaryBigEndian;
      else {
        error = "unknown format '" + std::string(w[1]) + "'";
        return false;
      }
      haveFormat = true;
    } else if (w[0] == "element") {
      if (w.size() != 3) {
        error = "bad element line";
        return false;
      }
      PlyElement e;
      e.name = std::string(w[1]);
      const auto r = std::from_chars(w[2].data(), w[2].data() + w[2].size(), e.count);
      if (r.ec != std::errc{} || r.ptr != w[2].data() + w[2].size()) {
        error = "bad element count '" + std::string(w[2]) + "'";
        return false;
      }
      header.elements.push_back(std::move(e));
    } else if (w[0] == "property") {
      if (header.elements.empty()) {
        error = "property before any element";
        return false;
      }
      PlyElement& e = header.elements.back();
      PlyProperty p;
      if (w.size() == 5 && w[1] == "list") {
        if (!parseType(w[2], p.countType) || !parseType(w[3], p.type)) {
          error = "bad list property types";
          return false;
        }
        p.isList = true;
        p.name = std::string(w[4]);
        e.hasList = true;
      } else if (w.size() == 3) {
        if (!parseType(w[1], p.type)) {
          error = "unknown property type '" + std::string(w[1]) + "'";
          return false;
        }
        p.name = std::string(w[2]);
      } else {
        error = "bad property line";
        return false;
      }
      if (e.properties.size() >= 4096) {
        error = "too many properties";
        return false;
      }
      p.offset = e.rowBytes;
      if (!p.isList) e.rowBytes += plyTypeSize(p.type);
      e.properties.push_back(std::move(p));
    } else {
      error = "unknown header line '" + std::string(w[0]) + "'";
      return false;
    }
  }
  if (!haveFormat) {
    error = "missing format line";
    return false;
  }
  header.dataOffset = pos;
  return true;
}

double plyValue(const char* p, PlyType t, bool bigEndian) {
  auto load = [&]<typename T>(T) {
    T v = base::loadLe<T>(p);
    if (bigEndian) v = base::byteSwap(v);
    return v;
  };
  switch (t) {
    case PlyType::i8:
      return static_cast<std::int8_t>(*p);
    case PlyType::u8:
      return static_cast<std::uint8_t>(*p);
    case PlyType::i16:
      return static_cast<std::int16_t>(load(std::uint16_t{}));
    case PlyType::u16:
      return load(std::uint16_t{});
    case PlyType::i32:
      return static_cast<std::int32_t>(load(std::uint32_t{}));
    case PlyType::u32:
      return load(std::uint32_t{});
    case PlyType::f32:
      return std::bit_cast<float>(load(std::uint32_t{}));
    case PlyType::f64:
      return std::bit_cast<double>(load(std::uint64_t{}));
  }
  return 0.0;
}

void checkRows(std::uint64_t first, std::size_t n, std::uint64_t count) {
  if (first > count || n > count - first)
    throw FormatError("rows " + std::to_string(first) + " to " + std::to_string(first + n) +
                      " lie past the scene's " + std::to_string(count) + " splats");
}

std::uint64_t plyElementOffset(std::uint64_t fileBytes, std::string_view name,
                               const PlyHeader& header, const PlyElement& element) {
  std::uint64_t offset = header.dataOffset;
  for (const PlyElement& e : header.elements) {
    if (&e == &element) break;
    if (e.hasList)
      fail(name, "element '" + e.name + "' with a list property precedes '" + element.name + "'");
    // Earlier elements must fit in the file too (count * rowBytes bounded by the bytes).
    checkCount(name, e.count, e.rowBytes, fileBytes - std::min(offset, fileBytes),
               ("element '" + e.name + "'").c_str());
    offset += e.count * e.rowBytes;
  }
  if (element.hasList) fail(name, "element '" + element.name + "' has a list property");
  const std::uint64_t have = fileBytes - std::min(offset, fileBytes);
  checkCount(name, element.count, element.rowBytes, have,
             ("element '" + element.name + "'").c_str());
  return offset;
}

std::size_t plyElementOffset(std::string_view bytes, std::string_view name, const PlyHeader& header,
                             const PlyElement& element) {
  return static_cast<std::size_t>(plyElementOffset(bytes.size(), name, header, element));
}

PieceFile::PieceFile(const std::string& path) : path_(path) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd_ < 0 || ::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode))
    fail(path, std::string("cannot open: ") + (fd_ < 0 ? std::strerror(errno) : "not a file"));
  size_ = static_cast<std::uint64_t>(st.st_size);
}

PieceFile::~PieceFile() {
  if (fd_ >= 0) ::close(fd_);
}

void PieceFile::read(std::uint64_t offset, char* out, std::size_t bytes) const {
  for (std::size_t done = 0; done < bytes;) {
    const ssize_t n = ::pread(fd_, out + done, bytes - done, static_cast<off_t>(offset + done));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) fail(path_, std::string("cannot read: ") + std::strerror(errno));
    if (n == 0)
      fail(path_, "expected " + std::to_string(bytes) + " bytes at byte " + std::to_string(offset) +
                      ", got " + std::to_string(done));
    done += static_cast<std::size_t>(n);
  }
}

std::string PieceFile::head(std::size_t max) const {
  std::string bytes(static_cast<std::size_t>(std::min<std::uint64_t>(size_, max)), '\0');
  read(0, bytes.data(), bytes.size());
  return bytes;
}

}  // namespace gs::splats::detail
