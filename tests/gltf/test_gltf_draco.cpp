// KHR_draco_mesh_compression (gltf/src/draco.cpp): a Draco stream made with libdraco's
// encoder, read back through the glTF importer; a damaged stream is an error naming Draco.
#include "base/data_url.hpp"
#include "base/file.hpp"
#include "encodings/parser.hpp"
#include "scene_walk.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>

using namespace gs::vrml;

namespace {

struct DracoStream {
  std::string bytes;
  std::uint32_t positionId = 0;
};

// A unit square in z = 0 as two triangles (4 points), Draco-encoded by libdraco 1.5.5's
// Encoder with its default options (tests/data/gltf/square.drc, 82 bytes; POSITION is
// attribute 0). Read from a file: linking the encoder here would bring libdraco's own copy
// of tinygltf into the test.
DracoStream dracoSquare() {
  std::string bytes, error;
  REQUIRE(gs::base::readFile((gs::test::sourceDir() / "tests/data/gltf/square.drc").string(), bytes,
                             error, 1 << 16));
  return {bytes, 0};
}

std::string dracoAsset(const DracoStream& s) {
  const std::string n = std::to_string(s.bytes.size());
  return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"scene":0,"nodes":[{"mesh":0}],
  "extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,
    "extensions":{"KHR_draco_mesh_compression":{"bufferView":0,"attributes":{"POSITION":)" +
         std::to_string(s.positionId) + R"(}}}}]}],
  "buffers":[{"byteLength":)" +
         n + R"(,"uri":")" + gs::base::makeDataUrl("application/octet-stream", s.bytes) + R"("}],
  "bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":)" +
         n + R"(}],
  "accessors":[{"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"componentType":5123,"count":6,"type":"SCALAR"}]})";
}

const Node& only(const Scene& s, std::string_view type) {
  const Node* n = gs::test::firstOfType(s, type);
  if (n == nullptr) FAIL("no " << type);
  return *n;
}

}  // namespace

TEST_CASE("a Draco-compressed primitive is decoded and drawn like a plain one", "[vrml][gltf]") {
  const Scene s = parseVrml(dracoAsset(dracoSquare()), "draco.gltf");
  std::string messages;
  for (const auto& d : s.diagnostics.items) messages += d.format() + "\n";
  INFO(messages);
  REQUIRE(s.diagnostics.items.empty());
  const Node& triangles = only(s, "IndexedTriangleSet");
  const auto& index = triangles.field("index")->get<FieldType::MFInt32>();
  CHECK(index.size() == 6);
  const Node& coord = *triangles.field("coord")->get<FieldType::SFNode>();
  const auto& points = coord.field("point")->get<FieldType::MFVec3f>();
  REQUIRE(points.size() >= 4);
  // Every corner of the square is there, and every index names a point.
  for (const glm::vec3 corner :
       {glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(1, 1, 0), glm::vec3(0, 1, 0)})
    CHECK(std::count(points.begin(), points.end(), corner) >= 1);
  for (std::int32_t i : index) CHECK(static_cast<std::size_t>(i) < points.size());

  // The same asset as GLB (its JSON chunk is rebuilt around the patched JSON).
  std::string json = dracoAsset(dracoSquare());
  while (json.size() % 4 != 0) json += ' ';
  std::string glb = "glTF";
  auto u32 = [&glb](std::uint32_t v) {
    for (int k = 0; k < 4; ++k) glb += static_cast<char>((v >> (8 * k)) & 0xFF);
  };
  u32(2);
  u32(static_cast<std::uint32_t>(20 + json.size()));
  u32(static_cast<std::uint32_t>(json.size()));
  u32(0x4E4F534A);
  glb += json;
  const Scene binary = parseVrml(glb, "draco.glb");
  CHECK(binary.diagnostics.errorCount() == 0);
  CHECK(only(binary, "IndexedTriangleSet").field("index")->get<FieldType::MFInt32>().size() == 6);
}

TEST_CASE("a damaged Draco stream or a missing attribute id is an error naming Draco",
          "[vrml][gltf]") {
  DracoStream damaged = dracoSquare();
  damaged.bytes.resize(damaged.bytes.size() / 2);  // cut short
  const Scene bad = parseVrml(dracoAsset(damaged), "bad.gltf");
  INFO(bad.diagnostics.items.back().format());
  REQUIRE(bad.diagnostics.errorCount() == 1);
  CHECK(bad.diagnostics.items.back().message.find("Draco") != std::string::npos);

  DracoStream missing = dracoSquare();
  missing.positionId = 77;
  const Scene none = parseVrml(dracoAsset(missing), "none.gltf");
  REQUIRE(none.diagnostics.errorCount() == 1);
  CHECK(none.diagnostics.items.back().message.find("attribute 77") != std::string::npos);
}
