// X3D Layering (X3D 4.0 clause 35): a root LayerSet's layers drawn in its `order`, each
// over the previous with the depth buffer cleared, a Layer's Viewport clipping it to its
// clipBoundary; drawn off-screen at 64x64 (world_files.hpp).
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace fs = std::filesystem;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

/// The blue emissive wall 5 m behind the origin that fills the view (layeredWorld's).
constexpr const char* kBlueWall = R"(Transform {
        translation 0 0 -5
        children Shape {
          appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 0 0 1 } }
          geometry Box { size 100 100 0.1 }
        }
      })";

/// A world with a small red emissive box at the origin (layer 0) and, in a LayerSet, one
/// Layer holding `children` (by default a blue emissive wall 5 m behind the box that fills
/// the view); the viewer looks down -z from 10 m. `order` is the LayerSet's; `viewport`
/// the Layer's viewport field.
std::string layeredWorld(const std::string& order, const std::string& viewport = "",
                         const std::string& children = kBlueWall) {
  return R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT Layering:1
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 10 fieldOfView 0.785398 }
Shape {
  appearance Appearance { material Material { diffuseColor 0 0 0 emissiveColor 1 0 0 } }
  geometry Box { size 2 2 0.1 }
}
LayerSet {
  order [)" +
         order +
         R"(]
  layers [
    Layer {
      )" +
         viewport +
         R"(
      children )" +
         children + R"(
    }
  ]
}
)";
}

Rendered drawLayered(const std::string& name, const std::string& order,
                     const std::string& viewport = "") {
  const fs::path file = worldDir() / (name + ".x3dv");
  writeText(file, layeredWorld(order, viewport));
  return renderFile(file);
}

}  // namespace

TEST_CASE("Layering: layer numbers, order and clipBoundary from the traversal",
          "[render][layering]") {
  auto scene = std::make_shared<const gs::vrml::Scene>(gs::vrml::parseVrml(
      layeredWorld("1 0 7 -1 1", "viewport Viewport { clipBoundary [0 0.5 0.25 2] }"),
      "layers.x3dv"));
  // A LayerSet belongs at the root: no "not allowed at the root" warning.
  CHECK(scene->diagnostics.items.empty());
  gs::scene::SceneTraversal traversal(scene, {});
  gs::scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 2);
  CHECK(frame.shapes[0].layer == 0);  // the root's box
  CHECK(frame.shapes[1].layer == 1);  // the Layer's wall, 1-based (clause 35.4.2)
  // Indices out of range (7, -1) are skipped; a layer may be listed twice.
  REQUIRE(frame.layerOrder.size() == 3);
  CHECK(frame.layerOrder[0].number == 1);
  CHECK(frame.layerOrder[1].number == 0);
  CHECK(frame.layerOrder[2].number == 1);
  CHECK(frame.layerOrder[1].clipBoundary == glm::vec4(0, 1, 0, 1));
  CHECK(frame.layerOrder[0].clipBoundary == glm::vec4(0, 0.5f, 0.25f, 1));  // 2 clamped to 1
  CHECK(gs::scene::layerRectangle(frame.layerOrder[0].clipBoundary, 10, 20, 64, 64) ==
        glm::ivec4(10, 36, 32, 48));
  CHECK(gs::scene::layerRectangle(glm::vec4(0.75f, 0.25f, 0, 1), 0, 0, 64, 64).z == 0);

  // Without a LayerSet nothing is layered.
  auto plain = std::make_shared<const gs::vrml::Scene>(
      gs::vrml::parseVrml("#X3D V4.0 utf8\nShape { geometry Box {} }\n", "plain.x3dv"));
  gs::scene::SceneTraversal plainTraversal(plain, {});
  plainTraversal.collect(plainTraversal.boundViewpointCamera(), frame);
  CHECK(frame.layerOrder.empty());
  REQUIRE(frame.shapes.size() == 1);
  CHECK(frame.shapes[0].layer == 0);
}

TEST_CASE("Layering: a later layer is drawn over the root layer even when farther away",
          "[render][offscreen][world][layering]") {
  // The blue wall is 5 m behind the red box, but layer 1 comes after layer 0 and the depth
  // buffer is cleared between them: blue everywhere.
  const Rendered over = drawLayered("layers_over", "0 1");
  CHECK(over.diagnostics.items.empty());
  CHECK(close(over.image.pixel(32, 32), 0, 0, 255, 8));
  CHECK(close(over.image.pixel(2, 2), 0, 0, 255, 8));
}

TEST_CASE("Layering: the LayerSet's order chooses and orders the layers drawn",
          "[render][offscreen][world][layering]") {
  // The default order [0]: only the root layer; the red box on the black background.
  const Rendered root = drawLayered("layers_root_only", "0");
  CHECK(close(root.image.pixel(32, 32), 255, 0, 0, 8));
  CHECK(close(root.image.pixel(2, 2), 0, 0, 0, 8));
  // [1]: the root layer (its red box) is hidden.
  const Rendered one = drawLayered("layers_one_only", "1");
  CHECK(close(one.image.pixel(32, 32), 0, 0, 255, 8));
  CHECK(close(one.image.pixel(2, 2), 0, 0, 255, 8));
  // [1 0]: the root layer on top: the red box over the blue wall.
  const Rendered reversed = drawLayered("layers_reversed", "1 0");
  CHECK(close(reversed.image.pixel(32, 32), 255, 0, 0, 8));
  CHECK(close(reversed.image.pixel(2, 2), 0, 0, 255, 8));
}

TEST_CASE("Layering: a Viewport's clipBoundary restricts its layer to that rectangle",
          "[render][offscreen][world][layering]") {
  // The Layer clipped to the left half: blue there (over the red box's left half), the red
  // box's right half and the black background on the right.
  const Rendered half =
      drawLayered("layers_left_half", "0 1", "viewport Viewport { clipBoundary [0 0.5 0 1] }");
  CHECK(half.diagnostics.items.empty());
  CHECK(close(half.image.pixel(4, 32), 0, 0, 255, 8));
  CHECK(close(half.image.pixel(28, 32), 0, 0, 255, 8));
  CHECK(close(half.image.pixel(36, 32), 255, 0, 0, 8));
  CHECK(close(half.image.pixel(58, 32), 0, 0, 0, 8));
  CHECK(close(half.image.pixel(58, 4), 0, 0, 0, 8));
}

TEST_CASE(
    "Layering: a layer's Gaussian splats are drawn with its shapes, in its order and "
    "clipBoundary",
    "[render][offscreen][world][layering]") {
  // A green Gaussian 2 m in front of the red box, in layer 1. Its layer is drawn first
  // ([1 0]): the root layer's box is on top of it, nearer or not. Clipped to the left half
  // ([0 1]): green only there.
  const auto world = [](const std::string& order, const std::string& viewport) {
    return layeredWorld(order, viewport, R"(Transform { translation 0 0 2 children GaussianSplats {
        positions [ 0 0 0 ] orientations [ 0 0 0 1 ] scales [ 1.5 1.5 0.1 ] opacities [ 1 ]
        sphericalHarmonicsDegree0Coef0 [ -1.77 1.77 -1.77 ] } })");
  };
  const fs::path under = worldDir() / "layers_splats_under.x3dv";
  writeText(under, world("1 0", ""));
  const Rendered a = renderFile(under);
  CHECK(a.diagnostics.items.empty());
  CHECK(close(a.image.pixel(32, 32), 255, 0, 0, 8));  // the box over the nearer splat
  const auto g = a.image.pixel(32, 16);               // above the box: the splat's edge
  CHECK(int(g[1]) > 100);
  CHECK(int(g[0]) < 40);

  const fs::path clipped = worldDir() / "layers_splats_clipped.x3dv";
  writeText(clipped, world("0 1", "viewport Viewport { clipBoundary [ 0 0.5 0 1 ] }"));
  const Rendered b = renderFile(clipped);
  CHECK(b.diagnostics.items.empty());
  const auto left = b.image.pixel(28, 32), right = b.image.pixel(36, 32);
  CHECK(int(left[1]) > 200);  // the splat over the box
  CHECK(int(left[0]) < 40);
  CHECK(close(right, 255, 0, 0, 8));  // outside the Layer's rectangle: the box
}

TEST_CASE("Layering: the shapes of a layer after one with splats are drawn by their own program",
          "[render][offscreen][world][layering]") {
  // PhysicalMaterial boxes in layers 0 and 2 (one program, bound once per layer when the
  // renderer knows what is bound) and a Gaussian in layer 1 between them, whose paths bind
  // programs of their own: the right box must still be drawn green, in every frame.
  const fs::path file = worldDir() / "layers_programs.x3dv";
  writeText(file, R"(#X3D V4.0 utf8
PROFILE Immersive
COMPONENT Layering:1
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 10 fieldOfView 0.785398 }
Transform { translation -2 0 0 children Shape {
  appearance Appearance { material PhysicalMaterial { baseColor 0 0 0 emissiveColor 1 0 0 } }
  geometry Box { size 2 2 0.1 } } }
LayerSet { order [ 0 1 2 ] layers [
  Layer { children Transform { translation 0 3 0 children GaussianSplats {
    positions [ 0 0 0 ] orientations [ 0 0 0 1 ] scales [ 0.3 0.3 0.1 ] opacities [ 1 ]
    sphericalHarmonicsDegree0Coef0 [ -1.77 -1.77 1.77 ] } } }
  Layer { children Transform { translation 2 0 0 children Shape {
    appearance Appearance { material PhysicalMaterial { baseColor 0 0 0 emissiveColor 0 1 0 } }
    geometry Box { size 2 2 0.1 } } } }
] }
)");
  for (int frames : {1, 3}) {
    INFO("frames " << frames);
    const Rendered r = renderFile(file, frames);
    CHECK(r.diagnostics.items.empty());
    CHECK(close(r.image.pixel(17, 32), 255, 0, 0, 8));  // the left box, layer 0
    CHECK(close(r.image.pixel(47, 32), 0, 255, 0, 8));  // the right box, layer 2
    CHECK(int(r.image.pixel(32, 9)[2]) > 150);          // the splat, layer 1
  }
}

TEST_CASE("Layering: a layer other than the active one has its own NavigationInfo's headlight",
          "[render][offscreen][world][layering]") {
  // The world's NavigationInfo turns the headlight off. A grey wall lit only by a headlight
  // in layer 1 (not the active layer): with no NavigationInfo of its own the layer has the
  // default one's headlight (X3D 4.0 clause 35.2.1, as X_ITE 15 lights a HUD layer); with
  // its own NavigationInfo { headlight FALSE } it is dark.
  const std::string wall = R"(Transform {
        translation 0 0 -5
        children Shape {
          appearance Appearance { material Material { diffuseColor 0.5 0.5 0.5 ambientIntensity 0 } }
          geometry Box { size 100 100 0.1 }
        }
      })";
  const fs::path litFile = worldDir() / "layers_own_headlight.x3dv";
  writeText(litFile, layeredWorld("0 1", "", wall));
  const Rendered lit = renderFile(litFile);
  CHECK(lit.diagnostics.items.empty());
  CHECK(close(lit.image.pixel(2, 2), 128, 128, 128, 12));
  const fs::path darkFile = worldDir() / "layers_own_headlight_off.x3dv";
  writeText(darkFile,
            layeredWorld("0 1", "", "[ NavigationInfo { headlight FALSE } " + wall + " ]"));
  const Rendered dark = renderFile(darkFile);
  CHECK(close(dark.image.pixel(2, 2), 0, 0, 0, 8));
  // Layer 1, drawn after the root layer, covers its red box there too.
  CHECK(close(dark.image.pixel(32, 32), 0, 0, 0, 8));
}
