// The OutlineGroup extension node (docs/vrml-extensions.md) in the traversal: outlines
// shown until their group's polygons arrive, RenderMode::outlines, hole tessellation.
#include "encodings/parser.hpp"
#include "geometry/geometry.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

using gs::scene::RenderMode;
using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;
using gs::scene::TraversalOptions;

namespace {

std::shared_ptr<const gs::vrml::Scene> parse(const std::string& text) {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(text, "/tmp/outline.wrl"));
  INFO(text);
  CHECK(scene->diagnostics.items.empty());
  return scene;
}

const std::string kHeader = "#VRML V2.0 utf8\n";
const std::string kOutline0 =
    "OutlineGroup { groupId 0 appearance Appearance { material Material {} }\n"
    "  outline [ 0 0 0, 2 0 0, 2 2 0, 0 2 0 ] }\n";
const std::string kPolygons0 =
    "OutlineGroup { groupId 0 children [ Shape { geometry IndexedFaceSet {\n"
    "  coord Coordinate { point [ 0 0 0, 2 0 0, 2 2 0, 0 2 0 ] } coordIndex [ 0 1 2 3 -1 ] } } ] "
    "}\n";
const std::string kPlainShape =
    "Shape { geometry IndexedFaceSet { coord Coordinate { point [ 5 0 0, 6 0 0, 6 1 0 ] }"
    " coordIndex [ 0 1 2 -1 ] } }\n";

std::size_t outlineShapes(const TraversalFrame& f) {
  std::size_t n = 0;
  for (const auto& s : f.shapes)
    if (s.geometry->typeName() == "OutlineGroup") ++n;
  return n;
}

}  // namespace

TEST_CASE("an outline is drawn until its group's polygons arrive", "[scene][outline]") {
  TraversalFrame frame;
  {
    SceneTraversal t(parse(kHeader + kOutline0 + kPlainShape));
    t.collect(t.boundViewpointCamera(), frame);
    REQUIRE(frame.shapes.size() == 2);
    REQUIRE(outlineShapes(frame) == 1);
    const auto& s = frame.shapes[0];
    CHECK(s.geometry == s.shape);
    REQUIRE(s.appearance != nullptr);
    CHECK(s.appearance->typeName() == "Appearance");
    const gs::vrml::Mesh& m = t.mesh(*s.geometry);
    CHECK(m.triangleCount() == 2);
    CHECK_FALSE(m.solid);
    REQUIRE(m.normals.size() == m.positions.size());
    CHECK(m.normals[0].z == Approx(1.0f));
  }
  {
    SceneTraversal t(parse(kHeader + kOutline0 + kPlainShape + kPolygons0));
    t.collect(t.boundViewpointCamera(), frame);
    CHECK(outlineShapes(frame) == 0);
    CHECK(frame.shapes.size() == 2);  // the plain shape and the group's polygons
  }
  {  // another group's polygons do not hide this outline; groupId -1 draws both
    const std::string other =
        "OutlineGroup { groupId 1 children [ Shape { geometry Box {} } ] }\n"
        "OutlineGroup { outline [ 0 0 1, 1 0 1, 1 1 1 ] children [ Shape { geometry Box {} } ] }\n";
    SceneTraversal t(parse(kHeader + kOutline0 + other));
    t.collect(t.boundViewpointCamera(), frame);
    CHECK(outlineShapes(frame) == 2);
    CHECK(frame.shapes.size() == 4);
  }
}

TEST_CASE("outlines mode draws only outlines and shapes outside outline groups",
          "[scene][outline]") {
  TraversalOptions options;
  options.mode = RenderMode::outlines;
  SceneTraversal t(parse(kHeader + kOutline0 + kPlainShape + kPolygons0), options);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  CHECK(outlineShapes(frame) == 1);
  REQUIRE(frame.shapes.size() == 2);
  CHECK(frame.shapes[1].geometry->typeName() == "IndexedFaceSet");  // the plain shape

  options.mode = RenderMode::splats;  // same as polygons for outline groups
  SceneTraversal s(parse(kHeader + kOutline0 + kPolygons0), options);
  s.collect(s.boundViewpointCamera(), frame);
  CHECK(outlineShapes(frame) == 0);
  CHECK(frame.shapes.size() == 1);
}

TEST_CASE("an outline with a hole is tessellated around the hole", "[scene][outline]") {
  // A 4x4 square with a 2x2 hole in the middle (hole given counter-clockwise: the
  // orientation of later loops does not matter).
  const std::string text = kHeader +
                           "OutlineGroup { groupId 3 outline [ 0 0 0, 4 0 0, 4 4 0, 0 4 0,"
                           " 1 1 0, 3 1 0, 3 3 0, 1 3 0 ] outlineLengths [ 4 4 ] }\n";
  SceneTraversal t(parse(text));
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 1);
  const gs::vrml::Mesh& m = t.mesh(*frame.shapes[0].geometry);
  REQUIRE(m.triangleCount() >= 8);
  double area = 0.0;
  for (std::size_t i = 0; i < m.indices.size(); i += 3) {
    const glm::vec3 a = m.positions[m.indices[i]], b = m.positions[m.indices[i + 1]],
                    c = m.positions[m.indices[i + 2]];
    const glm::vec3 n = glm::cross(b - a, c - a);
    CHECK(n.z > 0.0f);  // counter-clockwise about the outline's normal
    area += 0.5 * static_cast<double>(n.z);
    // no triangle covers the hole's centre region
    const glm::vec3 centroid = (a + b + c) / 3.0f;
    CHECK_FALSE((centroid.x > 1.0f && centroid.x < 3.0f && centroid.y > 1.0f && centroid.y < 3.0f));
  }
  CHECK(area == Approx(12.0));

  // Two holes, and lengths longer than the points (cut short, with a warning).
  gs::vrml::Diagnostics diag;
  const std::vector<glm::vec3> pts = {{0, 0, 0}, {10, 0, 0}, {10, 4, 0}, {0, 4, 0},
                                      {1, 1, 0}, {3, 1, 0},  {3, 3, 0},  {1, 3, 0},
                                      {6, 1, 0}, {8, 1, 0},  {8, 3, 0},  {6, 3, 0}};
  const gs::vrml::Mesh two = gs::vrml::triangulateOutline(pts, {4, 4, 4});
  double area2 = 0.0;
  for (std::size_t i = 0; i < two.indices.size(); i += 3)
    area2 += 0.5 * static_cast<double>(
                       glm::cross(two.positions[two.indices[i + 1]] - two.positions[two.indices[i]],
                                  two.positions[two.indices[i + 2]] - two.positions[two.indices[i]])
                           .z);
  CHECK(area2 == Approx(40.0 - 8.0));
  (void)gs::vrml::triangulateOutline(pts, {4, 40}, &diag);
  CHECK(diag.warningCount() == 1);
}

TEST_CASE("the extension fallback PROTOs and a world declaring them parse cleanly",
          "[scene][outline]") {
  const std::string dir = std::string(GS_SOURCE_DIR) + "/assets/worlds/";
  const gs::vrml::Scene protos = gs::vrml::loadVrmlFile(dir + "ghostspace-extensions.wrl");
  CHECK(protos.diagnostics.items.empty());
  CHECK(protos.protos.size() == 2);
  const std::string world =
      kHeader +
      "EXTERNPROTO OutlineGroup [ eventIn MFNode addChildren eventIn MFNode removeChildren\n"
      "  exposedField MFNode children exposedField SFNode appearance field SFInt32 groupId\n"
      "  field MFVec3f outline field MFInt32 outlineLengths field SFVec3f bboxCenter\n"
      "  field SFVec3f bboxSize ]\n"
      "  [ \"urn:ghostspace:OutlineGroup\" \"ghostspace-extensions.wrl#OutlineGroup\" ]\n"
      "OutlineGroup { groupId 0 children [ Shape { geometry Box {} } ] }\n";
  const auto scene =
      std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, dir + "uses-extensions.wrl"));
  CHECK(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  CHECK(frame.shapes.size() == 1);  // the fallback Group shows the polygons
}
