// Scene traversal on the CPU: node maths, grouping nodes, LOD, lights, bindables, Inline.
#include "base/data_url.hpp"
#include "encodings/parser.hpp"
#include "render_test_util.hpp"
#include "scene/picking.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>

using namespace gs::test;
using gs::scene::Camera;
using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;

namespace {
bool near(glm::vec3 a, glm::vec3 b, float eps = 1e-4f) {
  return glm::length(a - b) < eps;
}
glm::vec3 apply(const glm::mat4& m, glm::vec3 p) {
  return glm::vec3(m * glm::vec4(p, 1.0f));
}
NodePtr box() {
  return makeNode("TestBox", {{"size", sfVec3(2, 2, 2)}});
}
NodePtr shape(NodePtr g = box()) {
  return makeNode("Shape", {{"geometry", sfNode(g)}});
}
gs::scene::TraversalOptions options() {
  gs::scene::TraversalOptions o;
  o.tessellator = &testTessellate;
  return o;
}
constexpr float kHalfPi = 1.5707963f;
}  // namespace

TEST_CASE("Transform follows clause 6.52's order", "[render][traversal]") {
  auto t = makeNode("Transform", {{"translation", sfVec3(1, 2, 3)},
                                  {"rotation", sfRotation(0, 0, 1, kHalfPi)},
                                  {"scale", sfVec3(2, 1, 1)},
                                  {"center", sfVec3(1, 0, 0)}});
  const glm::mat4 m = gs::scene::transformMatrix(*t);
  // The centre stays put under rotation and scale, then translates.
  CHECK(near(apply(m, {1, 0, 0}), {2, 2, 3}));
  // (2,0,0): 1 from the centre along X, scaled to 2, rotated to +Y, back by the centre.
  CHECK(near(apply(m, {2, 0, 0}), {1 + 1, 2 + 2, 3}));
  // scaleOrientation rotates the axes of the scale.
  auto so = makeNode("Transform", {{"scale", sfVec3(2, 1, 1)},
                                   {"scaleOrientation", sfRotation(0, 0, 1, kHalfPi)}});
  const glm::mat4 s = gs::scene::transformMatrix(*so);
  CHECK(near(apply(s, {0, 1, 0}), {0, 2, 0}));
  CHECK(near(apply(s, {1, 0, 0}), {1, 0, 0}));
  // Missing fields read as their defaults: identity.
  CHECK(gs::scene::transformMatrix(*makeNode("Transform")) == glm::mat4(1.0f));
}

TEST_CASE("LOD level selection per clause 6.26", "[render][traversal]") {
  using gs::scene::selectLodLevel;
  const std::vector<float> range{10.0f, 20.0f};
  CHECK(selectLodLevel(range, 5.0f, 3) == 0);
  CHECK(selectLodLevel(range, 10.0f, 3) == 1);
  CHECK(selectLodLevel(range, 15.0f, 3) == 1);
  CHECK(selectLodLevel(range, 25.0f, 3) == 2);
  CHECK(selectLodLevel(range, 25.0f, 2) == 1);  // fewer levels than ranges + 1
  CHECK(selectLodLevel({}, 100.0f, 3) == 0);
  CHECK(selectLodLevel(range, 5.0f, 0) == -1);
}

TEST_CASE("Billboard rotations turn local Z towards the viewer", "[render][traversal]") {
  using gs::scene::billboardRotation;
  // Around +Y, viewer on +X: local +Z turns to +X.
  glm::mat4 r = billboardRotation({0, 1, 0}, {5, 3, 0}, {0, 1, 0});
  CHECK(near(glm::mat3(r) * glm::vec3(0, 0, 1), {1, 0, 0}));
  CHECK(near(glm::mat3(r) * glm::vec3(0, 1, 0), {0, 1, 0}));
  // Viewer on the axis: no rotation.
  CHECK(billboardRotation({0, 1, 0}, {0, 5, 0}, {0, 0, 1}) == glm::mat4(1.0f));
  // Screen-aligned: Z to the viewer, Y to the viewer's up.
  r = billboardRotation({0, 0, 0}, {0, 0, -5}, {1, 0, 0});
  CHECK(near(glm::mat3(r) * glm::vec3(0, 0, 1), {0, 0, -1}));
  CHECK(near(glm::mat3(r) * glm::vec3(0, 1, 0), {1, 0, 0}));
}

TEST_CASE("TextureTransform order is -C S R C T", "[render][traversal]") {
  auto tt = makeNode(
      "TextureTransform",
      {{"translation", sfVec2(0.5f, 0)}, {"scale", sfVec2(2, 2)}, {"center", sfVec2(0.5f, 0.5f)}});
  const glm::mat3 m = gs::scene::textureTransformMatrix(*tt);
  // (0,0): translate to (0.5,0), +C (1,0.5), rotate, scale (2,1), -C: (1.5,0.5)
  const glm::vec3 p = m * glm::vec3(0, 0, 1);
  CHECK(p.x == Approx(1.5f));
  CHECK(p.y == Approx(0.5f));
  auto rot = makeNode("TextureTransform", {{"rotation", sfFloat(kHalfPi)}});
  const glm::vec3 q = gs::scene::textureTransformMatrix(*rot) * glm::vec3(1, 0, 1);
  CHECK(q.x == Approx(0.0f).margin(1e-6));
  CHECK(q.y == Approx(1.0f));
}

TEST_CASE("the parser and the renderer resolve a URL the same way", "[render][traversal][url]") {
  // One resolver (base/url.hpp): an EXTERNPROTO and an Inline naming the same reference
  // from the same world reach their loaders as the same URL.
  const std::string world = "http://h.org/w/sub/world.wrl";
  const std::string text =
      "#VRML V2.0 utf8\nEXTERNPROTO P [] \"../protos/./p.wrl\"\n"
      "Inline { url \"../protos/./p.wrl\" }\n";
  std::string parserUrl;
  gs::base::CallbackFetcher parserFetcher(
      [&](const std::string& url, const std::string&, gs::base::FetchMode) {
        parserUrl = url;
        return gs::base::fetchFailed(url + ": not served here");
      });
  gs::vrml::ParseOptions parse;
  parse.fetcher = &parserFetcher;
  auto scene = std::make_shared<const gs::vrml::Scene>(gs::vrml::parseVrml(text, world, parse));
  std::string rendererUrl;
  gs::base::CallbackFetcher rendererFetcher(
      [&](const std::string& url, const std::string&, gs::base::FetchMode) {
        rendererUrl = url;
        return gs::base::fetchFailed(url + ": not served here");
      });
  gs::scene::TraversalOptions options;
  options.fetcher = &rendererFetcher;
  gs::scene::SceneTraversal traversal(scene, options);
  gs::scene::TraversalFrame frame;
  traversal.collect(traversal.boundViewpointCamera(), frame);
  CHECK(parserUrl == "http://h.org/w/protos/p.wrl");
  CHECK(rendererUrl == parserUrl);
}

TEST_CASE("traversal applies transforms and chooses Switch and LOD children",
          "[render][traversal]") {
  auto inner = shape();
  auto far = shape(makeNode("TestBox", {{"size", sfVec3(1, 1, 1)}}));
  auto root = makeNode(
      "Transform",
      {{"translation", sfVec3(10, 0, 0)},
       {"children",
        mfNode({makeNode("Group", {{"children", mfNode({inner})}}),
                makeNode("Switch", {{"whichChoice", sfInt(1)},
                                    {"choice", mfNode({shape(), shape(), shape()})}}),
                makeNode("Switch", {{"whichChoice", sfInt(-1)}, {"choice", mfNode({shape()})}}),
                makeNode("LOD", {{"range", mfFloat({20.0f})},
                                 {"center", sfVec3(0, 0, 0)},
                                 {"level", mfNode({shape(), far})}})})}});
  auto unresolved = shape();
  unresolved->unresolved = true;
  auto unknown = makeNode("SomethingElse", {{"children", mfNode({shape()})}});
  SceneTraversal t(makeScene({root, unresolved, unknown}), options());
  TraversalFrame frame;
  Camera viewer;  // at (0,0,10): 14.1 m from the LOD centre (10,0,0)
  t.collect(viewer, frame);
  REQUIRE(frame.shapes.size() == 3);  // Group child, Switch choice 1, LOD level 0
  CHECK(frame.shapes[0].shape == inner.get());
  CHECK(near(apply(frame.shapes[0].model, {0, 0, 0}), {10, 0, 0}));
  viewer.position = {10, 0, 30};
  t.collect(viewer, frame);
  REQUIRE(frame.shapes.size() == 3);
  CHECK(frame.shapes[2].shape == far.get());

  const auto& b = t.worldBounds();
  CHECK(near(b.min, {9, -1, -1}));
  CHECK(near(b.max, {11, 1, 1}));
}

TEST_CASE("DirectionalLight lights only its siblings; point lights are global",
          "[render][traversal]") {
  auto lit = shape();
  auto unlit = shape();
  auto light = makeNode("DirectionalLight", {{"direction", sfVec3(0, -1, 0)}});
  auto off = makeNode("DirectionalLight", {{"on", sfBool(false)}});
  auto point = makeNode("PointLight", {{"location", sfVec3(1, 0, 0)}, {"radius", sfFloat(5)}});
  auto group =
      makeNode("Transform", {{"rotation", sfRotation(0, 0, 1, kHalfPi)},
                             {"scale", sfVec3(2, 2, 2)},
                             {"children", mfNode({makeNode("Group", {{"children", mfNode({lit})}}),
                                                  light, off, point})}});
  SceneTraversal t(makeScene({group, unlit}), options());
  TraversalFrame frame;
  t.collect(Camera{}, frame);
  REQUIRE(frame.shapes.size() == 2);
  const auto& a = frame.shapes[0];
  REQUIRE(a.scopedLightCount == 1);
  const auto& l = frame.lights[frame.scopedLights[a.scopedLightBegin]];
  CHECK(l.type == gs::scene::LightType::directional);
  CHECK(near(l.direction, {1, 0, 0}));  // rotated by the Transform
  CHECK(frame.shapes[1].scopedLightCount == 0);
  REQUIRE(frame.globalLights.size() == 1);
  const auto& p = frame.lights[frame.globalLights[0]];
  CHECK(p.type == gs::scene::LightType::point);
  CHECK(near(p.location, {0, 2, 0}));
  CHECK(p.radius == Approx(10.0f));  // scaled with the Transform
}

TEST_CASE("a point light of negative radius reaches everywhere", "[render][traversal]") {
  // glTF's lights without a range come to X3D as radius -1 (castle-model-viewer's
  // blender_custom_properties.x3dv); X_ITE lights them at any distance.
  auto point = makeNode("PointLight", {{"radius", sfFloat(-1)}});
  SceneTraversal t(makeScene({point, shape()}), options());
  TraversalFrame frame;
  t.collect(Camera{}, frame);
  REQUIRE(frame.globalLights.size() == 1);
  CHECK(frame.lights[frame.globalLights[0]].radius > 1.0e20f);
}

TEST_CASE("the first Viewpoint, NavigationInfo, Background and Fog are bound",
          "[render][traversal]") {
  SECTION("defaults") {
    SceneTraversal t(makeScene({shape()}), options());
    CHECK(t.viewpoints().empty());
    const Camera c = t.boundViewpointCamera();
    CHECK(near(c.position, {0, 0, 10}));
    CHECK(c.fieldOfView == Approx(0.785398f));
    CHECK(c.nearClip == Approx(0.125f));
    CHECK(c.farClip > 11.0f);
    CHECK(t.navigation().headlight);
    CHECK(t.fog().visibilityRange == 0.0f);
    CHECK(t.background().skyColor.size() == 1);
  }
  SECTION("inside Transforms") {
    auto vp1 = makeNode("Viewpoint", {{"position", sfVec3(0, 0, 5)},
                                      {"orientation", sfRotation(0, 1, 0, kHalfPi)},
                                      {"description", sfString("first")}});
    auto vp2 = makeNode("Viewpoint", {{"position", sfVec3(1, 1, 1)}});
    auto nav = makeNode("NavigationInfo", {{"headlight", sfBool(false)},
                                           {"avatarSize", mfFloat({1.0f, 1.6f, 0.75f})},
                                           {"type", mfString({"EXAMINE"})}});
    auto fog = makeNode("Fog", {{"fogType", sfString("EXPONENTIAL")},
                                {"visibilityRange", sfFloat(50)},
                                {"color", sfColor(1, 0, 0)}});
    auto root = makeNode("Transform", {{"translation", sfVec3(0, 10, 0)},
                                       {"scale", sfVec3(2, 2, 2)},
                                       {"children", mfNode({vp1, nav, fog, shape()})}});
    SceneTraversal t(makeScene({root, vp2, makeNode("NavigationInfo")}), options());
    REQUIRE(t.viewpoints().size() == 2);
    CHECK(t.viewpoints()[0].description == "first");
    CHECK(t.viewpoints()[1].description == "Viewpoint 2");
    const Camera c = t.boundViewpointCamera();
    CHECK(near(c.position, {0, 10, 10}));
    CHECK(near(c.forward(), {-1, 0, 0}));
    CHECK(c.nearClip == Approx(0.5f));
    CHECK_FALSE(t.navigation().headlight);
    CHECK(t.navigation().type == std::vector<std::string>{"EXAMINE"});
    CHECK(t.fog().exponential);
    CHECK(t.fog().visibilityRange == Approx(100.0f));
  }
}

TEST_CASE("Inline loads once, resolves relative URLs and survives failures",
          "[render][traversal]") {
  std::vector<std::string> loads;
  gs::base::CallbackFetcher fetcher(
      [&](const std::string& url, const std::string& referrer, gs::base::FetchMode mode) {
        loads.push_back(url);
        CHECK(mode == gs::base::FetchMode::whole);  // no session: the traversal reads whole
        CHECK_FALSE(referrer.empty());
        if (url == "/w/sub/a.wrl")
          return gs::base::fetchReady(
              "#VRML V2.0 utf8\nInline { url \"../b.wrl\" }\nShape { geometry Box { } }\n");
        if (url == "/w/b.wrl")
          return gs::base::fetchReady(
              "#VRML V2.0 utf8\nShape { geometry Box { } }\nInline { url \"sub/a.wrl\" }\n");
        return gs::base::fetchFailed("cannot read " + url + ": no such file");
      });
  gs::scene::TraversalOptions o;
  o.fetcher = &fetcher;
  auto root = makeNode("Inline", {{"url", mfString({"missing.wrl", "sub/a.wrl"})}});
  auto gone = makeNode("Inline", {{"url", mfString({"gone.wrl"})}});
  SceneTraversal t(makeScene({root, gone}, "/w/main.wrl"), o);
  CHECK_FALSE(t.loadedInline(*root));  // not met yet: loadedInline loads nothing
  TraversalFrame frame;
  t.collect(Camera{}, frame);
  // The worlds loaded, as audio::SoundScene asks for them.
  REQUIRE(t.loadedInline(*root));
  CHECK(t.loadedInline(*root)->url == "/w/sub/a.wrl");
  CHECK_FALSE(t.loadedInline(*gone));
  // a.wrl's shape and b.wrl's shape; b.wrl inlining a.wrl again is a recursion: cut.
  CHECK(frame.shapes.size() == 2);
  CHECK(*frame.shapes[0].baseUrl == "/w/b.wrl");
  CHECK(*frame.shapes[1].baseUrl == "/w/sub/a.wrl");
  t.collect(Camera{}, frame);
  CHECK(loads ==
        std::vector<std::string>{"/w/missing.wrl", "/w/sub/a.wrl", "/w/b.wrl", "/w/gone.wrl"});
  bool recursion = false, missing = false;
  for (const auto& d : t.diagnostics().items) {
    if (d.message.find("includes itself") != std::string::npos) recursion = true;
    if (d.message.find("gone.wrl") != std::string::npos) missing = true;
  }
  CHECK(recursion);
  CHECK(missing);
}

TEST_CASE("the default Inline loader reads local files only", "[render][traversal]") {
  gs::scene::TraversalOptions o = options();
  SceneTraversal t(
      makeScene({makeNode("Inline", {{"url", mfString({"http://example.org/x.wrl"})}})}), o);
  TraversalFrame frame;
  t.collect(Camera{}, frame);
  CHECK(frame.shapes.empty());
  REQUIRE(t.diagnostics().items.size() == 1);
  CHECK(t.diagnostics().items[0].message.find("only local files") != std::string::npos);
}

TEST_CASE("X3D's 3D texture transforms act on (s, t, 0, 1)", "[render][traversal]") {
  const auto matrixOf = [](const std::string& transform) {
    const gs::vrml::Scene scene = gs::vrml::parseVrml(
        "#X3D V4.0 utf8\nPROFILE Full\nShape { appearance Appearance { textureTransform " +
            transform + " } }\n",
        "tt.x3dv");
    for (const auto& d : scene.diagnostics.items) FAIL_CHECK(d.format());
    const auto& appearance = scene.rootNodes.at(0)->sfnode("appearance");
    REQUIRE(appearance);
    return gs::scene::textureTransformMatrix(*appearance->sfnode("textureTransform"));
  };
  // Row by row in the file, for row vectors (as castle-model-viewer and X_ITE read it):
  // scale (2, 3), translation (0.5, 0.25) in the last row.
  glm::vec3 p =
      matrixOf("TextureTransformMatrix3D { matrix 2 0 0 0  0 3 0 0  0 0 1 0  0.5 0.25 0 1 }") *
      glm::vec3(1, 1, 1);
  CHECK(p.x == Approx(2.5f));
  CHECK(p.y == Approx(3.25f));
  // The 2D case above, in 3D: (0, 0) goes to (1.5, 0.5).
  p = matrixOf("TextureTransform3D { translation 0.5 0 0 scale 2 2 1 center 0.5 0.5 0 }") *
      glm::vec3(0, 0, 1);
  CHECK(p.x == Approx(1.5f));
  CHECK(p.y == Approx(0.5f));
}

TEST_CASE("OrthoViewpoint binds an orthographic camera showing its region", "[render][traversal]") {
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#X3D V4.0 utf8\nPROFILE Immersive\n"
      "OrthoViewpoint { position 0 0 10 fieldOfView [ -1 -1 4 4 ] }\nShape { geometry Box { } }\n",
      "ortho.x3dv"));
  gs::scene::SceneTraversal traversal(scene, options());
  REQUIRE(traversal.viewpoints().size() == 1);
  const gs::scene::Camera c = traversal.boundViewpointCamera();
  CHECK(c.orthographic);
  CHECK(c.orthoRegion == glm::vec4(-1, -1, 4, 4));
  // The region fills a square viewport exactly: (4, 4, z) is the top right corner.
  const glm::mat4 p = gs::scene::projectionMatrix(c, 1.0f) * gs::scene::viewMatrix(c);
  const glm::vec4 corner = p * glm::vec4(4, 4, 0, 1);
  CHECK(corner.x / corner.w == Approx(1.0f));
  CHECK(corner.y / corner.w == Approx(1.0f));
  // A wider viewport sees more across, the same vertically.
  const glm::vec4 wide =
      gs::scene::projectionMatrix(c, 2.0f) * gs::scene::viewMatrix(c) * glm::vec4(4, 4, 0, 1);
  CHECK(wide.x / wide.w == Approx(0.5f));  // (4 - 1.5) / 5
  CHECK(wide.y / wide.w == Approx(1.0f));
  // Picking rays are parallel to the view direction.
  const gs::scene::Ray a = gs::scene::rayThroughPixel(c, 100, 100, 0, 0);
  const gs::scene::Ray b = gs::scene::rayThroughPixel(c, 100, 100, 100, 100);
  CHECK(a.direction == b.direction);
  CHECK(a.origin.x == Approx(-1.0f));
  CHECK(b.origin.x == Approx(4.0f));
}

TEST_CASE("an Inlined file keeps its own length unit inside a file in kilometres",
          "[render][traversal]") {
  const auto dir = std::filesystem::temp_directory_path() / "gs_units_inline";
  std::filesystem::create_directories(dir);
  // The outer file is in km: its box is 2 m wide. The inlined file (no UNIT) is in metres:
  // its box, 4 m to the right, is 2 m wide too (X3D clause 4.3.6; castle's units.x3dv).
  std::ofstream(dir / "outer.x3dv")
      << "#X3D V3.3 utf8\nPROFILE Interchange\nUNIT length km 1000\n"
         "Shape { geometry Box { size 0.002 0.002 0.002 } }\nInline { url \"inner.x3dv\" }\n";
  std::ofstream(dir / "inner.x3dv")
      << "#X3D V3.3 utf8\nPROFILE Interchange\n"
         "Transform { translation 4 0 0 children Shape { geometry Box { } } }\n";
  auto scene =
      std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile((dir / "outer.x3dv").string()));
  gs::scene::SceneTraversal traversal(scene, gs::scene::TraversalOptions{});
  const gs::vrml::Bounds& b = traversal.worldBounds();
  CHECK(b.min.x == Approx(-1.0f));
  CHECK(b.max.x == Approx(5.0f));
  CHECK(b.max.y == Approx(1.0f));
}

TEST_CASE("a data: Inline in a remote world reads no local file either",
          "[render][traversal][url]") {
  // A world from the network may name a data: URL (it holds its bytes), but the world in it
  // is that remote content still: the local file its own Inline names is not read.
  const auto local = std::filesystem::temp_directory_path() / "gs_data_inline_secret.wrl";
  std::ofstream(local) << "#VRML V2.0 utf8\nShape { geometry Box { } }\n";
  const std::string inner = "#VRML V2.0 utf8\nInline { url \"file://" + local.string() + "\" }\n";
  auto dataInline =
      makeNode("Inline", {{"url", mfString({gs::base::makeDataUrl("model/vrml", inner)})}});
  SceneTraversal remote(makeScene({dataInline}, "http://example.com/w.wrl"), options());
  TraversalFrame frame;
  remote.collect(Camera{}, frame);
  CHECK(frame.shapes.empty());
  bool refused = false;
  for (const auto& d : remote.diagnostics().items)
    refused = refused || d.message.find("may only reference http(s) URLs") != std::string::npos;
  CHECK(refused);
  // A data: URL carries no trace of who named it: in a local world too, its world names
  // http(s) and data: URLs only. The data: Inline in it is read.
  const std::string nested =
      "#VRML V2.0 utf8\nInline { url \"" +
      gs::base::makeDataUrl("model/vrml", "#VRML V2.0 utf8\nShape { geometry Box { } }\n") +
      "\" }\nInline { url \"file://" + local.string() + "\" }\n";
  auto nestedInline =
      makeNode("Inline", {{"url", mfString({gs::base::makeDataUrl("model/vrml", nested)})}});
  SceneTraversal localWorld(makeScene({nestedInline}, "/w/main.wrl"), options());
  localWorld.collect(Camera{}, frame);
  CHECK(frame.shapes.size() == 1);
  std::filesystem::remove(local);
}
