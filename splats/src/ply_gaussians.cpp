// The INRIA 3D Gaussian splatting .ply (Kerbl et al. 2023's output; readers.hpp): one
// vertex element with x y z, f_dc_0..2, f_rest_* (channel-major), opacity (logit),
// scale_0..2 (log) and rot_0..3 (w x y z). Binary (either byte order) or ascii. Read in
// the file's own axes, as splat-transform holds a .ply (Transform.PLY, no conversion).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "reader_support.hpp"

namespace gs::splats {

namespace {

using detail::fail;
using detail::PlyElement;
using detail::PlyHeader;

/// The columns of a Gaussian vertex element: property indices, -1 where absent.
struct Columns {
  int pos[3], dc[3], scale[3], rot[4], opacity;
  std::vector<int> rest;  // channel-major f_rest_0..f_rest_(3n-1)
  int degree = 0;
};

Columns findColumns(std::string_view name, const PlyElement& v) {
  Columns c{};
  auto need = [&](const char* property) {
    const int i = v.find(property);
    if (i < 0) fail(name, std::string("property '") + property + "' missing");
    return i;
  };
  const char* pos[] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) c.pos[k] = need(pos[k]);
  for (int k = 0; k < 3; ++k) c.dc[k] = need(("f_dc_" + std::to_string(k)).c_str());
  for (int k = 0; k < 2; ++k) c.scale[k] = need(("scale_" + std::to_string(k)).c_str());
  c.scale[2] = v.find("scale_2");  // absent: a 2DGS surfel (splat-transform's reading: flat)
  for (int k = 0; k < 4; ++k) c.rot[k] = need(("rot_" + std::to_string(k)).c_str());
  c.opacity = need("opacity");
  // f_rest_0 .. f_rest_(N-1), N = 3 * (0, 3, 8 or 15), every one present.
  long highest = -1;
  for (const auto& p : v.properties) {
    if (p.name.rfind("f_rest_", 0) != 0) continue;
    long k = -1;
    const char* b = p.name.data() + 7;
    const char* e = p.name.data() + p.name.size();
    const auto r = std::from_chars(b, e, k);
    if (r.ec != std::errc{} || r.ptr != e || k < 0 || k > 1000)
      fail(name, "bad property name '" + p.name + "'");
    highest = std::max(highest, k);
  }
  const std::size_t total = static_cast<std::size_t>(highest + 1);
  c.degree = total % 3 == 0 ? detail::shDegreeForRest(total / 3) : -1;
  if (c.degree < 0)
    fail(name, "expected 0, 9, 24 or 45 f_rest properties, got " + std::to_string(total));
  for (std::size_t k = 0; k < total; ++k)
    c.rest.push_back(need(("f_rest_" + std::to_string(k)).c_str()));
  for (const auto& p : v.properties)
    if (p.isList) fail(name, "vertex property '" + p.name + "' is a list");
  return c;
}

/// Splat i from `value(i, propertyIndex)`.
template <typename Value>
void fill(GaussianCloud& cloud, const Columns& c, std::size_t count, Value&& value) {
  std::vector<float> rest(c.rest.size());
  for (std::size_t i = 0; i < count; ++i) {
    auto f = [&](int column) { return detail::toFloat(value(i, column)); };
    cloud.positions[i] = glm::vec3(f(c.pos[0]), f(c.pos[1]), f(c.pos[2]));
    cloud.shDc[i] = glm::vec3(f(c.dc[0]), f(c.dc[1]), f(c.dc[2]));
    cloud.scales[i] = glm::vec3(std::exp(f(c.scale[0])), std::exp(f(c.scale[1])),
                                c.scale[2] >= 0 ? std::exp(f(c.scale[2])) : 0.0f);
    cloud.rotations[i] = detail::unitQuat(f(c.rot[0]), f(c.rot[1]), f(c.rot[2]), f(c.rot[3]));
    cloud.opacities[i] = sigmoid(f(c.opacity));
    if (!rest.empty()) {
      for (std::size_t k = 0; k < rest.size(); ++k) rest[k] = f(c.rest[k]);
      detail::setChannelMajorRest(cloud, i, rest.data());
    }
  }
}

/// The values of `element`'s records in an ascii PLY, row-major; `pos` is where its first
/// line starts and moves past its last.
std::vector<double> asciiValues(std::string_view bytes, std::string_view name, std::size_t& pos,
                                const PlyElement& element, bool keep) {
  // Every record is a line of at least one value and a separator: 2 bytes or more.
  detail::checkCount(name, element.count, 2, bytes.size() - std::min(pos, bytes.size()),
                     ("ascii element '" + element.name + "'").c_str());
  std::vector<double> values;
  if (keep) {
    detail::checkCount(name, element.count, 2 * element.properties.size(),
                       bytes.size() - std::min(pos, bytes.size()),
                       ("ascii element '" + element.name + "'").c_str());
    values.reserve(element.count * element.properties.size());
  }
  for (std::uint64_t r = 0; r < element.count; ++r) {
    const std::size_t end = std::min(bytes.find('\n', pos), bytes.size());
    if (pos >= bytes.size())
      fail(name, "expected " + std::to_string(element.count) + " ascii records of element '" +
                     element.name + "', got " + std::to_string(r));
    if (keep) {
      const char* p = bytes.data() + pos;
      const char* e = bytes.data() + end;
      std::size_t n = 0;
      while (true) {
        while (p < e && (*p == ' ' || *p == '\t' || *p == '\r')) ++p;
        if (p == e) break;
        double v = 0.0;
        const auto res = std::from_chars(p, e, v);
        if (res.ec != std::errc{})
          fail(name,
               "bad number in record " + std::to_string(r) + " of element '" + element.name + "'");
        p = res.ptr;
        if (++n > element.properties.size()) break;
        values.push_back(v);
      }
      if (n != element.properties.size())
        fail(name, "expected " + std::to_string(element.properties.size()) + " values in record " +
                       std::to_string(r) + ", got " + std::to_string(n));
    }
    pos = end + 1;
  }
  return values;
}

/// The rows of a binary INRIA .ply's vertex element, decoded.
class PlyRowDecoder final : public GaussianRowDecoder {
 public:
  /// Throws FormatError naming `name` for what readPlyGaussians refuses in the header; the
  /// vertex element must lie within `fileBytes` (the file's size, or the most it may be).
  PlyRowDecoder(const PlyHeader& header, const std::string& name, std::uint64_t fileBytes)
      : header_(header) {
    const PlyElement* vertex = header_.find("vertex");
    if (!vertex) fail(name, "no vertex element");
    if (vertex->count == 0) fail(name, "expected at least one splat, got 0");
    if (vertex->count > kMaxSplats)
      fail(name, std::to_string(vertex->count) + " splats exceed the limit of " +
                     std::to_string(kMaxSplats));
    columns_ = findColumns(name, *vertex);
    vertex_ = vertex;
    offset_ = detail::plyElementOffset(fileBytes, name, header_, *vertex);
  }
  std::uint64_t dataOffset() const override { return offset_; }
  std::size_t rowBytes() const override { return vertex_->rowBytes; }
  std::uint64_t size() const override { return vertex_->count; }
  int shDegree() const override { return columns_.degree; }
  void decode(const char* rows, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, size());
    batch = GaussianCloud{};
    detail::allocate(batch, n, columns_.degree);
    const bool bigEndian = header_.format == detail::PlyFormat::binaryBigEndian;
    const auto& props = vertex_->properties;
    const std::size_t rowBytes = vertex_->rowBytes;
    fill(batch, columns_, n, [&](std::size_t i, int col) {
      const auto& p = props[static_cast<std::size_t>(col)];
      return detail::plyValue(rows + i * rowBytes + p.offset, p.type, bigEndian);
    });
  }

 private:
  PlyHeader header_;
  const PlyElement* vertex_ = nullptr;
  Columns columns_;
  std::uint64_t offset_ = 0;
};

/// A binary INRIA .ply read a batch of rows at a time.
class PlyGaussianBatches final : public GaussianBatchReader {
 public:
  PlyGaussianBatches(const std::string& path, const PlyHeader& header)
      : file_(path), rows_(header, path, file_.size()) {}
  std::uint64_t size() const override { return rows_.size(); }
  int shDegree() const override { return rows_.shDegree(); }
  std::size_t rowBytes() const override { return rows_.rowBytes(); }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, size() - next_));
    bytes_.resize(n * rowBytes());
    file_.read(rows_.dataOffset() + next_ * rowBytes(), bytes_.data(), bytes_.size());
    next_ += n;
    rows_.decode(bytes_.data(), next_ - n, n, batch);
    return n;
  }
  void rewind() override { next_ = 0; }

 private:
  detail::PieceFile file_;
  PlyRowDecoder rows_;
  std::uint64_t next_ = 0;
  std::vector<char> bytes_;
};

/// A .splat's 32-byte rows, decoded.
class SplatRowDecoder final : public GaussianRowDecoder {
 public:
  explicit SplatRowDecoder(std::uint64_t count) : count_(count) {}
  std::uint64_t dataOffset() const override { return 0; }
  std::size_t rowBytes() const override { return 32; }
  std::uint64_t size() const override { return count_; }
  int shDegree() const override { return 0; }
  void decode(const char* rows, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, count_);
    batch = n == 0 ? GaussianCloud{} : readSplatGaussians(std::string_view(rows, n * 32), ".splat");
  }

 private:
  std::uint64_t count_;
};

}  // namespace

std::unique_ptr<GaussianBatchReader> openPlyGaussianBatches(const std::string& path) {
  const detail::PieceFile file(path);
  const std::string head = file.head();
  PlyHeader header;
  std::string error;
  if (!detail::parsePlyHeader(head, header, error)) fail(path, error);
  // A packed vertex element is PlayCanvas's, as readPlyGaussians reads it.
  if (const PlyElement* vertex = header.find("vertex");
      vertex && vertex->find("packed_position") >= 0)
    return openCompressedPlyGaussianBatches(path);
  if (header.format == detail::PlyFormat::ascii)
    throw NotPiecewiseError(path + ": " + detail::kPiecewiseFormats + ", not an ascii PLY");
  return std::make_unique<PlyGaussianBatches>(path, header);
}

GaussianRows openGaussianRows(std::string_view head, const std::string& name,
                              std::uint64_t fileBytes) {
  GaussianRows r;
  if (!head.starts_with("ply") && detectSplatFormat(head, name) == SplatFormat::splat) {
    if (fileBytes == 0 || fileBytes % 32 != 0 || fileBytes > 32 * std::uint64_t{kMaxSplats})
      return r;  // not known, or not whole rows: read whole, where the reader says why
    r.decoder = std::make_unique<SplatRowDecoder>(fileBytes / 32);
    return r;
  }
  if (!head.starts_with("ply")) return r;
  if (head.find("end_header") == std::string_view::npos) {
    r.needMore = head.size() < (1u << 20);  // parsePlyHeader reads up to 1 MiB
    return r;
  }
  PlyHeader header;
  std::string error;
  if (!detail::parsePlyHeader(head, header, error)) {
    // The header line itself may be cut: wait for its end.
    r.needMore = head.size() < (1u << 20) && head.find("end_header\n") == std::string_view::npos &&
                 head.find("end_header\r\n") == std::string_view::npos;
    return r;
  }
  const PlyElement* vertex = header.find("vertex");
  if (header.format == detail::PlyFormat::ascii || !vertex) return r;
  if (vertex->find("packed_position") >= 0)
    return openCompressedPlyRows(header, head, name, fileBytes);
  r.decoder = std::make_unique<PlyRowDecoder>(header, name, fileBytes);
  return r;
}

GaussianCloud readPlyGaussians(std::string_view bytes, std::string_view name) {
  PlyHeader header;
  std::string error;
  if (!detail::parsePlyHeader(bytes, header, error)) fail(name, error);
  const PlyElement* vertex = header.find("vertex");
  if (!vertex) fail(name, "no vertex element");
  if (vertex->find("packed_position") >= 0) return readCompressedPlyGaussians(bytes, name);
  if (vertex->count == 0) fail(name, "expected at least one splat, got 0");
  const Columns c = findColumns(name, *vertex);
  if (vertex->count > kMaxSplats)
    fail(name, std::to_string(vertex->count) + " splats exceed the limit of " +
                   std::to_string(kMaxSplats));
  const std::size_t count = static_cast<std::size_t>(vertex->count);

  GaussianCloud cloud;
  if (header.format == detail::PlyFormat::ascii) {
    std::size_t pos = header.dataOffset;
    std::vector<double> values;
    for (const PlyElement& e : header.elements) {
      const bool isVertex = &e == vertex;
      std::vector<double> v = asciiValues(bytes, name, pos, e, isVertex);
      if (isVertex) {
        values = std::move(v);
        break;
      }
    }
    detail::allocate(cloud, count, c.degree);
    const std::size_t stride = vertex->properties.size();
    fill(cloud, c, count, [&](std::size_t i, int col) { return values[i * stride + col]; });
    return cloud;
  }
  const std::size_t offset = detail::plyElementOffset(bytes, name, header, *vertex);
  const bool bigEndian = header.format == detail::PlyFormat::binaryBigEndian;
  const char* data = bytes.data() + offset;
  const std::size_t rowBytes = vertex->rowBytes;
  const auto& props = vertex->properties;
  detail::allocate(cloud, count, c.degree);
  fill(cloud, c, count, [&](std::size_t i, int col) {
    const auto& p = props[static_cast<std::size_t>(col)];
    return detail::plyValue(data + i * rowBytes + p.offset, p.type, bigEndian);
  });
  return cloud;
}

}  // namespace gs::splats
