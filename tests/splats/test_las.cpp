// ASPRS LAS point clouds as Gaussians (splats/readers.hpp: readLasPoints) on laspy's test
// files (tests/data/las/README.md), and on damaged and hostile headers.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstring>
#include <string>

#include "splats/readers.hpp"
#include "test_support.hpp"

using namespace gs::splats;

namespace {

std::string las(const std::string& file) {
  const std::string bytes = gs::test::readBytes(gs::test::sourceDir() / "tests/data/las" / file);
  REQUIRE(!bytes.empty());
  return bytes;
}

glm::vec3 colorOf(const GaussianCloud& c, std::size_t i) {
  return 0.5f + kShC0 * c.shDc[i];
}

}  // namespace

TEST_CASE("LAS 1.2 with RGB: every point, survey coordinates kept to the centimetre",
          "[splats][las]") {
  const std::string bytes = las("simple.las");
  glm::dvec3 origin(0.0);
  const GaussianCloud cloud = readLasPoints(bytes, "simple.las", &origin);
  REQUIRE(cloud.size() == 1065);
  CHECK(origin.x == Approx(635619.85));
  CHECK(origin.y == Approx(848899.70));
  CHECK(origin.z == Approx(406.59));
  // The first point, read by hand: X, Y, Z int32 at the point data offset, scale 0.01.
  std::int32_t q[3];
  std::memcpy(q, bytes.data() + 227, sizeof q);
  for (int a = 0; a < 3; ++a)
    CHECK(cloud.positions[0][a] == Approx(q[a] * 0.01 - origin[a]).margin(0.005));
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const glm::vec3 p = cloud.positions[i];
    REQUIRE(p.x >= -0.01f);
    REQUIRE(p.x <= 3362.71f);  // the header's extent
    REQUIRE(p.z <= 179.8f);
    const glm::vec3 c = colorOf(cloud, i);
    REQUIRE(c.r >= -1e-4f);
    REQUIRE(c.r <= 1.0001f);
  }
  // Colour from the 16-bit RGB of the first point.
  std::uint16_t rgb[3];
  std::memcpy(rgb, bytes.data() + 227 + 28, sizeof rgb);
  const bool sixteen = rgb[0] > 255 || rgb[1] > 255 || rgb[2] > 255;
  CHECK(colorOf(cloud, 0).g == Approx(rgb[1] / (sixteen ? 65535.0 : 255.0)).margin(1e-4));
  CHECK(cloud.opacities[0] == 1.0f);
  CHECK(cloud.scales[0].x > 0.0f);
  CHECK(detectSplatFormat(bytes, "x") == SplatFormat::las);
  CHECK(readGaussians(bytes, "simple.las", {}).size() == 1065);
}

TEST_CASE("LAS 1.4 point format 6: intensity as grey, the 375-byte header", "[splats][las]") {
  const GaussianCloud cloud = readLasPoints(las("test1_4.las"), "test1_4.las");
  REQUIRE(cloud.size() == 1000);
  float darkest = 1.0f, brightest = 0.0f;
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    const glm::vec3 c = colorOf(cloud, i);
    REQUIRE(c.r == Approx(c.g));
    darkest = std::min(darkest, c.r);
    brightest = std::max(brightest, c.r);
    // Offsets of 10^6 and a scale of 1e-6: positions relative to the minimum corner are
    // small and exact enough in float.
    REQUIRE(std::abs(cloud.positions[i].x) < 600.0f);
  }
  CHECK(brightest == Approx(1.0f));
  CHECK(darkest < brightest);
}

TEST_CASE("LAZ, truncated and hostile LAS files are errors that say what is wrong",
          "[splats][las]") {
  CHECK_THROWS_WITH(readLasPoints(las("simple.laz"), "simple.laz"),
                    Catch::Contains("simple.laz: a LAZ (compressed) point cloud") &&
                        Catch::Contains("decompress it to LAS first"));
  const std::string bytes = las("simple.las");
  CHECK_THROWS_WITH(readLasPoints(bytes.substr(0, bytes.size() - 10), "cut.las"),
                    Catch::Contains("cut.las: expected"));
  CHECK_THROWS_WITH(readLasPoints(bytes.substr(0, 100), "short.las"),
                    Catch::Contains("truncated LAS header"));
  std::string hostile = bytes;
  const std::uint32_t many = 0xffffffffu;
  std::memcpy(hostile.data() + 107, &many, 4);  // four billion points in 36 KB
  CHECK_THROWS_AS(readLasPoints(hostile, "many.las"), FormatError);
  std::string version = bytes;
  version[25] = 9;
  CHECK_THROWS_WITH(readLasPoints(version, "v19.las"), Catch::Contains("LAS version 1.9"));
  std::string format = bytes;
  format[104] = 11;
  CHECK_THROWS_WITH(readLasPoints(format, "f11.las"), Catch::Contains("point format 11"));
  std::string shortRecord = bytes;
  shortRecord[105] = 20;  // format 3 needs 34 bytes
  shortRecord[106] = 0;
  CHECK_THROWS_WITH(readLasPoints(shortRecord, "rec.las"), Catch::Contains("too short"));
}
