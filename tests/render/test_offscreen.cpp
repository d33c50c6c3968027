// Off-screen pixels with OSMesa at 64x64 (llvmpipe renders on the CPU: keep them small).
// Set GS_RENDER_TEST_DUMP=dir to write each image there for a look.
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"
#include "render_test_util.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>

using namespace gs::test;
using gs::render::Image;
using gs::scene::Camera;

namespace {

constexpr int kSize = 64;

gs::render::GlContext& context() {
  static std::unique_ptr<gs::render::GlContext> c =
      gs::render::createOffscreenContext(kSize, kSize);
  c->makeCurrent();
  return *c;
}

void dump(const Image& img, const std::string& name) {
  if (const char* dir = std::getenv("GS_RENDER_TEST_DUMP"))
    gs::render::writePng((std::filesystem::path(dir) / (name + ".png")).string(), img);
}

Image render(const std::vector<NodePtr>& roots, const std::string& name,
             const Camera* camera = nullptr) {
  context();
  gs::render::SceneRenderer r(makeScene(roots), testRendererOptions());
  const Camera c = camera != nullptr ? *camera : r.boundViewpointCamera();
  r.draw(c, 0, 0, kSize, kSize);
  Image img = gs::render::readPixels(0, 0, kSize, kSize);
  dump(img, name);
  return img;
}

struct Rgb {
  int r, g, b;
};
Rgb at(const Image& img, int x, int y) {
  const std::uint8_t* p = img.pixel(x, y);
  return {p[0], p[1], p[2]};
}
bool close(Rgb a, Rgb b, int tolerance = 3) {
  return std::abs(a.r - b.r) <= tolerance && std::abs(a.g - b.g) <= tolerance &&
         std::abs(a.b - b.b) <= tolerance;
}
std::string str(Rgb c) {
  return std::to_string(c.r) + " " + std::to_string(c.g) + " " + std::to_string(c.b);
}

NodePtr emissive(NodePtr geometry, float r, float g, float b) {
  return shapeWith(std::move(geometry),
                   {{"emissiveColor", sfColor(r, g, b)}, {"diffuseColor", sfColor(0, 0, 0)}});
}

}  // namespace

TEST_CASE("an OSMesa context clears its framebuffer", "[render][offscreen]") {
  auto& c = context();
  CHECK(c.width() == kSize);
  CHECK(c.height() == kSize);
  const auto info = gs::render::glInfo();
  INFO(info.renderer << " / " << info.version);
  CHECK_FALSE(info.version.empty());
  glClearColor(0.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  const Image img = gs::render::readPixels(0, 0, kSize, kSize);
  CHECK(close(at(img, 0, 0), {0, 255, 0}, 0));
  CHECK(close(at(img, kSize - 1, kSize - 1), {0, 255, 0}, 0));
  CHECK_THROWS_WITH(gs::render::createOffscreenContext(0, 10), Catch::Contains("OSMesa"));
}

TEST_CASE("a red emissive box shows in the centre over the background", "[render][offscreen]") {
  auto sky = makeNode("Background", {{"skyColor", mfColor({{0, 0, 1}})}});
  const Image img = render({sky, emissive(makeNode("TestBox"), 1, 0, 0)}, "red_box");
  INFO("centre " << str(at(img, 32, 32)) << ", corner " << str(at(img, 0, 0)));
  CHECK(close(at(img, 32, 32), {255, 0, 0}));
  CHECK(close(at(img, 0, 0), {0, 0, 255}));
  CHECK(close(at(img, 63, 63), {0, 0, 255}));
}

TEST_CASE("solid TRUE culls back faces, solid FALSE draws them lit", "[render][offscreen]") {
  Camera behind;  // looking at the quad's back from -Z
  behind.position = {0, 0, -5};
  behind.orientation = glm::angleAxis(3.14159265f, glm::vec3(0, 1, 0));
  behind.nearClip = 0.1f;
  behind.farClip = 100.0f;
  auto quad = [](bool solid) {
    return shapeWith(makeNode("TestQuad", {{"solid", sfBool(solid)}}),
                     {{"diffuseColor", sfColor(1, 1, 1)}});
  };
  const Image culled = render({quad(true)}, "cull_solid", &behind);
  CHECK(close(at(culled, 32, 32), {0, 0, 0}));
  const Image twoSided = render({quad(false)}, "cull_two_sided", &behind);
  INFO("two-sided back face " << str(at(twoSided, 32, 32)));
  // The headlight shines on the flipped normal: full diffuse white.
  CHECK(close(at(twoSided, 32, 32), {255, 255, 255}, 6));
}

TEST_CASE("the headlight and scoped DirectionalLights light diffuse surfaces",
          "[render][offscreen]") {
  auto quad = [] {
    return shapeWith(makeNode("TestQuad", {{"size", sfVec2(8, 8)}}),
                     {{"diffuseColor", sfColor(0, 1, 0)}, {"ambientIntensity", sfFloat(0)}});
  };
  const Image headlit = render({quad()}, "light_headlight");
  CHECK(close(at(headlit, 32, 32), {0, 255, 0}, 6));

  auto dark = makeNode("NavigationInfo", {{"headlight", sfBool(false)}});
  const Image unlit = render({dark, quad()}, "light_none");
  CHECK(close(at(unlit, 32, 32), {0, 0, 0}));

  // A light at 60 degrees from the normal gives half the diffuse colour; it lights only
  // the Group it is in.
  auto light = makeNode("DirectionalLight", {{"direction", sfVec3(0, -0.8660254f, -0.5f)},
                                             {"color", sfColor(1, 1, 1)}});
  auto inGroup = makeNode("Group", {{"children", mfNode({light, quad()})}});
  const Image scoped = render({dark, inGroup}, "light_directional");
  INFO("directional " << str(at(scoped, 32, 32)));
  CHECK(close(at(scoped, 32, 32), {0, 128, 0}, 4));
  auto otherGroup = makeNode("Group", {{"children", mfNode({light})}});
  const Image outOfScope = render({dark, otherGroup, quad()}, "light_out_of_scope");
  CHECK(close(at(outOfScope, 32, 32), {0, 0, 0}));
}

TEST_CASE("transparent shapes blend over opaque ones", "[render][offscreen]") {
  auto back = emissive(makeNode("TestQuad", {{"z", sfFloat(-1)}}), 1, 0, 0);
  auto front =
      shapeWith(makeNode("TestQuad", {{"z", sfFloat(1)}}), {{"emissiveColor", sfColor(0, 0, 1)},
                                                            {"diffuseColor", sfColor(0, 0, 0)},
                                                            {"transparency", sfFloat(0.5f)}});
  // The transparent one comes first in the file: it must still be drawn last.
  const Image img = render({front, back}, "transparency");
  INFO("blend " << str(at(img, 32, 32)));
  CHECK(close(at(img, 32, 32), {128, 0, 128}, 3));
}

TEST_CASE("of two coplanar opaque shapes the later one shows", "[render][offscreen]") {
  // The depth test passes equal depths (GL_LEQUAL), as X_ITE's and castle-engine's do: a
  // button drawn on its panel in the same plane shows (X_ITE's PlayerControls test world).
  auto panel = emissive(makeNode("TestQuad", {{"size", sfVec2(4, 4)}}), 1, 0, 0);
  auto button = emissive(makeNode("TestQuad"), 0, 1, 0);
  const Image img = render({panel, button}, "coplanar");
  INFO("centre " << str(at(img, 32, 32)) << ", edge " << str(at(img, 20, 32)));
  CHECK(close(at(img, 32, 32), {0, 255, 0}));
  CHECK(close(at(img, 20, 32), {255, 0, 0}));
}

TEST_CASE("PixelTexture colours an unlit shape", "[render][offscreen]") {
  gs::vrml::SFImage image;
  image.width = 2;
  image.height = 2;
  image.components = 3;
  image.pixels = {0xFF0000, 0x00FF00, 0x0000FF, 0xFFFFFF};  // bottom row first
  auto texture = makeNode("PixelTexture", {{"image", FieldValue::make<FieldType::SFImage>(image)},
                                           {"repeatS", sfBool(false)},
                                           {"repeatT", sfBool(false)}});
  auto appearance = makeNode("Appearance", {{"texture", sfNode(texture)}});
  auto shape =
      makeNode("Shape", {{"appearance", sfNode(appearance)},
                         {"geometry", sfNode(makeNode("TestQuad", {{"size", sfVec2(8, 8)}}))}});
  const Image img = render({shape}, "pixel_texture");
  // The quad fills the view: the quadrants are the texels (image row 0 is the bottom).
  INFO("bottom-left " << str(at(img, 12, 52)) << " top-right " << str(at(img, 52, 12)));
  CHECK(close(at(img, 12, 52), {255, 0, 0}, 8));
  CHECK(close(at(img, 52, 52), {0, 255, 0}, 8));
  CHECK(close(at(img, 12, 12), {0, 0, 255}, 8));
  CHECK(close(at(img, 52, 12), {255, 255, 255}, 8));
}

TEST_CASE("Background sky and ground gradients", "[render][offscreen]") {
  auto bg = makeNode("Background", {{"skyColor", mfColor({{0, 0, 1}, {1, 1, 1}})},
                                    {"skyAngle", mfFloat({1.5707963f})},
                                    {"groundColor", mfColor({{0, 1, 0}, {0, 1, 0}})},
                                    {"groundAngle", mfFloat({1.5707963f})}});
  Camera up;  // looking straight up: the zenith is blue
  up.orientation = glm::angleAxis(1.5707963f, glm::vec3(1, 0, 0));
  const Image sky = render({bg}, "background_up", &up);
  CHECK(close(at(sky, 32, 32), {0, 0, 255}, 4));
  const Image level = render({bg}, "background_level");  // horizon across the middle
  CHECK(at(level, 32, 2).b > 200);                       // sky above
  CHECK(at(level, 32, 2).r > at(sky, 32, 32).r);         // whiter towards the horizon
  CHECK(close(at(level, 32, 60), {0, 255, 0}, 4));       // ground below
}

TEST_CASE("draw() only touches its viewport rectangle", "[render][offscreen]") {
  context();
  glClearColor(1.0f, 1.0f, 0.0f, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  gs::render::SceneRenderer r(makeScene({emissive(makeNode("TestBox"), 1, 0, 0)}),
                              testRendererOptions());
  r.draw(r.boundViewpointCamera(), 0, 0, kSize / 2, kSize);
  const Image img = gs::render::readPixels(0, 0, kSize, kSize);
  dump(img, "viewport");
  CHECK(close(at(img, 16, 32), {255, 0, 0}));  // box in the left half's centre
  CHECK(close(at(img, 48, 32), {255, 255, 0}));
  CHECK(r.trianglesDrawn() == 12);
  CHECK(r.statistics().shapes == 1);
}

TEST_CASE("lines and points are unlit in emissiveColor", "[render][offscreen]") {
  auto lines = emissive(makeNode("TestLines"), 1, 1, 0);
  const Image img = render({lines}, "lines");
  int yellow = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x)
      if (close(at(img, x, y), {255, 255, 0}, 10)) ++yellow;
  CHECK(yellow > 20);  // two diagonals about 15 pixels long
  auto points = emissive(makeNode("TestPoints"), 0, 1, 1);
  const Image p = render({points}, "points");
  CHECK(close(at(p, 32, 32), {0, 255, 255}, 10));
}

TEST_CASE("a texture with alpha is blended like a transparent material", "[render][offscreen]") {
  gs::vrml::SFImage image;
  image.width = 1;
  image.height = 1;
  image.components = 4;
  image.pixels = {0x0000FF80};  // blue, alpha 128
  auto texture = makeNode("PixelTexture", {{"image", FieldValue::make<FieldType::SFImage>(image)}});
  auto front = makeNode(
      "Shape", {{"appearance", sfNode(makeNode("Appearance", {{"texture", sfNode(texture)}}))},
                {"geometry", sfNode(makeNode("TestQuad", {{"z", sfFloat(1)}}))}});
  auto back = emissive(makeNode("TestQuad", {{"z", sfFloat(-1)}}), 1, 0, 0);
  const Image img = render({front, back}, "texture_alpha");
  INFO("blend " << str(at(img, 32, 32)));
  CHECK(close(at(img, 32, 32), {127, 0, 128}, 3));
}

namespace {
// Sets GHOSTSPACE_GL for one scope (restores what was there).
struct GlChoice {
  explicit GlChoice(const char* value) {
    if (const char* old = std::getenv("GHOSTSPACE_GL")) previous = old;
    setenv("GHOSTSPACE_GL", value, 1);
  }
  ~GlChoice() {
    if (previous.empty())
      unsetenv("GHOSTSPACE_GL");
    else
      setenv("GHOSTSPACE_GL", previous.c_str(), 1);
  }
  std::string previous;
};
}  // namespace

TEST_CASE("GHOSTSPACE_GL=egl draws through EGL what OSMesa draws", "[render][offscreen][egl]") {
  auto sky = makeNode("Background", {{"skyColor", mfColor({{0, 0, 1}})}});
  const std::vector<NodePtr> roots = {sky, emissive(makeNode("TestBox"), 1, 0, 0)};
  const Image osmesa = render(roots, "red_box_osmesa");
  std::unique_ptr<gs::render::GlContext> egl;
  {
    GlChoice choice("egl");
    try {
      egl = gs::render::createOffscreenContext(kSize, kSize);
    } catch (const std::runtime_error& e) {
      missingFixture(std::string("an EGL device (libEGL.so.1 and Mesa's or a GPU's driver): ") +
                     e.what());
      return;
    }
  }
  egl->makeCurrent();
  const auto info = gs::render::glInfo();
  INFO(info.renderer << " / " << info.version);
  Image drawn;
  {
    gs::render::SceneRenderer r(makeScene(roots), testRendererOptions());
    r.draw(r.boundViewpointCamera(), 0, 0, kSize, kSize);
    drawn = gs::render::readPixels(0, 0, kSize, kSize);
  }
  dump(drawn, "red_box_egl");
  CHECK(close(at(drawn, 32, 32), {255, 0, 0}));
  CHECK(close(at(drawn, 0, 0), {0, 0, 255}));
  int off = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) off += close(at(drawn, x, y), at(osmesa, x, y)) ? 0 : 1;
  CHECK(off == 0);
  egl.reset();
  context();  // OSMesa's again, for the cases after this one
}

TEST_CASE("an unknown GHOSTSPACE_GL is an error naming the choices", "[render][offscreen]") {
  GlChoice choice("vulkan");
  CHECK_THROWS_WITH(gs::render::createOffscreenContext(8, 8),
                    Catch::Contains("GHOSTSPACE_GL=vulkan") && Catch::Contains("osmesa") &&
                        Catch::Contains("egl"));
}
