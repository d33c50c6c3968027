// PlayCanvas .compressed.ply (readers.hpp): a binary little-endian PLY of a `chunk`
// element (per 256 splats: min/max of position, log scale and optionally colour), a
// `vertex` element of four packed uint32 (position 11-10-11, rotation 2-10-10-10 smallest
// three, log scale 11-10-11, colour and opacity 8-8-8-8) and an optional `sh` element of
// uint8 f_rest_*. Decoded as splat-transform 3.7's readCompressedChunked does (the file's
// own axes, Transform.PLY).
#include <cmath>
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

}  // namespace

GaussianCloud readCompressedPlyGaussians(std::string_view bytes, std::string_view name) {
  PlyHeader header;
  std::string error;
  if (!detail::parsePlyHeader(bytes, header, error)) fail(name, error);
  if (header.format != detail::PlyFormat::binaryLittleEndian)
    fail(name, "a compressed PLY must be binary_little_endian");
  const PlyElement* chunk = header.find("chunk");
  const PlyElement* vertex = header.find("vertex");
  const PlyElement* sh = header.find("sh");
  if (!chunk) fail(name, "no chunk element");
  if (!vertex) fail(name, "no vertex element");
  if (vertex->count == 0) fail(name, "expected at least one splat, got 0");

  // Packed vertex words: any integer type of 4 bytes.
  auto word = [&](const char* property) {
    const int i = vertex->find(property);
    if (i < 0) fail(name, std::string("property '") + property + "' missing");
    const auto& p = vertex->properties[static_cast<std::size_t>(i)];
    if (p.type != detail::PlyType::u32 && p.type != detail::PlyType::i32)
      fail(name, std::string("property '") + property + "' is not a 32-bit integer");
    return p.offset;
  };
  const std::size_t pPos = word("packed_position"), pRot = word("packed_rotation"),
                    pScale = word("packed_scale"), pColor = word("packed_color");

  // Chunk bounds, any numeric type.
  auto chunkColumn = [&](const char* property, bool required) -> int {
    const int i = chunk->find(property);
    if (i < 0 && required) fail(name, std::string("chunk property '") + property + "' missing");
    return i;
  };
  const char* boundNames[] = {"min_x",       "min_y",       "min_z",       "max_x",
                              "max_y",       "max_z",       "min_scale_x", "min_scale_y",
                              "min_scale_z", "max_scale_x", "max_scale_y", "max_scale_z"};
  int bounds[12];
  for (int k = 0; k < 12; ++k) bounds[k] = chunkColumn(boundNames[k], true);
  const char* colorNames[] = {"min_r", "min_g", "min_b", "max_r", "max_g", "max_b"};
  int colorBounds[6];
  bool hasColor = true;
  for (int k = 0; k < 6; ++k)
    hasColor = (colorBounds[k] = chunkColumn(colorNames[k], false)) >= 0 && hasColor;

  const std::size_t vertexOffset = detail::plyElementOffset(bytes, name, header, *vertex);
  const std::size_t chunkOffset = detail::plyElementOffset(bytes, name, header, *chunk);
  const std::uint64_t needChunks = (vertex->count + 255) / 256;
  if (chunk->count < needChunks)
    fail(name, "expected " + std::to_string(needChunks) + " chunks for " +
                   std::to_string(vertex->count) + " splats, got " + std::to_string(chunk->count));

  int degree = 0;
  std::vector<std::size_t> shOffsets;  // byte of f_rest_k within an sh record
  std::size_t shOffset = 0;
  if (sh) {
    const std::size_t total = sh->properties.size();
    degree = total % 3 == 0 ? detail::shDegreeForRest(total / 3) : -1;
    if (degree < 0)
      fail(name, "expected 0, 9, 24 or 45 sh properties, got " + std::to_string(total));
    if (sh->count != vertex->count)
      fail(name, "expected " + std::to_string(vertex->count) + " sh records, got " +
                     std::to_string(sh->count));
    for (std::size_t k = 0; k < total; ++k) {
      const int i = sh->find("f_rest_" + std::to_string(k));
      if (i < 0) fail(name, "sh property 'f_rest_" + std::to_string(k) + "' missing");
      const auto& p = sh->properties[static_cast<std::size_t>(i)];
      if (p.type != detail::PlyType::u8) fail(name, "sh property '" + p.name + "' is not uchar");
      shOffsets.push_back(p.offset);
    }
    shOffset = detail::plyElementOffset(bytes, name, header, *sh);
  }

  const std::size_t count = static_cast<std::size_t>(vertex->count);
  GaussianCloud cloud;
  detail::allocate(cloud, count, degree);
  const char* data = bytes.data();
  auto chunkValue = [&](std::size_t c, int column) {
    const auto& p = chunk->properties[static_cast<std::size_t>(column)];
    return detail::toFloat(
        detail::plyValue(data + chunkOffset + c * chunk->rowBytes + p.offset, p.type, false));
  };
  constexpr float kRotNorm = 1.41421356237309505f;  // 1 / (sqrt(2) / 2)
  std::vector<float> rest(shOffsets.size());
  float b[12], cb[6];
  std::size_t loaded = static_cast<std::size_t>(-1);
  for (std::size_t i = 0; i < count; ++i) {
    const std::size_t c = i >> 8;
    if (c != loaded) {
      for (int k = 0; k < 12; ++k) b[k] = chunkValue(c, bounds[k]);
      if (hasColor)
        for (int k = 0; k < 6; ++k) cb[k] = chunkValue(c, colorBounds[k]);
      loaded = c;
    }
    const char* row = data + vertexOffset + i * vertex->rowBytes;
    const std::uint32_t pp = base::loadLe<std::uint32_t>(row + pPos);
    const std::uint32_t pr = base::loadLe<std::uint32_t>(row + pRot);
    const std::uint32_t ps = base::loadLe<std::uint32_t>(row + pScale);
    const std::uint32_t pc = base::loadLe<std::uint32_t>(row + pColor);
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
    if (hasColor)
      rgb = glm::vec3(lerp(cb[0], cb[3], rgb.x), lerp(cb[1], cb[4], rgb.y),
                      lerp(cb[2], cb[5], rgb.z));
    cloud.shDc[i] = (rgb - 0.5f) / kShC0;
    if (!rest.empty()) {
      const char* s = data + shOffset + i * sh->rowBytes;
      for (std::size_t k = 0; k < rest.size(); ++k) {
        const unsigned v = static_cast<std::uint8_t>(s[shOffsets[k]]);
        const float n = v == 0 ? 0.0f : v == 255 ? 1.0f : (static_cast<float>(v) + 0.5f) / 256.0f;
        rest[k] = (n - 0.5f) * 8.0f;
      }
      detail::setChannelMajorRest(cloud, i, rest.data());
    }
  }
  return cloud;
}

}  // namespace gs::splats
