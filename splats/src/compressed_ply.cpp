// PlayCanvas .compressed.ply (readers.hpp): a binary little-endian PLY of a `chunk`
// element (per 256 splats: min/max of position, log scale and optionally colour), a
// `vertex` element of four packed uint32 (position 11-10-11, rotation 2-10-10-10 smallest
// three, log scale 11-10-11, colour and opacity 8-8-8-8) and an optional `sh` element of
// uint8 f_rest_*. Decoded as splat-transform 3.7's readCompressedChunked does (the file's
// own axes, Transform.PLY).
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "base/byte_order.hpp"
#include "reader_support.hpp"

namespace gs::splats {

namespace {

using detail::fail;
using detail::PlyElement;
using detail::PlyHeader;

float unorm(std::uint32_t v, int bits) {
  const std::uint32_t mask = (1u << bits) - 1u;
  return static_cast<float>(v & mask) / static_cast<float>(mask);
}

float lerp(float a, float b, float t) {
  return a * (1.0f - t) + b * t;
}

/// Where a compressed PLY's values lie: its elements, the packed words' and bounds'
/// columns, the SH properties. Points into the PlyHeader it was made from.
struct Layout {
  const PlyElement* chunk = nullptr;
  const PlyElement* vertex = nullptr;
  const PlyElement* sh = nullptr;
  std::size_t pPos = 0, pRot = 0, pScale = 0, pColor = 0;
  int bounds[12] = {};
  int colorBounds[6] = {};
  bool hasColor = true;
  int degree = 0;
  std::vector<std::size_t> shOffsets;  // byte of f_rest_k within an sh record
};

/// The layout of `header`, or FormatError naming `name` for what the format does not allow
/// (a missing element or property, a wrong type, too few chunks or sh records).
Layout layoutOf(const PlyHeader& header, std::string_view name) {
  if (header.format != detail::PlyFormat::binaryLittleEndian)
    fail(name, "a compressed PLY must be binary_little_endian");
  Layout L;
  L.chunk = header.find("chunk");
  L.vertex = header.find("vertex");
  L.sh = header.find("sh");
  if (!L.chunk) fail(name, "no chunk element");
  if (!L.vertex) fail(name, "no vertex element");
  const PlyElement& vertex = *L.vertex;
  const PlyElement& chunk = *L.chunk;
  if (vertex.count == 0) fail(name, "expected at least one splat, got 0");

  // Packed vertex words: any integer type of 4 bytes.
  auto word = [&](const char* property) {
    const int i = vertex.find(property);
    if (i < 0) fail(name, std::string("property '") + property + "' missing");
    const auto& p = vertex.properties[static_cast<std::size_t>(i)];
    if (p.type != detail::PlyType::u32 && p.type != detail::PlyType::i32)
      fail(name, std::string("property '") + property + "' is not a 32-bit integer");
    return p.offset;
  };
  L.pPos = word("packed_position");
  L.pRot = word("packed_rotation");
  L.pScale = word("packed_scale");
  L.pColor = word("packed_color");

  // Chunk bounds, any numeric type.
  auto chunkColumn = [&](const char* property, bool required) -> int {
    const int i = chunk.find(property);
    if (i < 0 && required) fail(name, std::string("chunk property '") + property + "' missing");
    return i;
  };
  const char* boundNames[] = {"min_x",       "min_y",       "min_z",       "max_x",
                              "max_y",       "max_z",       "min_scale_x", "min_scale_y",
                              "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"};
  for (int k = 0; k < 12; ++k) L.bounds[k] = chunkColumn(boundNames[k], true);
  const char* colorNames[] = {"min_r", "min_g", "min_b", "max_r", "max_g", "max_b"};
  for (int k = 0; k < 6; ++k)
    L.hasColor = (L.colorBounds[k] = chunkColumn(colorNames[k], false)) >= 0 && L.hasColor;
  const std::uint64_t needChunks = (vertex.count + 255) / 256;
  if (chunk.count < needChunks)
    fail(name, "expected " + std::to_string(needChunks) + " chunks for " +
                   std::to_string(vertex.count) + " splats, got " + std::to_string(chunk.count));
  if (vertex.count > kMaxSplats)
    fail(name, std::to_string(vertex.count) + " splats exceed the limit of " +
                   std::to_string(kMaxSplats));

  if (L.sh) {
    const std::size_t total = L.sh->properties.size();
    L.degree = total % 3 == 0 ? detail::shDegreeForRest(total / 3) : -1;
    if (L.degree < 0)
      fail(name, "expected 0, 9, 24 or 45 sh properties, got " + std::to_string(total));
    if (L.sh->count != vertex.count)
      fail(name, "expected " + std::to_string(vertex.count) + " sh records, got " +
                     std::to_string(L.sh->count));
    for (std::size_t k = 0; k < total; ++k) {
      const int i = L.sh->find("f_rest_" + std::to_string(k));
      if (i < 0) fail(name, "sh property 'f_rest_" + std::to_string(k) + "' missing");
      const auto& p = L.sh->properties[static_cast<std::size_t>(i)];
      if (p.type != detail::PlyType::u8) fail(name, "sh property '" + p.name + "' is not uchar");
      L.shOffsets.push_back(p.offset);
    }
  }
  return L;
}

/// Decodes splats [first, first + n) into `cloud` (allocated for n at L.degree) from the
/// records of chunks first / 256 on (`chunks`), and those splats' vertex and sh records
/// (`vertices`, `shRecords`; the latter null without sh).
void decodeRecords(const Layout& L, const char* chunks, const char* vertices, const char* shRecords,
                   std::size_t first, std::size_t n, GaussianCloud& cloud) {
  const std::size_t c0 = first >> 8;
  auto chunkValue = [&](std::size_t c, int column) {
    const auto& p = L.chunk->properties[static_cast<std::size_t>(column)];
    return detail::toFloat(
        detail::plyValue(chunks + (c - c0) * L.chunk->rowBytes + p.offset, p.type, false));
  };
  constexpr float kRotNorm = 1.41421356237309505f;  // 1 / (sqrt(2) / 2)
  std::vector<float> rest(L.shOffsets.size());
  float b[12], cb[6];
  std::size_t loaded = static_cast<std::size_t>(-1);
  for (std::size_t j = 0; j < n; ++j) {
    const std::size_t c = (first + j) >> 8;
    if (c != loaded) {
      for (int k = 0; k < 12; ++k) b[k] = chunkValue(c, L.bounds[k]);
      if (L.hasColor)
        for (int k = 0; k < 6; ++k) cb[k] = chunkValue(c, L.colorBounds[k]);
      loaded = c;
    }
    const char* row = vertices + j * L.vertex->rowBytes;
    const std::uint32_t pp = base::loadLe<std::uint32_t>(row + L.pPos);
    const std::uint32_t pr = base::loadLe<std::uint32_t>(row + L.pRot);
    const std::uint32_t ps = base::loadLe<std::uint32_t>(row + L.pScale);
    const std::uint32_t pc = base::loadLe<std::uint32_t>(row + L.pColor);
    const std::size_t i = j;
    cloud.positions[i] =
        glm::vec3(lerp(b[0], b[3], unorm(pp >> 21, 11)), lerp(b[1], b[4], unorm(pp >> 11, 10)),
                  lerp(b[2], b[5], unorm(pp, 11)));
    const float ra = (unorm(pr >> 20, 10) - 0.5f) * kRotNorm;
    const float rb = (unorm(pr >> 10, 10) - 0.5f) * kRotNorm;
    const float rc = (unorm(pr, 10) - 0.5f) * kRotNorm;
    const float rm = std::sqrt(std::max(0.0f, 1.0f - (ra * ra + rb * rb + rc * rc)));
    switch (pr >> 30) {
      case 0:
        cloud.rotations[i] = detail::unitQuat(rm, ra, rb, rc);
        break;
      case 1:
        cloud.rotations[i] = detail::unitQuat(ra, rm, rb, rc);
        break;
      case 2:
        cloud.rotations[i] = detail::unitQuat(ra, rb, rm, rc);
        break;
      default:
        cloud.rotations[i] = detail::unitQuat(ra, rb, rc, rm);
    }
    cloud.scales[i] = glm::vec3(std::exp(lerp(b[6], b[9], unorm(ps >> 21, 11))),
                                std::exp(lerp(b[7], b[10], unorm(ps >> 11, 10))),
                                std::exp(lerp(b[8], b[11], unorm(ps, 11))));
    cloud.opacities[i] = unorm(pc, 8);
    glm::vec3 rgb(unorm(pc >> 24, 8), unorm(pc >> 16, 8), unorm(pc >> 8, 8));
    if (L.hasColor)
      rgb = glm::vec3(lerp(cb[0], cb[3], rgb.x), lerp(cb[1], cb[4], rgb.y),
                      lerp(cb[2], cb[5], rgb.z));
    cloud.shDc[i] = (rgb - 0.5f) / kShC0;
    if (!rest.empty()) {
      const char* s = shRecords + j * L.sh->rowBytes;
      for (std::size_t k = 0; k < rest.size(); ++k) {
        const unsigned v = static_cast<std::uint8_t>(s[L.shOffsets[k]]);
        const float u = v == 0 ? 0.0f : v == 255 ? 1.0f : (static_cast<float>(v) + 0.5f) / 256.0f;
        rest[k] = (u - 0.5f) * 8.0f;
      }
      detail::setChannelMajorRest(cloud, i, rest.data());
    }
  }
}

/// A compressed PLY read a batch of splats at a time: the batch's chunk, vertex and sh
/// records read by offset.
class CompressedPlyBatches final : public GaussianBatchReader {
 public:
  explicit CompressedPlyBatches(const std::string& path) : file_(path) {
    const std::string head = file_.head();
    std::string error;
    if (!detail::parsePlyHeader(head, header_, error)) fail(path, error);
    layout_ = layoutOf(header_, path);
    vertexOffset_ = detail::plyElementOffset(file_.size(), path, header_, *layout_.vertex);
    chunkOffset_ = detail::plyElementOffset(file_.size(), path, header_, *layout_.chunk);
    if (layout_.sh) shOffset_ = detail::plyElementOffset(file_.size(), path, header_, *layout_.sh);
  }
  std::uint64_t size() const override { return layout_.vertex->count; }
  int shDegree() const override { return layout_.degree; }
  std::size_t rowBytes() const override {
    return layout_.vertex->rowBytes + (layout_.sh ? layout_.sh->rowBytes : 0) +
           layout_.chunk->rowBytes / 256 + 1;
  }
  std::size_t read(GaussianCloud& batch, std::size_t max) override {
    const auto n = static_cast<std::size_t>(std::min<std::uint64_t>(max, size() - next_));
    batch = GaussianCloud{};
    detail::allocate(batch, n, layout_.degree);
    if (n == 0) return 0;
    const std::uint64_t c0 = next_ >> 8, c1 = (next_ + n - 1) >> 8;
    const std::size_t chunkBytes = layout_.chunk->rowBytes;
    chunks_.resize(static_cast<std::size_t>(c1 - c0 + 1) * chunkBytes);
    file_.read(chunkOffset_ + c0 * chunkBytes, chunks_.data(), chunks_.size());
    vertices_.resize(n * layout_.vertex->rowBytes);
    file_.read(vertexOffset_ + next_ * layout_.vertex->rowBytes, vertices_.data(),
               vertices_.size());
    if (layout_.sh) {
      sh_.resize(n * layout_.sh->rowBytes);
      file_.read(shOffset_ + next_ * layout_.sh->rowBytes, sh_.data(), sh_.size());
    }
    decodeRecords(layout_, chunks_.data(), vertices_.data(), layout_.sh ? sh_.data() : nullptr,
                  static_cast<std::size_t>(next_), n, batch);
    next_ += n;
    return n;
  }
  void rewind() override { next_ = 0; }

 private:
  detail::PieceFile file_;
  PlyHeader header_;
  Layout layout_;
  std::uint64_t vertexOffset_ = 0, chunkOffset_ = 0, shOffset_ = 0, next_ = 0;
  std::vector<char> chunks_, vertices_, sh_;
};

/// A compressed PLY's vertex records decoded as they arrive (openGaussianRows): each
/// splat's position, rotation, scale, colour and opacity without its SH, which lie in the
/// sh element after every vertex record. The chunk table is copied from the file's head.
class CompressedPlyRowDecoder final : public GaussianRowDecoder {
 public:
  CompressedPlyRowDecoder(const PlyHeader& header, const Layout& layout, std::string chunks,
                          std::uint64_t vertexOffset)
      : header_(header), chunks_(std::move(chunks)), vertexOffset_(vertexOffset) {
    // The layout's element pointers are re-pointed into this decoder's own header copy.
    layout_ = layout;
    layout_.chunk = header_.find("chunk");
    layout_.vertex = header_.find("vertex");
    layout_.sh = nullptr;  // rows carry no SH: the preview is of degree 0
    layout_.degree = 0;
    layout_.shOffsets.clear();
  }
  CompressedPlyRowDecoder(const CompressedPlyRowDecoder&) = delete;  // layout_ points into header_
  CompressedPlyRowDecoder& operator=(const CompressedPlyRowDecoder&) = delete;
  std::uint64_t dataOffset() const override { return vertexOffset_; }
  std::size_t rowBytes() const override { return layout_.vertex->rowBytes; }
  std::uint64_t size() const override { return layout_.vertex->count; }
  int shDegree() const override { return 0; }
  bool wholeFileAtEnd() const override { return true; }
  void decode(const char* rows, std::uint64_t first, std::size_t n,
              GaussianCloud& batch) const override {
    detail::checkRows(first, n, size());
    batch = GaussianCloud{};
    detail::allocate(batch, n, 0);
    if (n == 0) return;
    decodeRecords(layout_, chunks_.data() + (first >> 8) * layout_.chunk->rowBytes, rows, nullptr,
                  static_cast<std::size_t>(first), n, batch);
  }

 private:
  PlyHeader header_;
  Layout layout_;
  std::string chunks_;  // the chunk records of every splat
  std::uint64_t vertexOffset_ = 0;
};

}  // namespace

GaussianRows openCompressedPlyRows(const PlyHeader& header, std::string_view head,
                                   const std::string& name, std::uint64_t fileBytes) {
  GaussianRows r;
  const Layout L = layoutOf(header, name);
  const std::uint64_t chunkOffset = detail::plyElementOffset(fileBytes, name, header, *L.chunk);
  const std::uint64_t vertexOffset = detail::plyElementOffset(fileBytes, name, header, *L.vertex);
  if (chunkOffset > vertexOffset) return r;  // the chunk table comes last: read whole
  const std::uint64_t tableEnd = chunkOffset + (L.vertex->count + 255) / 256 * L.chunk->rowBytes;
  if (head.size() < tableEnd) {
    r.needMore = true;  // bounded by the file: plyElementOffset checked the table lies in it
    return r;
  }
  r.decoder = std::make_unique<CompressedPlyRowDecoder>(
      header, L,
      std::string(head.substr(static_cast<std::size_t>(chunkOffset),
                              static_cast<std::size_t>(tableEnd - chunkOffset))),
      vertexOffset);
  return r;
}

std::unique_ptr<GaussianBatchReader> openCompressedPlyGaussianBatches(const std::string& path) {
  return std::make_unique<CompressedPlyBatches>(path);
}

GaussianCloud readCompressedPlyGaussians(std::string_view bytes, std::string_view name) {
  PlyHeader header;
  std::string error;
  if (!detail::parsePlyHeader(bytes, header, error)) fail(name, error);
  const Layout L = layoutOf(header, name);
  const std::size_t vertexOffset = detail::plyElementOffset(bytes, name, header, *L.vertex);
  const std::size_t chunkOffset = detail::plyElementOffset(bytes, name, header, *L.chunk);
  const std::size_t shOffset = L.sh ? detail::plyElementOffset(bytes, name, header, *L.sh) : 0;
  const std::size_t count = static_cast<std::size_t>(L.vertex->count);
  GaussianCloud cloud;
  detail::allocate(cloud, count, L.degree);
  decodeRecords(L, bytes.data() + chunkOffset, bytes.data() + vertexOffset,
                L.sh ? bytes.data() + shOffset : nullptr, 0, count, cloud);
  return cloud;
}

}  // namespace gs::splats
