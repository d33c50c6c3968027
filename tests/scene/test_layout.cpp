// X3D Layout (X3D 4.0 clause 36): the placement of a Layout in its parent rectangle
// (scene/layout.hpp) worked by hand, and a LayoutLayer's and a ScreenGroup's shapes at the
// pixels they ask for, at two window sizes, through the traversal and the camera's
// projection.
#include "encodings/parser.hpp"
#include "scene/camera.hpp"
#include "scene/layout.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <glm/glm.hpp>

#include <memory>
#include <string>

using Catch::Detail::Approx;
using gs::scene::LayoutPlacement;
using gs::scene::LayoutRectangle;
using gs::scene::placeLayout;
using gs::scene::viewRectangle;

namespace {

gs::vrml::NodePtr layoutNode(const std::string& fields) {
  const gs::vrml::Scene s =
      gs::vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\nLayout { " + fields + " }\n", "l.x3dv");
  REQUIRE(s.diagnostics.items.empty());
  REQUIRE(s.rootNodes.size() == 1);
  return s.rootNodes[0];
}

// Where `local` (a point of shape `i`'s coordinates) lands on a `w` x `h` view of the
// world's camera: pixels from the left and from the top.
glm::vec2 pixelOf(const std::string& world, int w, int h, std::size_t i, glm::vec3 local) {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(world, "layout.x3dv"));
  gs::scene::SceneTraversal t(scene);
  t.setViewportSize(w, h);
  gs::scene::TraversalFrame frame;
  const gs::scene::Camera camera = t.boundViewpointCamera();
  t.collect(camera, frame);
  REQUIRE(frame.shapes.size() > i);
  const glm::vec4 clip = gs::scene::projectionMatrix(camera, float(w) / float(h)) *
                         gs::scene::viewMatrix(camera) * frame.shapes[i].model *
                         glm::vec4(local, 1.0f);
  const glm::vec2 ndc = glm::vec2(clip) / clip.w;
  return {(ndc.x + 1.0f) / 2.0f * float(w), (1.0f - ndc.y) / 2.0f * float(h)};
}

/// A world's first lines: a LayoutLayer whose PIXEL layout is a 200x60-pixel panel 10
/// pixels in from the top left corner; the layer's `children` field and its closing braces
/// follow.
constexpr const char* kPanelLayer = R"(#X3D V4.0 utf8
PROFILE Full
Viewpoint { position 0 0 6 }
LayerSet { order [ 0 1 ] layers LayoutLayer {
  layout Layout { align [ "LEFT" "TOP" ] offsetUnits "PIXEL" offset [ 10 -10 ]
                  sizeUnits "PIXEL" size [ 200 60 ] scaleMode "PIXEL" })";

}  // namespace

TEST_CASE("Layout: a view's rectangle spans its smaller side, the larger sees more",
          "[scene][x3d][layout]") {
  const LayoutRectangle r = viewRectangle({400, 300}, 2.0f);
  CHECK(r.size.x == Approx(8.0f / 3.0f));
  CHECK(r.size.y == Approx(2.0f));
  CHECK(r.metresPerPixel.x == Approx(2.0f / 300.0f));
  CHECK(r.top);
}

TEST_CASE("Layout: pixel sizes and offsets against the top left corner, at two view widths",
          "[scene][x3d][layout]") {
  const auto layout = layoutNode(
      R"(align [ "LEFT" "TOP" ] offsetUnits [ "PIXEL" "PIXEL" ] offset [ 10 -10 ]
         sizeUnits [ "PIXEL" "PIXEL" ] size [ 200 60 ] scaleMode [ "PIXEL" "PIXEL" ])");
  const float px = 2.0f / 300.0f;  // a pixel, in metres of a 300-pixel-high view 2 m high
  for (const float width : {400.0f, 640.0f}) {
    const LayoutPlacement p = placeLayout(*layout, viewRectangle({width, 300}, 2.0f));
    const float half = width / 300.0f;  // half the view's width, metres
    CHECK(p.rectangle.size.x == Approx(200 * px));
    CHECK(p.rectangle.size.y == Approx(60 * px));
    // The rectangle's centre: 10 + 100 pixels from the left, 10 + 30 from the top.
    CHECK(p.translation.x == Approx(-half + 110 * px));
    CHECK(p.translation.y == Approx(1.0f - 40 * px));
    CHECK(p.scale.x == Approx(px));
    CHECK(p.scale.y == Approx(px));
    CHECK_FALSE(p.keepScale[0]);
  }
}

TEST_CASE("Layout: the defaults fill the parent; WORLD units and NONE inside another Layout",
          "[scene][x3d][layout]") {
  const LayoutRectangle view = viewRectangle({400, 300}, 2.0f);
  // Top level: size 1 1 WORLD is FRACTION of the view, scaleMode NONE is FRACTION.
  const LayoutPlacement whole = placeLayout(*layoutNode(""), view);
  CHECK(whole.rectangle.size.x == Approx(view.size.x));
  CHECK(whole.rectangle.size.y == Approx(2.0f));
  CHECK(whole.translation == glm::vec2(0.0f));
  CHECK(whole.scale.x == Approx(view.size.x));
  // Inside a PIXEL-sized Layout, WORLD is PIXEL; NONE keeps the scale in force; RIGHT
  // BOTTOM puts a 20-pixel square in the parent's corner.
  const LayoutPlacement parent =
      placeLayout(*layoutNode(R"(sizeUnits "PIXEL" size [ 100 50 ] scaleMode "PIXEL")"), view);
  const LayoutPlacement child =
      placeLayout(*layoutNode(R"(align [ "RIGHT" "BOTTOM" ] size [ 20 20 ])"), parent.rectangle);
  const float px = 2.0f / 300.0f;
  CHECK(child.rectangle.size.x == Approx(20 * px));
  CHECK(child.translation.x == Approx(40 * px));   // (100 - 20) / 2 pixels right
  CHECK(child.translation.y == Approx(-15 * px));  // (50 - 20) / 2 pixels down
  CHECK(child.keepScale[0]);
  CHECK(child.keepScale[1]);
  // STRETCH in x takes y's scale; in both, the larger side's.
  const LayoutPlacement stretch =
      placeLayout(*layoutNode(R"(size [ 0.5 0.25 ] scaleMode [ "STRETCH" "FRACTION" ])"), view);
  CHECK(stretch.scale.x == Approx(0.5f));  // y's: a quarter of 2 m
  const LayoutPlacement both =
      placeLayout(*layoutNode(R"(size [ 0.5 0.25 ] scaleMode "STRETCH")"), view);
  CHECK(both.scale.x == Approx(0.5f * view.size.x));
  CHECK(both.scale.y == Approx(0.5f * view.size.x));
}

TEST_CASE("LayoutLayer and ScreenGroup shapes land on the pixels their layout names",
          "[scene][x3d][layout]") {
  const std::string world = std::string(kPanelLayer) + R"(
  children Shape { geometry Rectangle2D { size 200 60 } } } }
Transform { translation 1 0 0 children ScreenGroup { children Shape {
  geometry Rectangle2D { size 16 16 } } } }
)";
  for (const int width : {400, 640}) {
    INFO("width " << width);
    // Shape 0 is the ScreenGroup's (the root layer's shapes come first), shape 1 the panel.
    const glm::vec2 topLeft = pixelOf(world, width, 300, 1, {-100, 30, 0});
    const glm::vec2 bottomRight = pixelOf(world, width, 300, 1, {100, -30, 0});
    CHECK(topLeft.x == Approx(10.0f).margin(0.01));
    CHECK(topLeft.y == Approx(10.0f).margin(0.01));
    CHECK(bottomRight.x == Approx(210.0f).margin(0.01));
    CHECK(bottomRight.y == Approx(70.0f).margin(0.01));
    // The ScreenGroup: 16 units are 16 pixels, wherever its origin projects.
    const glm::vec2 a = pixelOf(world, width, 300, 0, {-8, 0, 0});
    const glm::vec2 b = pixelOf(world, width, 300, 0, {8, 0, 0});
    CHECK(b.x - a.x == Approx(16.0f).margin(0.01));
  }
}

TEST_CASE("A LayoutLayer holding a viewpoint is seen through it, its layout in that view",
          "[scene][x3d][layout]") {
  // An OrthoViewpoint whose region is 4 m high (1 m is 75 of 300 pixels), 1 m right of the
  // layer's origin. Depths in a layer are compressed in front of the world's camera, so a
  // shape 10 m from the layer's viewpoint lands within a pixel of its orthographic place
  // (traversal_walk.hpp layerWithOwnView).
  const std::string world = std::string(kPanelLayer) + R"(
  children [
    OrthoViewpoint { position 1 0 10 fieldOfView [ -2 -2 2 2 ] }
    Shape { geometry Rectangle2D { size 200 60 } } ] } }
)";
  for (const int width : {300, 400}) {
    INFO("width " << width);
    // The PIXEL layout places its child by pixels from the view's top left corner, from
    // the layer's origin as the viewpoint sees it (X_ITE's Layout keeps the model-view
    // origin): 75 pixels left of where the default view puts it.
    const glm::vec2 topLeft = pixelOf(world, width, 300, 0, {-100, 30, 0});
    const glm::vec2 bottomRight = pixelOf(world, width, 300, 0, {100, -30, 0});
    CHECK(topLeft.x == Approx(10.0f - 75.0f).margin(1.0));
    CHECK(topLeft.y == Approx(10.0f).margin(1.0));
    CHECK(bottomRight.x - topLeft.x == Approx(200.0f).margin(1.0));
    CHECK(bottomRight.y - topLeft.y == Approx(60.0f).margin(1.0));
  }
  // Without a layout: the layer's metres are the OrthoViewpoint's, seen from 1 m right.
  const std::string plain = R"(#X3D V4.0 utf8
PROFILE Full
Viewpoint { position 0 0 6 }
LayerSet { order [ 0 1 ] layers LayoutLayer { children [
  OrthoViewpoint { position 1 0 10 fieldOfView [ -2 -2 2 2 ] }
  Shape { geometry Rectangle2D { size 1 1 } } ] } }
)";
  const glm::vec2 a = pixelOf(plain, 300, 300, 0, {-0.5f, 0.5f, 0});
  const glm::vec2 b = pixelOf(plain, 300, 300, 0, {0.5f, -0.5f, 0});
  CHECK(b.x - a.x == Approx(75.0f).margin(0.5));
  CHECK(b.y - a.y == Approx(75.0f).margin(0.5));
  CHECK((a.x + b.x) / 2.0f == Approx(150.0f - 75.0f).margin(0.5));
  CHECK((a.y + b.y) / 2.0f == Approx(150.0f).margin(0.5));
  // The default view (no viewpoint in the layer): the region -1 .. 1, the square centred.
  const std::string none = R"(#X3D V4.0 utf8
PROFILE Full
Viewpoint { position 0 0 6 }
LayerSet { order [ 0 1 ] layers LayoutLayer { children
  Shape { geometry Rectangle2D { size 1 1 } } } }
)";
  const glm::vec2 c = pixelOf(none, 300, 300, 0, {-0.5f, 0.5f, 0});
  const glm::vec2 d = pixelOf(none, 300, 300, 0, {0.5f, -0.5f, 0});
  CHECK(d.x - c.x == Approx(150.0f).margin(0.01));
  CHECK((c.x + d.x) / 2.0f == Approx(150.0f).margin(0.01));
}

TEST_CASE("Text in a ScreenFontStyle is measured in pixels outside a ScreenGroup too",
          "[scene][x3d][layout]") {
  // X3D 4.0 clause 36.4.5, as X_ITE's ScreenText draws it (create3000's
  // EnvironmentalSensor/TransformSensor.x3d labels its axes so): 16 units of the text's
  // coordinates are 16 pixels at any distance and any scale of its Transform. A FontStyle's
  // text stays in the world's metres.
  const auto world = [](const std::string& fontStyle) {
    return "#X3D V4.0 utf8\nPROFILE Full\nViewpoint { position 0 0 6 }\n"
           "Transform { translation 1 0 -4 scale 3 3 3 children Shape { geometry Text { "
           "string \"A\" fontStyle " +
           fontStyle + " } } }\n";
  };
  for (const int width : {400, 640}) {
    INFO("width " << width);
    const std::string screen = world("ScreenFontStyle { pointSize 12 }");
    const glm::vec2 a = pixelOf(screen, width, 300, 0, {0, 0, 0});
    const glm::vec2 b = pixelOf(screen, width, 300, 0, {16, 0, 0});
    CHECK(b.x - a.x == Approx(16.0f).margin(0.01));
    // A FontStyle of size 1 at 10 m, scaled 3: 16 units are far more than 16 pixels.
    const std::string metres = world("FontStyle { }");
    const float wide =
        pixelOf(metres, width, 300, 0, {16, 0, 0}).x - pixelOf(metres, width, 300, 0, {0, 0, 0}).x;
    CHECK(wide > 500.0f);
  }
}
