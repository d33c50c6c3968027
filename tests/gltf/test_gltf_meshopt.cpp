// EXT_meshopt_compression (gltf/src/meshopt.cpp): vertex and index streams made with
// libmeshoptimizer's encoders, read back through the glTF importer; a damaged stream is an
// error naming the extension.
#include "base/data_url.hpp"
#include "encodings/parser.hpp"
#include "scene_walk.hpp"

#include <meshoptimizer.h>
#include <catch2/catch.hpp>

#include <vector>

using namespace gs::vrml;

namespace {

const std::vector<glm::vec3> kCorners = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
const std::vector<unsigned> kIndices = {0, 1, 2, 0, 2, 3};

struct Compressed {
  std::string vertices, indices;
};

Compressed compressSquare() {
  Compressed c;
  c.vertices.resize(meshopt_encodeVertexBufferBound(kCorners.size(), sizeof(glm::vec3)));
  c.vertices.resize(meshopt_encodeVertexBuffer(reinterpret_cast<unsigned char*>(c.vertices.data()),
                                               c.vertices.size(), kCorners.data(), kCorners.size(),
                                               sizeof(glm::vec3)));
  c.indices.resize(meshopt_encodeIndexBufferBound(kIndices.size(), kCorners.size()));
  c.indices.resize(meshopt_encodeIndexBuffer(reinterpret_cast<unsigned char*>(c.indices.data()),
                                             c.indices.size(), kIndices.data(), kIndices.size()));
  return c;
}

// A square whose positions (ATTRIBUTES, stride 12) and 16-bit indices (TRIANGLES) are
// compressed in buffer 0; buffer 1 is the uncompressed fallback, which has no uri.
std::string meshoptAsset(const Compressed& c) {
  const std::string v = std::to_string(c.vertices.size()), i = std::to_string(c.indices.size());
  return R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"scene":0,"nodes":[{"mesh":0}],
  "extensionsUsed":["EXT_meshopt_compression"],"extensionsRequired":["EXT_meshopt_compression"],
  "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],
  "buffers":[{"byteLength":)" +
         std::to_string(c.vertices.size() + c.indices.size()) + R"(,"uri":")" +
         gs::base::makeDataUrl("application/octet-stream", c.vertices + c.indices) + R"("},
    {"byteLength":60,"extensions":{"EXT_meshopt_compression":{"fallback":true}}}],
  "bufferViews":[
    {"buffer":1,"byteOffset":0,"byteLength":48,"byteStride":12,
     "extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":0,"byteLength":)" +
         v + R"(,"byteStride":12,"count":4,"mode":"ATTRIBUTES"}}},
    {"buffer":1,"byteOffset":48,"byteLength":12,
     "extensions":{"EXT_meshopt_compression":{"buffer":0,"byteOffset":)" +
         v + R"(,"byteLength":)" + i +
         R"(,"byteStride":2,"count":6,"mode":"TRIANGLES"}}}],
  "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
               {"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}]})";
}

}  // namespace

TEST_CASE("an EXT_meshopt_compression primitive is decoded and drawn like a plain one",
          "[vrml][gltf]") {
  const Scene s = parseVrml(meshoptAsset(compressSquare()), "meshopt.gltf");
  std::string messages;
  for (const auto& d : s.diagnostics.items) messages += d.format() + "\n";
  INFO(messages);
  REQUIRE(s.diagnostics.items.empty());  // required, and read: no diagnostic
  const Node* triangles = gs::test::firstOfType(s, "IndexedTriangleSet");
  REQUIRE(triangles != nullptr);
  const auto& index = triangles->field("index")->get<FieldType::MFInt32>();
  CHECK(index == std::vector<std::int32_t>{0, 1, 2, 0, 2, 3});
  const Node& coord = *triangles->field("coord")->get<FieldType::SFNode>();
  CHECK(coord.field("point")->get<FieldType::MFVec3f>() == kCorners);
}

TEST_CASE("a damaged EXT_meshopt_compression stream is an error naming the extension",
          "[vrml][gltf]") {
  Compressed damaged = compressSquare();
  damaged.vertices.resize(damaged.vertices.size() / 2);  // cut short
  const Scene bad = parseVrml(meshoptAsset(damaged), "bad.gltf");
  REQUIRE(bad.diagnostics.errorCount() == 1);
  INFO(bad.diagnostics.items.back().format());
  CHECK(bad.diagnostics.items.back().message.find(
            "bad.gltf: EXT_meshopt_compression of bufferView 0: the ATTRIBUTES stream is "
            "damaged") != std::string::npos);
  CHECK(bad.rootNodes.empty());
}
