// Text (6.47) as triangles (scene/text_mesh.hpp): holes, texture coordinates, the glyph
// cache, diagnostics, picking and worldTriangles.
#include "encodings/parser.hpp"
#include "scene/picking.hpp"
#include "scene/text_mesh.hpp"
#include "scene/world_triangles.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

namespace {

std::shared_ptr<gs::vrml::Scene> world(const std::string& body) {
  return std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml("#VRML V2.0 utf8\n" + body, "text.wrl"));
}

const gs::vrml::Node& textOf(const gs::vrml::Scene& s) {
  return *s.rootNodes.at(0)->sfnode("geometry");
}

double meshArea(const gs::vrml::Mesh& m) {
  double a = 0.0;
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::dvec3 p(m.positions[m.indices[t]]), q(m.positions[m.indices[t + 1]]),
        r(m.positions[m.indices[t + 2]]);
    a += 0.5 * glm::cross(q - p, r - p).z;  // > 0: counter-clockwise seen from +Z
  }
  return a;
}

bool covered(const gs::vrml::Mesh& m, glm::vec2 p) {
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    float d = 0, u = 0, v = 0;
    if (gs::scene::intersectTriangle(glm::vec3(p, 1.0f), {0, 0, -1}, m.positions[m.indices[t]],
                                     m.positions[m.indices[t + 1]], m.positions[m.indices[t + 2]],
                                     d, u, v))
      return true;
  }
  return false;
}

// Area of the outline's regions (outer loops minus holes), font units squared.
double outlineArea(const gs::formats::GlyphOutline& o) {
  double a = 0.0;
  for (const auto& r : o.regions) {
    std::size_t at = 0;
    for (std::int32_t n : r.loopLengths) {
      for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
        const glm::dvec2 s(r.points[at + i]),
            e(r.points[at + (i + 1) % static_cast<std::size_t>(n)]);
        a += 0.5 * (s.x * e.y - e.x * s.y);
      }
      at += static_cast<std::size_t>(n);
    }
  }
  return a;
}

}  // namespace

TEST_CASE("Text 'O' triangulates with its hole", "[scene][text]") {
  auto scene = world(
      R"(Shape { geometry Text { string "O" fontStyle FontStyle { size 2 family "SANS" } } })");
  gs::vrml::Diagnostics diag;
  const gs::vrml::Mesh m = gs::scene::tessellateText(textOf(*scene), &diag);
  CHECK(diag.items.empty());
  REQUIRE(m.triangleCount() > 20);
  CHECK_FALSE(m.solid);
  CHECK(m.normals.size() == m.positions.size());
  CHECK(m.normals[0] == glm::vec3(0, 0, 1));
  // Every triangle counter-clockwise seen from +Z; the area is the ring's area.
  for (std::size_t t = 0; t + 2 < m.indices.size(); t += 3) {
    const glm::vec3 &p = m.positions[m.indices[t]], &q = m.positions[m.indices[t + 1]],
                    &r = m.positions[m.indices[t + 2]];
    CHECK(glm::cross(q - p, r - p).z >= 0.0f);
  }
  const auto layout =
      gs::formats::sharedFontLibrary().layout({"O"}, gs::scene::textStyleOf(textOf(*scene)));
  const gs::formats::FaceInfo face =
      gs::formats::sharedFontLibrary().faceInfo(layout.glyphs.at(0).key.face);
  CHECK(face.family == "PT Sans");  // SANS (docs/text.md), 1000 units per em
  const double scale = 2.0 / face.unitsPerEm;
  const double ring =
      outlineArea(gs::formats::sharedFontLibrary().outline(layout.glyphs.at(0).key));
  CHECK(meshArea(m) == Approx(ring * scale * scale).epsilon(1e-4));
  // The bounding box is the line's layout box (advance by ascender..descender, as
  // castle-model-viewer frames Text), larger than the glyph's ink.
  gs::vrml::Bounds ink;
  for (const glm::vec3& p : m.positions) ink.extend(p);
  CHECK(m.bounds.min.x == Approx(layout.bounds.min.x));
  CHECK(m.bounds.max.x == Approx(layout.bounds.max.x));
  CHECK(m.bounds.min.y == Approx(layout.bounds.min.y));
  CHECK(m.bounds.max.y == Approx(layout.bounds.max.y));
  CHECK(m.bounds.min.y == Approx(face.descender * scale));  // PT Sans' descender
  CHECK(m.bounds.max.y == Approx(face.ascender * scale));   // and ascender
  CHECK(face.descender < 0.0f);
  CHECK(face.ascender > 0.5f * face.unitsPerEm);
  CHECK(m.bounds.min.y < ink.min.y - 0.3f);
  CHECK(m.bounds.max.y > ink.max.y + 0.3f);
  // The centre of the O is open, the ring is filled.
  const glm::vec3 c = ink.center();
  CHECK_FALSE(covered(m, {c.x, c.y}));
  CHECK(covered(m, {ink.min.x + 0.05f, c.y}));
  // 6.47: texture coordinates are the position over size from the first string's origin
  // (BEGIN / FIRST: the local origin).
  for (std::size_t i = 0; i < m.positions.size(); i += 7) {
    CHECK(m.texCoords[i].x == Approx(m.positions[i].x / 2.0f).margin(1e-6));
    CHECK(m.texCoords[i].y == Approx(m.positions[i].y / 2.0f).margin(1e-6));
  }
}

TEST_CASE("Text glyph triangulations are cached per face and glyph", "[scene][text]") {
  auto scene = world(R"(Shape { geometry Text { string "QQQ QQ" } })");
  gs::scene::tessellateText(textOf(*scene));
  const std::size_t before = gs::scene::cachedGlyphMeshCount();
  const gs::vrml::Mesh m = gs::scene::tessellateText(textOf(*scene));
  CHECK(gs::scene::cachedGlyphMeshCount() == before);
  auto single = world(R"(Shape { geometry Text { string "Q" } })");
  const gs::vrml::Mesh one = gs::scene::tessellateText(textOf(*single));
  CHECK(m.triangleCount() == 5 * one.triangleCount());  // the blank has no triangles
}

TEST_CASE("Text font problems are diagnostics, not failures", "[scene][text]") {
  auto scene = world(
      "Shape { geometry Text { string [ \"ok\" \"bad \xFF byte\" ]\n"
      "fontStyle FontStyle { family \"NoSuchFamilyAnywhere\" "
      "justify [ \"SIDEWAYS\" ] } } }");
  gs::vrml::Diagnostics diag;
  const gs::vrml::Mesh m = gs::scene::tessellateText(textOf(*scene), &diag);
  CHECK(m.triangleCount() > 0);
  REQUIRE(diag.items.size() == 3);
  std::string all;
  for (const auto& d : diag.items) all += d.message + "\n";
  CHECK(all.find("NoSuchFamilyAnywhere") != std::string::npos);
  CHECK(all.find("SIDEWAYS") != std::string::npos);
  CHECK(all.find("UTF-8") != std::string::npos);
  auto empty = world(R"(Shape { geometry Text { } })");
  CHECK(gs::scene::tessellateText(textOf(*empty)).positions.empty());
}

TEST_CASE("Text is picked and flattened like other geometry", "[scene][text][picking]") {
  auto scene = world(R"(Transform { translation 0 0 -1 children
    Shape { geometry Text { string "HI" fontStyle FontStyle { family "SANS" } } } })");
  gs::scene::SceneTraversal traversal(scene);
  const gs::scene::Camera viewer;
  // The left stem of the H: x in [0.098, 0.198] em in DejaVu Sans, y in [0, 0.729].
  const auto hit = gs::scene::pick(traversal, viewer, {{0.15f, 0.3f, 10.0f}, {0, 0, -1}});
  REQUIRE(hit);
  CHECK(hit->point.z == Approx(-1.0f));
  CHECK(hit->texCoord.x == Approx(0.15f).margin(1e-5));
  CHECK_FALSE(gs::scene::pick(traversal, viewer, {{0.4f, 0.6f, 10.0f}, {0, 0, -1}}));  // H's gap
  const auto tris = gs::scene::worldTriangles(scene);
  CHECK(tris.indices.size() / 3 > 10);
  for (const glm::vec3& p : tris.positions) CHECK(p.z == Approx(-1.0f));
}
