// X3D Texture projection in the traversal (X3D 4.0 clause 42): a projector's frame and
// projection as X_ITE 15 computes them, and its scope (global: every shape of the layer;
// else its siblings and their descendants).
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <memory>

namespace {

std::shared_ptr<gs::vrml::Scene> projectorWorld(const std::string& body) {
  auto scene = std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\n" + body, "projectors.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  return scene;
}

glm::vec3 ndc(const glm::mat4& m, const glm::vec3& p) {
  const glm::vec4 c = m * glm::vec4(p, 1.0f);
  return glm::vec3(c) / c.w;
}

}  // namespace

TEST_CASE("texture projectors: frame, perspective and parallel projections",
          "[scene][x3d][projection]") {
  auto scene = projectorWorld(R"(
DEF P TextureProjector { location 1 2 3 direction 0 0 -1 fieldOfView 0.5 nearDistance 1
  texture PixelTexture { image 1 1 1 0xff } }
DEF Q TextureProjectorParallel { direction 1 0 0 upVector 0 1 0 fieldOfView -2 -1 2 1
  texture PixelTexture { image 1 1 1 0xff } }
DEF Off TextureProjector { on FALSE texture PixelTexture { image 1 1 1 0xff } }
DEF Bare TextureProjector { }
)");
  const auto& roots = scene->rootNodes;
  gs::scene::TextureProjectorInstance p, q, off, bare;
  REQUIRE(gs::scene::textureProjectorInstance(*roots[0], glm::mat4(1.0f), p));
  REQUIRE(gs::scene::textureProjectorInstance(*roots[1], glm::mat4(1.0f), q));
  CHECK_FALSE(gs::scene::textureProjectorInstance(*roots[2], glm::mat4(1.0f), off));
  CHECK_FALSE(gs::scene::textureProjectorInstance(*roots[3], glm::mat4(1.0f), bare));
  // Looking down -Z from (1, 2, 3), image top towards +Y.
  CHECK(p.projectorToWorld[3] == glm::vec4(1, 2, 3, 1));
  CHECK(p.projectorToWorld[2].z == Approx(1.0f));
  CHECK(p.projectorToWorld[1].y == Approx(1.0f));
  // A wide image (200 x 100): the field of view spans its height.
  const glm::mat4 wide = gs::scene::textureProjection(p, 200, 100);
  const float t = std::tan(0.25f);
  CHECK(ndc(wide, {0.0f, 5.0f * t, -5.0f}).y == Approx(1.0f));
  CHECK(ndc(wide, {10.0f * t, 0.0f, -5.0f}).x == Approx(1.0f));
  CHECK(ndc(wide, {0.0f, 0.0f, -1.0f}).z == Approx(-1.0f));  // on the near plane
  // A tall one (100 x 200): its width.
  const glm::mat4 tall = gs::scene::textureProjection(p, 100, 200);
  CHECK(ndc(tall, {5.0f * t, 0.0f, -5.0f}).x == Approx(1.0f));
  // Parallel, along +X (projector -Z): a square image widens the 4 x 2 area to 4 x 4.
  CHECK(q.projectorToWorld[2].x == Approx(-1.0f));
  const glm::mat4 square = gs::scene::textureProjection(q, 1, 1);
  CHECK(ndc(square, {2.0f, 2.0f, -3.0f}).x == Approx(1.0f));
  CHECK(ndc(square, {2.0f, 2.0f, -3.0f}).y == Approx(1.0f));
}

TEST_CASE("texture projectors: global ones reach every shape, others their siblings",
          "[scene][x3d][projection]") {
  auto scene = projectorWorld(R"(
Shape { geometry Box { } }
Group { children [
  TextureProjector { global FALSE texture PixelTexture { image 1 1 1 0xff } }
  Transform { children Shape { geometry Sphere { } } }
] }
Shape { geometry Cone { } }
TextureProjectorParallel { texture PixelTexture { image 1 1 1 0xff } }
)");
  gs::scene::SceneTraversal traversal(scene);
  gs::scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  REQUIRE(frame.shapes.size() == 3);
  REQUIRE(frame.projectors.size() == 2);
  REQUIRE(frame.globalProjectors.size() == 1);
  CHECK(frame.projectors[frame.globalProjectors[0]].parallel);
  CHECK(frame.shapes[0].projectorCount == 0);
  REQUIRE(frame.shapes[1].projectorCount == 1);
  CHECK_FALSE(frame.projectors[frame.scopedProjectors[frame.shapes[1].projectorBegin]].parallel);
  CHECK(frame.shapes[2].projectorCount == 0);
}
