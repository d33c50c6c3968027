// session::WorldView without a window: an off-screen context, a StreamingSession and
// WorldRuntimes, frames at fixed times, pixels read back.
#include "http/fault_server.hpp"
#include "http/nginx_server.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "session/streaming_session.hpp"
#include "session/world_runtime.hpp"
#include "session/world_view.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <cstdlib>
#include <memory>
#include <string>

using gs::render::Image;
using gs::session::StreamingSession;
using gs::session::ViewGroup;
using gs::session::WorldRuntimes;
using gs::session::WorldView;

namespace {

constexpr int kSize = 64;

gs::render::GlContext& context() {
  static auto c = gs::render::createOffscreenContext(kSize, kSize);
  c->makeCurrent();
  return *c;
}

/// One viewport of one world, with its own session and execution models.
struct Viewer {
  StreamingSession session;
  ViewGroup group{session};
  // Script files through the session's loader, as the window and --snapshot read them.
  WorldRuntimes runtimes{gs::session::RuntimeOptions{}, &session.loader()};
  std::unique_ptr<WorldView> view;

  explicit Viewer(const std::string& path) {
    std::string error;
    auto scene = session.open(path, error);
    REQUIRE(scene);
    view = std::make_unique<WorldView>(group, scene, gs::render::SceneRendererOptions{});
    view->setRect(0, 0, kSize, kSize);
    // As --snapshot: the world loads whole, then runs from time 0.
    settle(0.0);
    group.attachRuntimes(runtimes, 0.0, true);
  }

  /// frame(time) until a pump finds nothing arriving and nothing more was asked for; the
  /// pixels of the last frame.
  Image settle(double time) {
    for (int i = 0; i < 2000; ++i) {
      const bool changed = view->frame(time);
      if (!changed && group.settled()) return gs::render::readPixels(0, 0, kSize, kSize);
      if (!changed) session.loader().wait(0.01);
    }
    FAIL("the view did not settle");
    return {};
  }
};

}  // namespace

TEST_CASE("a WorldView loads the Inline a Script's Switch choice shows at initialize",
          "[session][offscreen][world_view]") {
  context();
  gs::test::TempDir dir("world-view");
  dir.write("part.wrl",
            "#VRML V2.0 utf8\n"
            "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
            "        geometry Box { size 4 4 4 } }\n");
  const std::string main =
      dir.write("main.wrl",
                "#VRML V2.0 utf8\n"
                "Viewpoint { position 0 0 12 }\n"
                "DEF SW Switch { whichChoice -1 choice [ Inline { url \"part.wrl\" } ] }\n"
                "DEF S Script { eventOut SFInt32 choice\n"
                "  url \"javascript: function initialize() { choice = 0; }\" }\n"
                "ROUTE S.choice TO SW.set_whichChoice\n");
  Viewer v(main);
  Image image = v.settle(0.0);
  CHECK(v.view->renderer().traversal().inlineScenes().size() == 1);
  if (const char* out = std::getenv("GS_RENDER_TEST_DUMP"))
    gs::render::writePng(std::string(out) + "/world_view_switch.png", image);
  const std::uint8_t* p = image.pixel(kSize / 2, kSize / 2);
  INFO("centre " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]));
  CHECK(p[0] > 100);
  CHECK(p[1] < 60);
  CHECK(p[2] < 60);
}

TEST_CASE("a Script whose url file is on its way starts when it arrives, holding no frame",
          "[session][offscreen][world_view][script][http]") {
  context();
  gs::test::NginxServer server;
  if (!server.ok()) return;  // reported as a missing fixture
  server.writeFile("part.wrl",
                   "#VRML V2.0 utf8\n"
                   "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
                   "        geometry Box { size 4 4 4 } }\n");
  server.writeFile("choose.js", "function initialize() { choice = 0; }\n");
  server.writeFile("main.wrl",
                   "#VRML V2.0 utf8\n"
                   "Viewpoint { position 0 0 12 }\n"
                   "DEF SW Switch { whichChoice -1 choice [ Inline { url \"part.wrl\" } ] }\n"
                   "DEF S Script { eventOut SFInt32 choice url \"choose.js\" }\n"
                   "ROUTE S.choice TO SW.set_whichChoice\n");
  Viewer v(server.url("/main.wrl"));
  gs::runtime::ExecutionModel& model = v.runtimes.of(v.view->scene(), 0.0);
  // The model was made without waiting for choose.js: the Script waits for it.
  CHECK(model.scriptsArriving() == 1);
  Image image = v.settle(0.0);
  CHECK(model.scriptsArriving() == 0);
  CHECK(model.diagnostics().items.empty());
  CHECK(v.view->renderer().traversal().inlineScenes().size() == 1);
  const std::uint8_t* p = image.pixel(kSize / 2, kSize / 2);
  INFO("centre " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]));
  CHECK(p[0] > 100);
  CHECK(p[1] < 60);
}

TEST_CASE("an animated world at fixed times gives the same pixels through two WorldViews",
          "[session][offscreen][world_view]") {
  context();
  gs::test::TempDir dir("world-view");
  const std::string main =
      dir.write("anim.wrl",
                "#VRML V2.0 utf8\n"
                "Viewpoint { position 0 0 12 }\n"
                "DEF T Transform { children Shape {\n"
                "  appearance Appearance { material Material { diffuseColor 0 1 0 } }\n"
                "  geometry Box { size 2 2 2 } } }\n"
                "DEF TS TimeSensor { cycleInterval 2 loop TRUE }\n"
                "DEF PI PositionInterpolator { key [ 0 1 ] keyValue [ -3 0 0, 3 0 0 ] }\n"
                "ROUTE TS.fraction_changed TO PI.set_fraction\n"
                "ROUTE PI.value_changed TO T.set_translation\n");
  Viewer a(main);
  Viewer b(main);
  const Image a1 = a.settle(0.5);
  const Image b1 = b.settle(0.5);
  const Image a2 = a.settle(1.5);
  const Image b2 = b.settle(1.5);
  if (const char* out = std::getenv("GS_RENDER_TEST_DUMP")) {
    gs::render::writePng(std::string(out) + "/world_view_a1.png", a1);
    gs::render::writePng(std::string(out) + "/world_view_b1.png", b1);
    gs::render::writePng(std::string(out) + "/world_view_a2.png", a2);
    gs::render::writePng(std::string(out) + "/world_view_b2.png", b2);
  }
  const bool same1 = a1.rgba == b1.rgba, same2 = a2.rgba == b2.rgba;
  CHECK(same1);
  CHECK(same2);
  // The box moved between the two times (x -1.5 at 0.5 s, 1.5 at 1.5 s): left of the
  // centre, then right of it.
  CHECK(a1.pixel(kSize / 2 - 12, kSize / 2)[1] > 100);
  CHECK(a1.pixel(kSize / 2 + 12, kSize / 2)[1] < 30);
  CHECK(a2.pixel(kSize / 2 - 12, kSize / 2)[1] < 30);
  CHECK(a2.pixel(kSize / 2 + 12, kSize / 2)[1] > 100);
}

TEST_CASE("a ROUTE to an IMPORTed node runs once the Inline that EXPORTs it has arrived",
          "[session][offscreen][world_view][x3d]") {
  context();
  gs::test::TempDir dir("world-view-import");
  dir.write("part.x3dv",
            "#X3D V4.0 utf8\n"
            "DEF Mover Transform { children Shape {\n"
            "  appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
            "  geometry Box { size 2 2 2 } } }\n"
            "EXPORT Mover AS Moved\n");
  const std::string main =
      dir.write("main.x3dv",
                "#X3D V4.0 utf8\n"
                "Viewpoint { position 0 0 12 }\n"
                "DEF I Inline { url \"part.x3dv\" }\n"
                "IMPORT I.Moved AS M\n"
                "DEF T TimeSensor { loop TRUE cycleInterval 4 }\n"
                "DEF P PositionInterpolator { key [ 0 1 ] keyValue [ -4 0 0, 4 0 0 ] }\n"
                "ROUTE T.fraction_changed TO P.set_fraction\n"
                "ROUTE P.value_changed TO M.set_translation\n");
  Viewer v(main);
  REQUIRE(v.view->scene()->x3d.importedRoutes.size() == 1);
  // At t = 1 s the box is a quarter of the way (x = -2): left of centre; at 3 s right.
  auto redColumns = [](const Image& im) {
    int left = 0, right = 0;
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        const std::uint8_t* p = im.pixel(x, y);
        if (p[0] > 120 && p[1] < 60 && p[2] < 60) (x < kSize / 2 ? left : right) += 1;
      }
    return std::pair<int, int>(left, right);
  };
  const auto at1 = redColumns(v.settle(1.0));
  const auto at3 = redColumns(v.settle(3.0));
  CHECK(at1.first > 0);
  CHECK(at1.second == 0);
  CHECK(at3.second > 0);
  CHECK(at3.first == 0);
}

TEST_CASE("LoadSensors hear of the Inlines and textures a WorldView loaded, and of failures",
          "[session][offscreen][world_view][x3d][load_sensor]") {
  context();
  gs::test::TempDir dir("world-view-load");
  dir.write("part.x3dv",
            "#X3D V4.0 utf8\n"
            "Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
            "        geometry Box { size 4 4 4 } }\n");
  gs::render::writePng((dir.path / "t.png").string(), Image(2, 2, 0, 0, 255));
  const std::string main =
      dir.write("main.x3dv",
                "#X3D V4.0 utf8\n"
                "PROFILE Immersive\n"
                "Viewpoint { position 0 0 12 }\n"
                "DEF I Inline { url \"part.x3dv\" }\n"
                "DEF Missing Inline { url \"missing.x3dv\" }\n"
                "Transform { translation 0 3 0 children Shape {\n"
                "  appearance Appearance { texture DEF T ImageTexture { url \"t.png\" } }\n"
                "  geometry Box { size 0.5 0.5 0.5 } } }\n"
                "Transform { translation 0 -3 0 children Shape {\n"
                "  appearance Appearance { texture DEF U ImageTexture { url \"none.png\" } }\n"
                "  geometry Box { size 0.5 0.5 0.5 } } }\n"
                "DEF LI LoadSensor { children USE I }\n"
                "DEF LM LoadSensor { children USE Missing }\n"
                "DEF LT LoadSensor { children USE T }\n"
                "DEF LU LoadSensor { children USE U }\n"
                "DEF LB LoadSensor { children [ USE I USE T ] }\n"
                // isLoaded FALSE (a failure) toggles NM / NU: FALSE is also the default.
                "DEF FM BooleanFilter {} DEF NM BooleanToggle {}\n"
                "DEF FU BooleanFilter {} DEF NU BooleanToggle {}\n"
                "ROUTE LM.isLoaded TO FM.set_boolean ROUTE FM.inputNegate TO NM.set_boolean\n"
                "ROUTE LU.isLoaded TO FU.set_boolean ROUTE FU.inputNegate TO NU.set_boolean\n");
  Viewer v(main);
  v.settle(0.0);
  v.settle(0.5);
  auto sensor = [&](const std::string& name) -> const gs::vrml::Node& {
    for (const gs::vrml::NodePtr& n : v.view->scene()->rootNodes)
      if (n && n->defName == name) return *n;
    FAIL("no node " << name);
    throw 0;
  };
  auto flag = [&](const std::string& name, const std::string& field) {
    return sensor(name).field(field)->get<gs::vrml::FieldType::SFBool>();
  };
  const auto& model = v.runtimes.of(v.view->scene(), 0.0);
  INFO(model.diagnostics().items.size());
  for (const char* name : {"LI", "LT", "LB"}) {
    INFO(name);
    CHECK(flag(name, "isLoaded"));
    CHECK_FALSE(flag(name, "isActive"));
    CHECK(sensor(name).field("progress")->get<gs::vrml::FieldType::SFFloat>() == 1.0f);
  }
  for (const char* name : {"LM", "LU"}) {
    INFO(name);
    CHECK_FALSE(flag(name, "isLoaded"));
    CHECK_FALSE(flag(name, "isActive"));
  }
  CHECK(flag("NM", "toggle"));  // LM sent isLoaded FALSE
  CHECK(flag("NU", "toggle"));
}

TEST_CASE("An IMPORT's node reaches Scripts' getImportedNode once its Inline arrives",
          "[session][offscreen][world_view][x3d][import]") {
  context();
  gs::test::TempDir dir("world-view-import");
  dir.write("part.x3dv",
            "#X3D V4.0 utf8\n"
            "DEF Inner Transform { children Shape { geometry Box { } } }\n"
            "EXPORT Inner AS Outer\n");
  const std::string main = dir.write("main.x3dv",
                                     "#X3D V4.0 utf8\n"
                                     "PROFILE Immersive\n"
                                     "DEF I Inline { url \"part.x3dv\" }\n"
                                     "IMPORT I.Outer AS Imported\n"
                                     "IMPORT I.NotExported AS Nothing\n");
  Viewer v(main);
  v.settle(0.0);
  v.settle(0.5);
  const auto& model = v.runtimes.of(v.view->scene(), 0.0);
  const gs::vrml::NodePtr imported = model.importedNode("Imported");
  REQUIRE(imported);
  CHECK(imported->defName == "Inner");
  CHECK_FALSE(model.importedNode("Nothing"));
  CHECK_FALSE(model.importedNode("Inner"));  // the Inline's own name is not the world's
}

TEST_CASE("a world a Script replaced while it streams adds no more of its file's nodes",
          "[session][offscreen][world_view][script][http]") {
  // The window's order: the world runs while it arrives. Its Script replaces it at once;
  // the rest of the file (a padding comment, then a red Sphere) arrives slowly after.
  context();
  const std::string world =
      "#VRML V2.0 utf8\n"
      "DEF S Script { url \"javascript: function initialize() {\n"
      "  Browser.replaceWorld(Browser.createVrmlFromString(\n"
      "    'Shape { geometry Box { } }')); }\" }\n" +
      std::string("#") + std::string(6000, '-') + "\n" + "Shape { geometry Sphere { } }\n";
  gs::test::FaultServer::Config config;
  config.body = world;
  config.bytesPerSecond = 20000.0;  // 0.3 s for the whole file
  gs::test::FaultServer server(config);
  REQUIRE(server.ok());
  StreamingSession session;
  ViewGroup group{session};
  WorldRuntimes runtimes{gs::session::RuntimeOptions{}, &session.loader()};
  std::string error;
  auto scene = session.open(server.url("/replaced.wrl"), error);
  REQUIRE(scene);
  WorldView view(group, scene, gs::render::SceneRendererOptions{});
  view.setRect(0, 0, kSize, kSize);
  group.attachRuntimes(runtimes, 0.0, false);
  double time = 0.0;
  for (int i = 0; i < 2000 && !(group.settled() && time > 1.0); ++i) {
    time += 0.01;
    view.frame(time);
    session.loader().wait(0.005);
  }
  REQUIRE(group.settled());
  // Only the Script's Box: the Sphere that arrived later was not added.
  REQUIRE(scene->rootNodes.size() == 1);
  CHECK(scene->rootNodes[0]->sfnode("geometry")->typeName() == "Box");
  std::vector<std::pair<bool, std::string>> messages;
  session.drainMessages(messages);
  bool said = false;
  for (const auto& [isError, text] : messages)
    said |= text.find("replaceWorld") != std::string::npos;
  CHECK(said);
}
