// The output events drawing computes (SceneTraversal::takeDrawnOutputs): a LOD's
// level_changed (X3D 4.0 clause 10.4.2), a GeoLOD's level_changed and children (25.4.5),
// each when it changes, and only from the collects that report them.
#include "encodings/parser.hpp"
#include "scene/traversal.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

using gs::scene::Camera;
using gs::scene::SceneTraversal;
using gs::scene::TraversalFrame;
using gs::vrml::FieldType;

namespace {

std::shared_ptr<gs::vrml::Scene> drawnOutputWorld(const std::string& body) {
  return std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\n" + body, "levels.x3dv"));
}

Camera cameraAt(float z) {
  Camera c;
  c.position = glm::vec3(0.0f, 0.0f, z);
  return c;
}

/// "field=value" of each output, in order.
std::vector<std::string> outputText(const gs::vrml::DrawnOutputs& outputs) {
  std::vector<std::string> out;
  for (const gs::vrml::DrawnOutput& o : outputs) {
    std::string v = o.value.type() == FieldType::SFInt32
                        ? std::to_string(o.value.get<FieldType::SFInt32>())
                        : std::to_string(o.value.get<FieldType::MFNode>().size()) + " nodes";
    out.push_back(std::string(o.field) + "=" + v);
  }
  return out;
}

}  // namespace

TEST_CASE("Drawing reports the level a LOD shows when it changes", "[scene][x3d]") {
  auto scene = drawnOutputWorld(R"(
DEF L LOD { range [ 10 20 ] level [
  Shape { geometry Box {} } Shape { geometry Sphere {} } Shape { geometry Cone {} } ] }
)");
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  TraversalFrame frame;
  frame.reportOutputs = true;
  t.collect(cameraAt(5.0f), frame);
  gs::vrml::DrawnOutputs outputs = t.takeDrawnOutputs();
  REQUIRE(outputs.size() == 1);  // the first report is an event
  CHECK(outputs[0].node.node == scene->rootNodes.at(0).get());
  CHECK(outputText(outputs) == std::vector<std::string>{"level_changed=0"});
  t.collect(cameraAt(6.0f), frame);  // the same level: nothing
  CHECK(t.takeDrawnOutputs().empty());
  t.collect(cameraAt(15.0f), frame);
  t.collect(cameraAt(30.0f), frame);
  CHECK(outputText(t.takeDrawnOutputs()) ==
        std::vector<std::string>{"level_changed=1", "level_changed=2"});
  // A collect that does not report (bounds, picking) changes nothing.
  frame.reportOutputs = false;
  t.collect(cameraAt(5.0f), frame);
  CHECK(t.takeDrawnOutputs().empty());
}

TEST_CASE("Drawing reports the level and children a GeoLOD shows", "[scene][x3d][geospatial]") {
  // No child urls: the rootNode is what it shows, near or far; level_changed says which
  // level the distance asks for (range 100 m around its center).
  auto scene = drawnOutputWorld(R"(
DEF G GeoLOD { geoSystem [ "GC" ] center 0 0 0 range 100
  rootNode [ Shape { geometry Box {} } Shape { geometry Sphere {} } ] }
)");
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  TraversalFrame frame;
  frame.reportOutputs = true;
  t.collect(cameraAt(500.0f), frame);
  CHECK(outputText(t.takeDrawnOutputs()) ==
        std::vector<std::string>{"level_changed=0", "children=2 nodes"});
  t.collect(cameraAt(50.0f), frame);  // within range: level 1, the same children
  CHECK(outputText(t.takeDrawnOutputs()) == std::vector<std::string>{"level_changed=1"});
  CHECK(frame.shapes.size() == 2);
}

TEST_CASE("Drawing reports a GeoLOD's loaded child files as its children, once",
          "[scene][x3d][geospatial]") {
  // Two child files (one root node, then two): within range they replace the rootNode, and
  // their three root nodes are the children output; the same frame again sends nothing.
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / "gs_drawn_outputs";
  fs::create_directories(dir);
  std::ofstream(dir / "c1.x3dv") << "#X3D V4.0 utf8\nShape { geometry Box {} }\n";
  std::ofstream(dir / "c2.x3dv")
      << "#X3D V4.0 utf8\nShape { geometry Sphere {} }\nShape { geometry Cone {} }\n";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#X3D V4.0 utf8\nPROFILE Full\nDEF G GeoLOD { geoSystem [ \"GC\" ] range 100\n"
      "  child1Url \"c1.x3dv\" child2Url \"c2.x3dv\"\n"
      "  rootNode [ Shape { geometry Box {} } ] }\n",
      (dir / "world.x3dv").string()));
  REQUIRE(scene->diagnostics.items.empty());
  SceneTraversal t(scene);
  TraversalFrame frame;
  frame.reportOutputs = true;
  t.collect(cameraAt(50.0f), frame);
  CHECK(outputText(t.takeDrawnOutputs()) ==
        std::vector<std::string>{"level_changed=1", "children=3 nodes"});
  CHECK(frame.shapes.size() == 3);
  t.collect(cameraAt(40.0f), frame);
  CHECK(t.takeDrawnOutputs().empty());
  t.collect(cameraAt(500.0f), frame);  // out of range: the rootNode again
  CHECK(outputText(t.takeDrawnOutputs()) ==
        std::vector<std::string>{"level_changed=0", "children=1 nodes"});
  t.collect(cameraAt(50.0f), frame);
  CHECK(outputText(t.takeDrawnOutputs()) ==
        std::vector<std::string>{"level_changed=1", "children=3 nodes"});
}
