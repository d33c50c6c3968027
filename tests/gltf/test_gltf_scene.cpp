// glTF 2.0 assets read as worlds (gltf/src/import*.cpp): the corpus models with the node
// counts their JSON says, and small assets made here for what the corpus lacks (STEP
// samplers, required and unknown extensions, data: images, hostile indices).
#include "encodings/parser.hpp"
#include "encodings/streaming_parser.hpp"
#include "scene_walk.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

using namespace gs::vrml;

namespace {

std::string describe(const Scene& s) {
  std::string out;
  for (const auto& d : s.diagnostics.items) out += d.format() + "\n";
  return out;
}

// A one-triangle asset with its buffer as a data: URI; `extra` is spliced into the
// top-level object.
std::string triangleAsset(const std::string& extra = "") {
  // 3 float VEC3 positions (36 bytes) + 3 u16 indices (6 bytes, padded to 8): base64 of the
  // 44 bytes.
  return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"scene":0,
  "nodes":[{"mesh":0,"name":"Tri"}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],
  "materials":[{"pbrMetallicRoughness":{"baseColorFactor":[1,0,0,1],"metallicFactor":0}}],
  "buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}])" +
         extra + "}";
}

}  // namespace

TEST_CASE("a glTF asset is a world of X3D nodes", "[vrml][gltf]") {
  const Scene s = parseVrml(triangleAsset(), "tri.gltf");
  INFO(describe(s));
  CHECK(s.diagnostics.items.empty());
  CHECK(s.x3d.encoding == "glTF");
  auto counts = gs::test::countTypes(s);
  CHECK(counts["Transform"] == 1);
  CHECK(counts["Shape"] == 1);
  CHECK(counts["IndexedTriangleSet"] == 1);
  CHECK(counts["PhysicalMaterial"] == 1);
  REQUIRE(s.rootNodes.size() == 1);
  CHECK(s.rootNodes[0]->defName == "Tri");
}

TEST_CASE("glTF extensions: a required unknown one is an error naming it, a used one a warning",
          "[vrml][gltf]") {
  const Scene required = parseVrml(
      triangleAsset(R"(,"extensionsUsed":["EXT_future"],"extensionsRequired":["EXT_future"])"),
      "req.gltf");
  REQUIRE(required.diagnostics.errorCount() == 1);
  CHECK(required.diagnostics.items.back().message.find("EXT_future") != std::string::npos);
  CHECK(required.rootNodes.empty());

  const Scene used = parseVrml(triangleAsset(R"(,"extensionsUsed":["EXT_future"])"), "use.gltf");
  CHECK(used.diagnostics.errorCount() == 0);
  REQUIRE(used.diagnostics.items.size() == 1);
  CHECK(used.diagnostics.items[0].message.find("EXT_future") != std::string::npos);
  CHECK(used.rootNodes.size() == 1);  // the rest is drawn
}

TEST_CASE("glTF animations become TimeSensors, interpolators and ROUTEs; STEP holds each key",
          "[vrml][gltf]") {
  // Times 0 and 1 (8 bytes) then two VEC3 translations (24 bytes) appended to the buffer.
  std::string asset = triangleAsset(
      R"(,"animations":[{"name":"Hop","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],
      "samplers":[{"input":2,"output":3,"interpolation":"STEP"}]}])");
  // Extend buffer 0 with a second buffer holding the animation data.
  const std::string animBuffer =
      R"({"byteLength":32,"uri":"data:application/octet-stream;base64,AAAAAAAAgD8AAAAAAAAAAAAAAAAAAIA/AAAAQAAAQEA="})";
  asset.replace(asset.find("\"buffers\":["), 11, "\"buffers\":[" + animBuffer + ",");
  // Buffer views now name buffer 1 for the triangle: move them to index 1, add views 2, 3.
  std::string::size_type at = 0;
  while ((at = asset.find("\"buffer\":0", at)) != std::string::npos)
    asset.replace(at, 10, "\"buffer\":1");
  asset.replace(
      asset.find("\"bufferViews\":["), 15,
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":8},{"buffer":0,"byteOffset":8,"byteLength":24},)");
  // Accessors: views shift by 2; add the time and value accessors.
  asset.replace(asset.find("\"bufferView\":0,\"componentType\":5126,\"count\":3"), 14,
                "\"bufferView\":2");
  asset.replace(asset.find("\"bufferView\":1,\"componentType\":5123"), 14, "\"bufferView\":3");
  const std::string indexAccessor = R"("count":3,"type":"SCALAR"}])";
  asset.replace(asset.find(indexAccessor), indexAccessor.size(),
                R"("count":3,"type":"SCALAR"},
                   {"bufferView":0,"componentType":5126,"count":2,"type":"SCALAR","min":[0],"max":[1]},
                   {"bufferView":1,"componentType":5126,"count":2,"type":"VEC3"}])");
  const Scene s = parseVrml(asset, "anim.gltf");
  INFO(describe(s));
  INFO(asset);
  CHECK(s.diagnostics.errorCount() == 0);
  auto counts = gs::test::countTypes(s);
  REQUIRE(counts["TimeSensor"] == 1);
  REQUIRE(counts["PositionInterpolator"] == 1);
  REQUIRE(s.routes.size() == 2);
  const Route& last = s.routes[1];
  CHECK(last.toField == "set_translation");
  CHECK(last.toNode == s.rootNodes[0]);
  const NodePtr interp = last.fromNode;
  const auto& key = interp->field("key")->get<FieldType::MFFloat>();
  const auto& value = interp->field("keyValue")->get<FieldType::MFVec3f>();
  // STEP: key 0 holds (0 0 0) until just before 1, where (1 2 3) starts.
  REQUIRE(key.size() == 3);
  CHECK(key[0] == 0.0f);
  CHECK(key[1] < 1.0f);
  CHECK(key[1] > 0.999f);
  CHECK(key[2] == 1.0f);
  CHECK(value[1] == glm::vec3(0.0f));
  CHECK(value[2] == glm::vec3(1.0f, 2.0f, 3.0f));
  const NodePtr sensor = s.routes[0].fromNode;
  CHECK(sensor->defName == "Hop");
  CHECK(sensor->field("cycleInterval")->get<FieldType::SFTime>() == 1.0);
}

TEST_CASE("hostile glTF indices and counts are errors, not reads out of bounds", "[vrml][gltf]") {
  std::string big = triangleAsset();
  big.replace(big.find("\"count\":3,\"type\":\"SCALAR\""), 9, "\"count\":300000000");
  const Scene s1 = parseVrml(big, "big.gltf");
  CHECK(s1.diagnostics.errorCount() == 1);
  std::string node = triangleAsset();
  node.replace(node.find("\"nodes\":[0]"), 11, "\"nodes\":[7]");
  const Scene s2 = parseVrml(node, "node.gltf");
  REQUIRE(s2.diagnostics.errorCount() == 1);
  CHECK(s2.diagnostics.items[0].message.find("node 7 does not exist") != std::string::npos);
  std::string cycle = triangleAsset();
  cycle.replace(cycle.find("\"name\":\"Tri\""), 12, "\"name\":\"Tri\",\"children\":[0]");
  const Scene s3 = parseVrml(cycle, "cycle.gltf");
  CHECK(s3.diagnostics.errorCount() == 1);
}

TEST_CASE("a glTF asset streams like a world: complete when the last byte arrives",
          "[vrml][gltf]") {
  const std::string asset = triangleAsset();
  StreamingParser p("tri.gltf");
  for (std::size_t i = 0; i < asset.size(); i += 100)
    p.feed(std::string_view(asset).substr(i, 100));
  p.finish();
  CHECK(p.scene().rootNodes.size() == 1);
  CHECK(p.scene().x3d.encoding == "glTF");
}

TEST_CASE("the corpus glTF models load as worlds with their nodes", "[vrml][gltf][corpus]") {
  if (!gs::test::haveCorpus("gltf")) return;
  const auto dir = gs::test::corpusDir() / "gltf/castle";
  struct Expect {
    const char* path;
    std::map<std::string, int> counts;
  };
  const Expect models[] = {
      {"castle/castle.gltf", {{"Shape", 16}, {"Appearance", 8}, {"ImageTexture", 11}}},
      {"gltf/punctual_lights/test_lights.gltf",
       {{"DirectionalLight", 1}, {"PointLight", 1}, {"SpotLight", 1}, {"Viewpoint", 1}}},
      {"animation/gltf_skinned_animation/fox_from_khronos/Fox.gltf",
       {{"TimeSensor", 3}, {"ImageTexture", 1}, {"Skin", 1}}},
      {"animation/blender_skinned_animation/skinned_anim.glb",
       {{"TimeSensor", 2}, {"Skin", 1}, {"Shape", 2}}},
      {"gltf/lines/lines.gltf", {{"IndexedLineSet", 2}, {"UnlitMaterial", 1}}},
      {"blender/baking_lighting/sample_level_using_baked_texture.gltf",
       {{"UnlitMaterial", 1}, {"Viewpoint", 1}}},
      {"blender/per_vertex_colors/vertex_paint.glb", {{"ColorRGBA", 1}}},
      // Three animations of the two sparse targets' weights: a CoordinateInterpolator and
      // a NormalInterpolator each.
      {"gltf/morph_targets/monkey_morph.glb",
       {{"Shape", 1}, {"TimeSensor", 3}, {"CoordinateInterpolator", 3}, {"NormalInterpolator", 3}}},
      {"animation/gltf_skinned_animation/animals_from_quaternius/Bunny.gltf",
       {{"TimeSensor", 14}, {"Shape", 6}, {"Skin", 6}}},
  };
  for (const Expect& e : models) {
    INFO(e.path);
    const Scene s = loadVrmlFile((dir / e.path).string());
    INFO(describe(s));
    CHECK(s.diagnostics.errorCount() == 0);
    auto counts = gs::test::countTypes(s);
    for (const auto& [type, n] : e.counts) {
      INFO(type);
      CHECK(counts[type] == n);
    }
  }
  // Fox's TimeSensors are named after its animations; only the first loops from the start.
  const Scene fox =
      loadVrmlFile((dir / "animation/gltf_skinned_animation/fox_from_khronos/Fox.gltf").string());
  std::vector<std::string> names;
  for (const auto& n : fox.rootNodes)
    if (n->typeName() == "TimeSensor") names.push_back(n->defName);
  CHECK(names == std::vector<std::string>{"Survey", "Walk", "Run"});
}

TEST_CASE("glTF morph targets: a node's own weights replace its mesh's", "[vrml][gltf]") {
  // The target's displacement is the POSITION accessor itself: weight w scales the
  // triangle by 1 + w.
  std::string asset = triangleAsset();
  const std::string primitive = R"("material":0}]}])";
  asset.replace(asset.find(primitive), primitive.size(),
                R"("material":0,"targets":[{"POSITION":0}]}],"weights":[0.5]}])");
  asset.replace(asset.find("\"name\":\"Tri\""), 12, "\"name\":\"Tri\",\"weights\":[1]");
  INFO(asset);
  const Scene s = parseVrml(asset, "morph.gltf");
  INFO(describe(s));
  REQUIRE(s.diagnostics.errorCount() == 0);
  const Node* coord = gs::test::firstOfType(s, "Coordinate");
  REQUIRE(coord != nullptr);
  const auto& p = coord->field("point")->get<FieldType::MFVec3f>();
  REQUIRE(p.size() == 3);
  CHECK(p[1] == glm::vec3(2, 0, 0));  // (1 0 0) + 1 x (1 0 0): the node's weight, not 0.5
}

TEST_CASE("glTF Gaussian splats are drawn by one GaussianSplats node naming the asset",
          "[vrml][gltf][splat]") {
  // A triangle and a KHR_gaussian_splatting primitive (its attributes are the splat
  // reader's to check: splats::readGltfGaussians reads the asset again by the node's url).
  const std::string asset =
      R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0,1]}],"scene":0,
  "extensionsUsed":["KHR_gaussian_splatting"],
  "nodes":[{"mesh":0,"name":"Tri"},{"mesh":1,"translation":[2,0,0]}],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]},
            {"primitives":[{"attributes":{"POSITION":0},"mode":0,
                            "extensions":{"KHR_gaussian_splatting":{}}}]}],
  "buffers":[{"byteLength":44,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAAAAABAAIAAAA="}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":6}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]})";
  const Scene s = parseVrml(asset, "http://example.org/mixed.gltf");
  INFO(describe(s));
  CHECK(s.diagnostics.items.empty());  // no "extension not supported" warning
  auto counts = gs::test::countTypes(s);
  CHECK(counts["Shape"] == 1);  // the triangle; the splats are no PointSet
  CHECK(counts["PointSet"] == 0);
  REQUIRE(counts["GaussianSplats"] == 1);
  // At the root, under a Transform turning the reader's capture axes back to glTF's.
  REQUIRE(s.rootNodes.size() == 3);
  const NodePtr& turn = s.rootNodes.back();
  const Rotation r = turn->get<FieldType::SFRotation>("rotation", Rotation());
  CHECK(r == Rotation(0.0f, 0.0f, 1.0f, static_cast<float>(3.14159265358979323846)));
  const auto children = turn->get<FieldType::MFNode>("children", std::vector<NodePtr>{});
  REQUIRE(children.size() == 1);
  CHECK(children[0]->typeName() == "GaussianSplats");
  CHECK(children[0]->get<FieldType::MFString>("url", std::vector<std::string>{}) ==
        std::vector<std::string>{"mixed.gltf"});  // resolves to the asset itself
  // A relative path with folders: its own name still, not the path again.
  const Scene relative = parseVrml(asset, "models/mixed.gltf?v=2");
  auto found = gs::test::countTypes(relative);
  REQUIRE(found["GaussianSplats"] == 1);
  const auto turned =
      relative.rootNodes.back()->get<FieldType::MFNode>("children", std::vector<NodePtr>{});
  CHECK(turned[0]->get<FieldType::MFString>("url", std::vector<std::string>{}) ==
        std::vector<std::string>{"mixed.gltf?v=2"});
}
