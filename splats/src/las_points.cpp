// ASPRS LAS 1.0-1.4 point clouds as Gaussians (readers.hpp: readLasPoints; docs/splats.md,
// "LAS point clouds"). The header's scale and offset are applied in double precision and
// the points are kept relative to the header's minimum corner, so survey coordinates
// (UTM eastings of 10^5-10^6 m) keep their centimetres in float.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <vector>

#include "base/byte_order.hpp"
#include "reader_support.hpp"

namespace gs::splats {

namespace {

using base::loadLe;

double loadDouble(const char* p) {
  const std::uint64_t bits = loadLe<std::uint64_t>(p);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// The smallest record of each point data format (LAS 1.4, table 7 onwards) and where its
// RGB sits (-1: none).
struct PointFormat {
  std::size_t bytes;
  int rgb;
};
constexpr PointFormat kFormats[] = {{20, -1}, {28, -1}, {26, 20}, {34, 28}, {57, -1}, {63, 28},
                                    {30, -1}, {36, 30}, {38, 30}, {59, -1}, {67, 30}};

}  // namespace

GaussianCloud readLasPoints(std::string_view bytes, std::string_view name, glm::dvec3* origin) {
  if (bytes.size() < 227 || !bytes.starts_with("LASF"))
    detail::fail(name, bytes.starts_with("LASF")
                           ? "truncated LAS header (" + std::to_string(bytes.size()) + " bytes)"
                           : std::string("not a LAS file (no 'LASF')"));
  const char* h = bytes.data();
  const int major = static_cast<unsigned char>(h[24]), minor = static_cast<unsigned char>(h[25]);
  if (major != 1 || minor > 4)
    detail::fail(name, "LAS version " + std::to_string(major) + "." + std::to_string(minor) +
                           " is not one this build reads (1.0 to 1.4)");
  const auto headerSize = loadLe<std::uint16_t>(h + 94);
  const auto pointOffset = loadLe<std::uint32_t>(h + 96);
  const auto formatByte = static_cast<unsigned char>(h[104]);
  const auto recordBytes = loadLe<std::uint16_t>(h + 105);
  if (formatByte & 0xc0)
    detail::fail(name,
                 "a LAZ (compressed) point cloud; no library of this build decodes "
                 "LAZ: decompress it to LAS first (laszip -i in.laz -o out.las, or "
                 "pdal translate)");
  if (formatByte > 10) detail::fail(name, "unknown LAS point format " + std::to_string(formatByte));
  const PointFormat format = kFormats[formatByte];
  if (recordBytes < format.bytes)
    detail::fail(name, "point records of " + std::to_string(recordBytes) +
                           " bytes are too short for point format " + std::to_string(formatByte) +
                           " (" + std::to_string(format.bytes) + ")");
  std::uint64_t count = loadLe<std::uint32_t>(h + 107);
  if (minor >= 4 && headerSize >= 375 && bytes.size() >= 255) {
    const auto count64 = loadLe<std::uint64_t>(h + 247);
    if (count == 0 || count64 > count) count = count64;
  }
  if (headerSize < 227 || pointOffset < headerSize || pointOffset > bytes.size())
    detail::fail(name, "point data offset " + std::to_string(pointOffset) +
                           " lies outside the file (" + std::to_string(bytes.size()) + " bytes)");
  detail::checkCount(name, count, recordBytes, bytes.size() - pointOffset, "LAS points");
  const glm::dvec3 scale(loadDouble(h + 131), loadDouble(h + 139), loadDouble(h + 147));
  const glm::dvec3 offset(loadDouble(h + 155), loadDouble(h + 163), loadDouble(h + 171));
  const glm::dvec3 low(loadDouble(h + 187), loadDouble(h + 203), loadDouble(h + 219));
  const glm::dvec3 high(loadDouble(h + 179), loadDouble(h + 195), loadDouble(h + 211));
  for (int a = 0; a < 3; ++a)
    if (!std::isfinite(scale[a]) || scale[a] == 0.0 || !std::isfinite(offset[a]) ||
        !std::isfinite(low[a]) || !std::isfinite(high[a]))
      detail::fail(name, "impossible scale, offset or bounds in the LAS header");
  const glm::dvec3 base = low;  // positions relative to the header's minimum corner
  if (origin) *origin = base;

  GaussianCloud cloud;
  detail::allocate(cloud, static_cast<std::size_t>(count), 0);
  const char* p = bytes.data() + pointOffset;
  std::uint32_t brightest = 1;
  bool sixteenBit = false;
  std::vector<std::array<std::uint16_t, 3>> rgb(format.rgb >= 0 ? count : 0);
  std::vector<std::uint16_t> intensity(format.rgb >= 0 ? 0 : count);
  for (std::size_t i = 0; i < count; ++i, p += recordBytes) {
    const glm::dvec3 q(loadLe<std::int32_t>(p), loadLe<std::int32_t>(p + 4),
                       loadLe<std::int32_t>(p + 8));
    const glm::dvec3 world = q * scale + offset - base;
    cloud.positions[i] =
        glm::vec3(detail::toFloat(world.x), detail::toFloat(world.y), detail::toFloat(world.z));
    if (format.rgb >= 0) {
      for (int c = 0; c < 3; ++c) {
        rgb[i][static_cast<std::size_t>(c)] = loadLe<std::uint16_t>(p + format.rgb + 2 * c);
        sixteenBit |= rgb[i][static_cast<std::size_t>(c)] > 255;
      }
    } else {
      intensity[i] = loadLe<std::uint16_t>(p + 12);
      brightest = std::max<std::uint32_t>(brightest, intensity[i]);
    }
  }
  // A splat per point: isotropic, as wide as the points' spacing over the box's largest
  // face (airborne lidar is 2.5D), opaque; colour from RGB (8 or 16 bits, as the file
  // holds them) or, without RGB, intensity as grey.
  glm::dvec3 extent = glm::max(high - low, glm::dvec3(0.0));
  std::sort(&extent.x, &extent.x + 3);
  const double face = std::max(extent.y * extent.z, 1e-12);
  const float sigma = static_cast<float>(
      0.5 * std::sqrt(face / static_cast<double>(std::max<std::uint64_t>(count, 1))));
  for (std::size_t i = 0; i < count; ++i) {
    cloud.scales[i] = glm::vec3(sigma);
    cloud.opacities[i] = 1.0f;
    glm::vec3 color;
    if (format.rgb >= 0)
      color = glm::vec3(rgb[i][0], rgb[i][1], rgb[i][2]) / (sixteenBit ? 65535.0f : 255.0f);
    else
      color = glm::vec3(static_cast<float>(intensity[i]) / static_cast<float>(brightest));
    cloud.shDc[i] = (color - 0.5f) / kShC0;
  }
  return cloud;
}

}  // namespace gs::splats
