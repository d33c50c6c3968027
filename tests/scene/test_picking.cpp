// CPU picking (scene/picking.hpp): the nearest triangle, the path of grouping nodes with
// their matrices, misses, rays through pixels.
#include "encodings/parser.hpp"
#include "scene/picking.hpp"

#include <catch2/catch.hpp>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "vrml/transform.hpp"

#include <memory>

using gs::scene::Camera;
using gs::scene::pick;
using gs::scene::Ray;
using gs::scene::SceneTraversal;

namespace {

bool near(glm::vec3 a, glm::vec3 b, float eps = 1e-5f) {
  return glm::length(a - b) < eps;
}

bool nearMatrix(const glm::mat4& a, const glm::mat4& b) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (std::abs(a[c][r] - b[c][r]) > 1e-5f) return false;
  return true;
}

std::shared_ptr<gs::vrml::Scene> world(const std::string& body) {
  return std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml("#VRML V2.0 utf8\n" + body, "picking.wrl"));
}

const gs::vrml::Node* def(const gs::vrml::Scene& s, const std::string& name) {
  std::function<const gs::vrml::Node*(const gs::vrml::NodePtr&)> find =
      [&](const gs::vrml::NodePtr& n) -> const gs::vrml::Node* {
    if (!n) return nullptr;
    if (n->defName == name) return n.get();
    for (std::size_t i = 0; i < n->fieldCount(); ++i) {
      const auto& v = n->fieldAt(i);
      if (v.type() == gs::vrml::FieldType::SFNode)
        if (const auto* f = find(v.get<gs::vrml::FieldType::SFNode>())) return f;
      if (v.type() == gs::vrml::FieldType::MFNode)
        for (const auto& c : v.get<gs::vrml::FieldType::MFNode>())
          if (const auto* f = find(c)) return f;
    }
    return nullptr;
  };
  for (const auto& n : s.rootNodes)
    if (const auto* f = find(n)) return f;
  return nullptr;
}

constexpr const char* kWorld = R"(
DEF ROOT Transform { translation 0 0 -5 children [
  DEF NEAR Transform { translation 0 0 2 children [
    DEF TS TouchSensor {}
    DEF SN Shape { geometry Box { size 1 1 1 } }
  ] }
  DEF FAR Group { children DEF SF Shape { geometry Box { size 4 4 1 } } }
] }
)";

}  // namespace

TEST_CASE("picking: the nearest triangle, with its path and matrices", "[scene][picking]") {
  auto scene = world(kWorld);
  SceneTraversal traversal(scene);
  const Camera viewer;  // at 0 0 10 looking along -Z
  const auto hit = pick(traversal, viewer, Ray{{0.1f, 0.2f, 10.0f}, {0.0f, 0.0f, -1.0f}});
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "SN"));
  CHECK(near(hit->point, {0.1f, 0.2f, -2.5f}));
  CHECK(near(hit->normal, {0.0f, 0.0f, 1.0f}));
  CHECK(hit->distance == Approx(12.5f));
  CHECK(near(glm::vec3(hit->texCoord, 0.0f), {0.6f, 0.7f, 0.0f}));  // 6.4: front face s, t
  REQUIRE(hit->path.size() == 4);
  CHECK(hit->path[0].node == nullptr);
  CHECK(hit->path[0].children == &scene->rootNodes);
  CHECK(nearMatrix(hit->path[0].localToWorld, glm::mat4(1.0f)));
  CHECK(hit->path[1].node == def(*scene, "ROOT"));
  CHECK(nearMatrix(hit->path[1].localToWorld, glm::translate(glm::mat4(1.0f), {0, 0, -5})));
  CHECK(hit->path[2].node == def(*scene, "NEAR"));
  CHECK(nearMatrix(hit->path[2].localToWorld, glm::translate(glm::mat4(1.0f), {0, 0, -3})));
  CHECK(hit->path[3].node == def(*scene, "SN"));
  CHECK(nearMatrix(hit->path[3].localToWorld, glm::translate(glm::mat4(1.0f), {0, 0, -3})));
}

TEST_CASE("picking: beside the near box the far one; misses", "[scene][picking]") {
  auto scene = world(kWorld);
  SceneTraversal traversal(scene);
  const Camera viewer;
  const auto far = pick(traversal, viewer, Ray{{1.5f, 0.0f, 10.0f}, {0.0f, 0.0f, -2.0f}});
  REQUIRE(far);
  CHECK(far->shape == def(*scene, "SF"));
  CHECK(near(far->point, {1.5f, 0.0f, -4.5f}));
  CHECK(far->distance == Approx(14.5f));  // world units, whatever the direction's length
  REQUIRE(far->path.size() == 4);
  CHECK(far->path[2].node == def(*scene, "FAR"));
  CHECK(!pick(traversal, viewer, Ray{{5.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}}));
  CHECK(!pick(traversal, viewer, Ray{{0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, 1.0f}}));  // behind
  // From inside the far box, the near box's back face is hit first along +Z.
  const auto inside = pick(traversal, viewer, Ray{{0.0f, 0.0f, -5.0f}, {0.0f, 0.0f, 1.0f}});
  REQUIRE(inside);
  CHECK(inside->shape == def(*scene, "SF"));
  CHECK(near(inside->point, {0.0f, 0.0f, -4.5f}));
}

TEST_CASE("picking: only the chosen Switch child; rotated and scaled transforms",
          "[scene][picking]") {
  auto scene = world(R"(
DEF SW Switch { whichChoice 1 choice [
  Shape { geometry Box {} }
  DEF T Transform { rotation 0 1 0 1.5707963 scale 2 2 2 children
    DEF S Shape { geometry Sphere { radius 0.5 } } }
] }
)");
  SceneTraversal traversal(scene);
  const auto hit = pick(traversal, Camera{}, Ray{{0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}});
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "S"));
  CHECK(hit->point.z == Approx(1.0f).margin(2e-2));  // the tessellated sphere, radius 1
  CHECK(near(hit->normal, {0.0f, 0.0f, 1.0f}, 2e-2f));
  REQUIRE(hit->path.size() == 3);  // the root, T (no entry for the Switch), S
  CHECK(hit->path[1].node == def(*scene, "T"));
  const glm::vec3 x = glm::vec3(hit->path[1].localToWorld * glm::vec4(1, 0, 0, 0));
  CHECK(near(x, {0.0f, 0.0f, -2.0f}, 1e-5f));
}

TEST_CASE("picking: the ray through a pixel", "[scene][picking]") {
  Camera c;  // 0 0 10, fieldOfView 0.785398
  const Ray centre = gs::scene::rayThroughPixel(c, 200, 100, 100.0f, 50.0f);
  CHECK(near(centre.origin, {0.0f, 0.0f, 10.0f}));
  CHECK(near(centre.direction, {0.0f, 0.0f, -1.0f}));
  // The top edge's centre: half the vertical field of view up (aspect 2: vertical fov).
  const Ray top = gs::scene::rayThroughPixel(c, 200, 100, 100.0f, 0.0f);
  CHECK(std::atan2(top.direction.y, -top.direction.z) == Approx(0.785398f / 2.0f));
  const Ray right = gs::scene::rayThroughPixel(c, 200, 100, 200.0f, 50.0f);
  CHECK(right.direction.x / -right.direction.z == Approx(2.0f * std::tan(0.785398f / 2.0f)));
}

TEST_CASE("picking: Moller-Trumbore", "[scene][picking]") {
  float t = 0, u = 0, v = 0;
  CHECK(gs::scene::intersectTriangle({0.25f, 0.25f, 1}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0},
                                     t, u, v));
  CHECK(t == Approx(1.0f));
  CHECK(u == Approx(0.25f));
  CHECK(v == Approx(0.25f));
  CHECK(!gs::scene::intersectTriangle({0.75f, 0.75f, 1}, {0, 0, -1}, {0, 0, 0}, {1, 0, 0},
                                      {0, 1, 0}, t, u, v));
}

TEST_CASE(
    "picking: X3D's visible FALSE hides a node and its children, pointerEvents FALSE lets "
    "the pointer through",
    "[scene][picking]") {
  const auto x3d = [](const std::string& glassPointerEvents) {
    return std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
        "#X3D V4.0 utf8\nPROFILE Full\n"
        "DEF GLASS Transform { translation 0 0 2 children DEF GS Shape { pointerEvents " +
            glassPointerEvents +
            " geometry Box { size 4 4 0.1 } } }\n"
            "DEF HIDDEN Transform { translation 0 0 1 visible FALSE children Shape {"
            " geometry Box { size 4 4 0.1 } } }\n"
            "Transform { translation 0 0 0.5 children DEF HS Shape { visible FALSE"
            " geometry Box { size 4 4 0.1 } } }\n"
            "DEF BACK Shape { geometry Box { size 4 4 0.1 } }\n",
        "visible.x3dv"));
  };
  const Ray ray{{0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}};
  {
    auto scene = x3d("FALSE");
    REQUIRE(scene->diagnostics.items.empty());
    SceneTraversal traversal(scene);
    gs::scene::TraversalFrame frame;
    traversal.collect(Camera{}, frame);
    CHECK(frame.shapes.size() == 2);  // the glass and the back: nothing invisible is drawn
    const auto hit = pick(traversal, Camera{}, ray);
    REQUIRE(hit);
    CHECK(hit->shape == def(*scene, "BACK"));  // through the glass and the invisible boxes
  }
  {
    auto scene = x3d("TRUE");
    SceneTraversal traversal(scene);
    const auto hit = pick(traversal, Camera{}, ray);
    REQUIRE(hit);
    CHECK(hit->shape == def(*scene, "GS"));
  }
}

TEST_CASE("a Viewpoint under a scaled Transform sees that Transform's world unscaled",
          "[scene][picking][camera]") {
  // X_ITE's camera is the Viewpoint's whole matrix (create3000's Rendering/ClipPlane.x3d
  // puts its Viewpoint and shapes under Transform { scale 1 2 3 scaleOrientation ... }):
  // a point of the Transform's coordinates lands where it would with no Transform, and the
  // ray through that pixel meets it.
  const auto scene = world(R"(#X3D V4.0 utf8
PROFILE Immersive
DEF T Transform { translation 1 2 3 rotation 0.27 0.53 0.8 4 scale 1 2 3
  scaleOrientation 0.71 0.29 -0.64 1.13
  children Viewpoint { position 0.5 0.25 6 orientation 0 1 0 0.2 } }
)");
  SceneTraversal traversal(scene);
  const Camera camera = traversal.boundViewpointCamera();
  gs::scene::Camera plain;
  plain.position = {0.5f, 0.25f, 6.0f};
  plain.orientation = glm::angleAxis(0.2f, glm::vec3(0, 1, 0));
  const gs::vrml::Node& t = *def(*scene, "T");
  const glm::mat4 m = gs::vrml::transformMatrix(t);
  const auto pixel = [](const Camera& c, glm::vec3 p) {
    const glm::vec4 clip =
        gs::scene::projectionMatrix(c, 1.0f) * gs::scene::viewMatrix(c) * glm::vec4(p, 1.0f);
    return glm::vec2(clip) / clip.w;
  };
  for (const glm::vec3 local : {glm::vec3(0, 0, 0), glm::vec3(1, -0.5f, 0.5f)}) {
    INFO("local " << local.x << " " << local.y << " " << local.z);
    const glm::vec2 a = pixel(camera, glm::vec3(m * glm::vec4(local, 1.0f)));
    const glm::vec2 b = pixel(plain, local);
    CHECK(glm::length(a - b) < 1e-4f);
    // The ray through that pixel (100 x 100) meets the world point.
    const Ray ray =
        gs::scene::rayThroughPixel(camera, 100, 100, (a.x + 1.0f) * 50.0f, (1.0f - a.y) * 50.0f);
    const glm::vec3 to = glm::vec3(m * glm::vec4(local, 1.0f)) - ray.origin;
    CHECK(glm::length(glm::cross(glm::normalize(to), ray.direction)) < 1e-3f);
  }
}

TEST_CASE("a Viewpoint under a mirroring or flattening Transform keeps its turn only",
          "[scene][picking][camera]") {
  // The renderer winds every shape counterclockwise: a mirrored view would show solid
  // shapes inside out, and a flattened one has no inverse.
  for (const char* scale : {"-1 1 1", "1 0 1"}) {
    INFO(scale);
    const auto scene = world(std::string("#X3D V4.0 utf8\nPROFILE Immersive\n"
                                         "Transform { scale ") +
                             scale + " children Viewpoint { position 0 0 6 } }\n");
    SceneTraversal traversal(scene);
    CHECK(traversal.boundViewpointCamera().deform == glm::mat3(1.0f));
  }
}

TEST_CASE("picking: layers are picked as drawn, the top layer first", "[scene][picking]") {
  // Layer 1's box lies far behind the root layer's, but layer 1 is drawn over it; layer 2
  // is not pickable, nor is layer 5 on top of all (pointerEvents FALSE); layer 3 covers
  // everything but only in the right half of the window (its clipBoundary); layer 4 is not
  // in `order`. The camera is the default
  // Viewpoint's, from which the layers without one are seen as they are.
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V3.3 utf8
PROFILE Full
DEF BACK Shape { geometry Box { size 4 4 1 } }
LayerSet { order [ 0 1 3 2 5 ] layers [
  Layer { children Transform { translation 0 0 -20 children DEF FARBOX Shape { geometry Box { } } } }
  Layer { isPickable FALSE children DEF UNPICKABLE Shape { geometry Box { size 8 8 1 } } }
  Layer { viewport Viewport { clipBoundary [ 0.5 1 0 1 ] }
          children Transform { translation 0 0 -30 children DEF RIGHT Shape { geometry Box { size 20 20 1 } } } }
  Layer { children DEF UNLISTED Shape { geometry Box { size 9 9 1 } } }
  Layer { pointerEvents FALSE children DEF PASSED_THROUGH Shape { geometry Box { size 9 9 1 } } }
] }
)",
                                                                     "layers.x3dv"));
  std::string diagnostics;
  for (const auto& d : scene->diagnostics.items) diagnostics += d.format() + "\n";
  INFO(diagnostics);
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal traversal(scene);
  const Camera viewer;
  const Ray centre{{0.0f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}};
  const Ray aside{{1.5f, 0.0f, 10.0f}, {0.0f, 0.0f, -1.0f}};
  const glm::vec2 left(0.25f, 0.5f), right(0.75f, 0.5f);
  // In the left half, layer 3 is not there: layer 1's far box, not the nearer root box.
  auto hit = pick(traversal, viewer, centre, left);
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "FARBOX"));
  // Beside the far box, down to the root layer.
  hit = pick(traversal, viewer, aside, left);
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "BACK"));
  // In the right half (or with no pointer position), layer 3 is over layers 0 and 1.
  hit = pick(traversal, viewer, centre, right);
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "RIGHT"));
  hit = pick(traversal, viewer, aside);
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "RIGHT"));
}

TEST_CASE("picking: a LayoutLayer's shapes are picked where its view draws them",
          "[scene][picking][layout]") {
  // A LayoutLayer over the root's box: its layout is the top right quarter of its region
  // -1 .. 1, and the panel fills the middle half of it (the FRACTION scale: a unit is the
  // rectangle), 0.625 .. 0.875 of the window on each axis. A bearing through the window's
  // centre meets the root's box, one through the panel's centre the panel.
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(R"(#X3D V4.0 utf8
PROFILE Full
DEF BACK Shape { geometry Box { size 20 20 1 } }
LayerSet { order [ 0 1 ] layers LayoutLayer {
  layout Layout { align [ "RIGHT" "TOP" ] size [ 0.25 0.25 ] }
  children DEF PANEL Shape { geometry Rectangle2D { size 0.5 0.5 } } } }
)",
                                                                     "layout_pick.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal traversal(scene);
  traversal.setViewportSize(100, 100);
  const Camera viewer;  // at 0 0 10, a field of view of 45 degrees
  const float edge = std::tan(viewer.fieldOfView / 2.0f);
  const auto through = [&](float x, float y) {  // window fractions, 0 0 the bottom left
    const glm::vec3 d((2.0f * x - 1.0f) * edge, (2.0f * y - 1.0f) * edge, -1.0f);
    return Ray{{0.0f, 0.0f, 10.0f}, glm::normalize(d)};
  };
  auto hit = pick(traversal, viewer, through(0.5f, 0.5f), glm::vec2(0.5f, 0.5f));
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "BACK"));
  hit = pick(traversal, viewer, through(0.875f, 0.875f), glm::vec2(0.875f, 0.875f));
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "PANEL"));
  // Beside the panel, in its layout's rectangle but not on the shape: the root's box.
  hit = pick(traversal, viewer, through(0.97f, 0.97f), glm::vec2(0.97f, 0.97f));
  REQUIRE(hit);
  CHECK(hit->shape == def(*scene, "BACK"));
}
