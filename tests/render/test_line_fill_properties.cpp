// X3D LineProperties and FillProperties (X3D 4.0 clauses 12.4.6 and 12.4.3): line width
// and dash patterns, hatching and unfilled polygons, drawn off-screen at 64x64 by the
// generic surface program (frame 1) and by its specialized variant (frame 3).
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <string>
#include <vector>

namespace fs = std::filesystem;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// The two materials the hatches are drawn on: the Phong program's and the physical one's.
constexpr const char* kHatchMaterials[] = {
    "Material { diffuseColor 0 0 0 emissiveColor 0 1 0 }",
    "PhysicalMaterial { baseColor 0 0 0 emissiveColor 0 1 0 }"};

/// A square filling the 90-degree view from (0, 0, 1), unlit green (emissive `material`),
/// with `fill` as the Appearance's fillProperties (may be empty).
fs::path hatchWorld(const std::string& name, const std::string& fill,
                    const std::string& material = kHatchMaterials[0]) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V4.0 utf8
PROFILE Interchange
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Transform { translation 0 0 -1 scale 2 2 1 children Shape {
  appearance Appearance { material )" +
                      material + R"(
    )" + fill + R"( }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } }
)");
  return file;
}

/// A horizontal line across the middle of the view, red, with `line` as the Appearance's
/// lineProperties (may be empty).
fs::path lineWorld(const std::string& name, const std::string& line) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V3.2 utf8
PROFILE Interchange
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Shape {
  appearance Appearance { material Material { emissiveColor 1 0 0 } )" +
                      line + R"( }
  geometry LineSet { vertexCount [2] coord Coordinate { point [-2 0.01 0, 2 0.01 0] } } }
)");
  return file;
}

/// Per pixel of row or column `index`: whether it has colour (r, g, b).
std::vector<bool> pixelsOf(const Rendered& r, bool row, int index, int red, int green, int blue) {
  std::vector<bool> out;
  for (int i = 0; i < gs::test::kWorldSize; ++i) {
    const std::uint8_t* p = row ? r.image.pixel(i, index) : r.image.pixel(index, i);
    out.push_back(close(p, red, green, blue, 24));
  }
  return out;
}

int countOf(const std::vector<bool>& v) {
  int n = 0;
  for (bool b : v) n += b ? 1 : 0;
  return n;
}

/// Rows (from the top) where column 20 shows the line's red.
int lineRows(const Rendered& r) {
  return countOf(pixelsOf(r, false, 20, 255, 0, 0));
}

}  // namespace

TEST_CASE("FillProperties hatches polygons every 8 pixels in hatchColor",
          "[render][offscreen][world][fill]") {
  for (const char* material : kHatchMaterials)
    for (int frames : {1, 3}) {
      INFO(material << ", frames " << frames);
      // Style 1, horizontal lines: column 20 is red on 8 of 64 rows, 8 apart, green between.
      const Rendered h = renderFile(
          hatchWorld("fill_horizontal",
                     "fillProperties FillProperties { hatchStyle 1 hatchColor 1 0 0 }", material),
          frames);
      CHECK(h.diagnostics.items.empty());
      const std::vector<bool> red = pixelsOf(h, false, 20, 255, 0, 0);
      CHECK(countOf(red) == 8);
      CHECK(countOf(pixelsOf(h, false, 20, 0, 255, 0)) == 56);
      for (int y = 0; y + 8 < 64; ++y) CHECK(red[static_cast<std::size_t>(y)] == red[y + 8u]);
      // Every row is alike along x (the hatches are horizontal).
      CHECK(countOf(pixelsOf(h, true, 7, 255, 0, 0)) + countOf(pixelsOf(h, true, 7, 0, 255, 0)) ==
            64);
      // Style 5, cross-hatch: both rows and columns.
      const Rendered cross = renderFile(
          hatchWorld("fill_cross",
                     "fillProperties FillProperties { hatchStyle 5 hatchColor 1 0 0 }", material),
          frames);
      const int crossRed = countOf(pixelsOf(cross, false, 20, 255, 0, 0));
      CHECK((crossRed == 8 || crossRed == 64));  // a column on or off a vertical hatch line
      int redColumns = 0;
      for (int x = 0; x < 64; ++x)
        redColumns += countOf(pixelsOf(cross, false, x, 255, 0, 0)) == 64;
      CHECK(redColumns == 8);
    }
}

TEST_CASE("FillProperties filled FALSE leaves only the hatches; neither draws nothing",
          "[render][offscreen][world][fill]") {
  for (const char* material : kHatchMaterials)
    for (int frames : {1, 3}) {
      INFO(material << ", frames " << frames);
      const Rendered v = renderFile(
          hatchWorld("fill_unfilled",
                     "fillProperties FillProperties { filled FALSE hatchStyle 2 hatchColor 1 1 0 }",
                     material),
          frames);
      const std::vector<bool> row = pixelsOf(v, true, 30, 255, 255, 0);
      CHECK(countOf(row) == 8);
      CHECK(countOf(pixelsOf(v, true, 30, 0, 0, 0)) == 56);  // the background shows through
      const Rendered none = renderFile(
          hatchWorld("fill_none", "fillProperties FillProperties { filled FALSE hatched FALSE }",
                     material),
          frames);
      CHECK(countOf(pixelsOf(none, true, 30, 0, 0, 0)) == 64);
      // Without FillProperties the square is filled green.
      const Rendered plain = renderFile(hatchWorld("fill_default", "", material), frames);
      CHECK(countOf(pixelsOf(plain, true, 30, 0, 255, 0)) == 64);
    }
}

TEST_CASE("LineProperties widens lines and draws dash patterns",
          "[render][offscreen][world][line]") {
  for (int frames : {1, 3}) {
    INFO("frames " << frames);
    const Rendered plain = renderFile(lineWorld("line_plain", ""), frames);
    CHECK(lineRows(plain) == 1);
    const Rendered wide = renderFile(
        lineWorld("line_wide", "lineProperties LineProperties { linewidthScaleFactor 5 }"), frames);
    CHECK(wide.diagnostics.items.empty());
    CHECK(lineRows(wide) == 5);
    const Rendered off = renderFile(
        lineWorld("line_not_applied",
                  "lineProperties LineProperties { applied FALSE linewidthScaleFactor 5 }"),
        frames);
    CHECK(lineRows(off) == 1);
    // Dashed (type 2): 9 points on, 7 off (X_ITE's pattern; a point is 4/3 pixel) along the
    // line, from its provoking vertex: 36 of the 64 pixels.
    const Rendered dashed = renderFile(
        lineWorld("line_dashed", "lineProperties LineProperties { linetype 2 }"), frames);
    int y = 0;
    for (int row = 0; row < 64; ++row)
      if (countOf(pixelsOf(dashed, true, row, 255, 0, 0)) > 0) y = row;
    const int on = countOf(pixelsOf(dashed, true, y, 255, 0, 0));
    CHECK(on >= 33);  // 9/16 of 64, give or take a dash cut at the edges
    CHECK(on <= 39);
    // Dotted (type 3): 2 on, 2 off: half the pixels.
    const Rendered dotted = renderFile(
        lineWorld("line_dotted", "lineProperties LineProperties { linetype 3 }"), frames);
    const int dots = countOf(pixelsOf(dotted, true, y, 255, 0, 0));
    CHECK(dots >= 31);
    CHECK(dots <= 33);
  }
}

TEST_CASE("An unsupported linetype draws solid with a warning at the node",
          "[render][offscreen][world][line]") {
  const Rendered r =
      renderFile(lineWorld("line_type_9", "lineProperties LineProperties { linetype 9 }"));
  REQUIRE(r.diagnostics.items.size() == 1);
  CHECK(r.diagnostics.items[0].message.find("linetype 9") != std::string::npos);
  CHECK(r.diagnostics.items[0].location.line == 5);
  CHECK(lineRows(r) == 1);
  int lit = 0;
  for (int row = 0; row < 64; ++row) lit += countOf(pixelsOf(r, true, row, 255, 0, 0));
  CHECK(lit == 64);
}

namespace {

/// One red point at the origin seen from 1 m, with `points` as the Appearance's
/// pointProperties (may be empty); the renderer's nominal point size for an X3D world is 1
/// pixel (X_ITE's).
int pointPixels(const std::string& name, const std::string& points, int frames) {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, R"(#X3D V4.0 utf8
PROFILE Interchange
Viewpoint { position 0 0 1 fieldOfView 1.5708 }
Shape {
  appearance Appearance { material UnlitMaterial { emissiveColor 1 0 0 } )" +
                      points + R"( }
  geometry PointSet { coord Coordinate { point [0 0 0] } } }
)");
  const Rendered r = renderFile(file, frames);
  int lit = 0;
  for (int row = 0; row < gs::test::kWorldSize; ++row)
    lit += countOf(pixelsOf(r, true, row, 255, 0, 0));
  return lit;
}

}  // namespace

TEST_CASE("PointProperties scales, attenuates and clamps the point size",
          "[render][offscreen][world][point]") {
  for (int frames : {1, 3}) {
    INFO("frames " << frames);
    CHECK(pointPixels("point_plain", "", frames) == 1);  // 1 x 1 (X_ITE's nominal size)
    CHECK(pointPixels("point_scaled",
                      "pointProperties PointProperties { pointSizeScaleFactor 3 "
                      "pointSizeMaxValue 10 }",
                      frames) == 9);  // 1 * 3 = 3 pixels wide
    // Attenuation 2 r^2 at r = 1 halves it: 4 / 2 = 2 pixels wide.
    CHECK(pointPixels("point_attenuated",
                      "pointProperties PointProperties { pointSizeScaleFactor 4 "
                      "pointSizeMaxValue 10 attenuation 0 0 2 }",
                      frames) == 4);
    // The minimum wins over a smaller computed size; the default maximum (1) caps a scale.
    CHECK(pointPixels("point_minimum", "pointProperties PointProperties { pointSizeMinValue 4 }",
                      frames) == 16);
    CHECK(pointPixels("point_capped", "pointProperties PointProperties { pointSizeScaleFactor 3 }",
                      frames) == 1);
  }
}
