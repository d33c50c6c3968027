// Reading a Gaussian splatting scene piecewise (splats/readers.hpp: openGaussianBatches,
// the out-of-core tileset encode's input): every batch size gives the whole reader's
// splats, bit for bit, in either byte order, for .splat, .compressed.ply, SPZ (v3 gzip in
// one or two members, v4 zstd) and SOG (bundle and meta.json); the frame built over
// batches is gaussianFrame's; the formats not read piecewise are refused by name, and
// damaged compressed data is an error naming the file.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "base/byte_order.hpp"
#include "base/gzip.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

using namespace gs::splats;
namespace fs = std::filesystem;

namespace {

fs::path splatData(const char* file) {
  return gs::test::sourceDir() / "tests" / "data" / "splats" / file;
}

// Every splat of the scene through batches of `size` (the reader rewound first).
GaussianCloud readInBatches(GaussianBatchReader& reader, std::size_t size) {
  GaussianCloud all, batch;
  all.shDegree = reader.shDegree();
  reader.rewind();
  while (const std::size_t n = reader.read(batch, size)) {
    REQUIRE(n <= size);
    REQUIRE(batch.size() == n);
    REQUIRE(batch.shDegree == reader.shDegree());
    all.appendRange(batch, 0, n);
  }
  return all;
}

void checkSameBits(const GaussianCloud& a, const GaussianCloud& b) {
  REQUIRE(a.size() == b.size());
  REQUIRE(a.shDegree == b.shDegree);
  const auto same = [](const auto& x, const auto& y) {
    return x.size() == y.size() &&
           std::memcmp(x.data(), y.data(), x.size() * sizeof(x.front())) == 0;
  };
  CHECK(same(a.positions, b.positions));
  CHECK(same(a.scales, b.scales));
  CHECK(same(a.rotations, b.rotations));
  CHECK(same(a.opacities, b.opacities));
  CHECK(same(a.shDc, b.shDc));
  CHECK(a.shRest.size() == b.shRest.size());
  if (!a.shRest.empty()) CHECK(same(a.shRest, b.shRest));
}

// `ply` (binary little-endian, every property a float) in big-endian order.
std::string bigEndian(const std::string& ply) {
  std::string out = ply;
  const std::size_t body = out.find("end_header\n") + 11;
  const std::size_t at = out.find("binary_little_endian");
  REQUIRE(at < body);
  out.replace(at, 20, "binary_big_endian");
  const std::size_t start = body - 3;  // the header is 3 bytes shorter
  for (std::size_t i = start; i + 4 <= out.size(); i += 4) {
    std::swap(out[i], out[i + 3]);
    std::swap(out[i + 1], out[i + 2]);
  }
  return out;
}

/// The GLB `glb` with its JSON chunk edited by `edit` (the BIN chunk kept).
std::string editedGlb(const std::string& glb, const std::function<void(std::string&)>& edit) {
  const std::uint32_t length = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  std::string json = glb.substr(20, length);
  edit(json);
  while (json.size() % 4 != 0) json += ' ';
  const std::string rest = glb.substr(20 + length);
  std::string out = glb.substr(0, 8);
  gs::base::appendLe<std::uint32_t>(out,
                                    static_cast<std::uint32_t>(20 + json.size() + rest.size()));
  gs::base::appendLe<std::uint32_t>(out, static_cast<std::uint32_t>(json.size()));
  gs::base::appendLe<std::uint32_t>(out, 0x4E4F534Au);
  return out + json + rest;
}

void replaceOnce(std::string& s, const std::string& from, const std::string& to) {
  const std::size_t at = s.find(from);
  REQUIRE(at != std::string::npos);
  s.replace(at, from.size(), to);
}

}  // namespace

// Reads the files beside `scene` (SOG's textures), as the encode's side-file reader does.
SideFileReader besideFiles(const fs::path& scene) {
  return [scene](const std::string& relative, std::string& bytes, std::string& error) {
    const fs::path path = scene.parent_path() / relative;
    if (!fs::is_regular_file(path)) {
      error = "no " + path.string();
      return false;
    }
    bytes = gs::test::readBytes(path);
    return true;
  };
}

TEST_CASE("openGaussianBatches gives the whole reader's splats for every batch size",
          "[splats][ooc]") {
  gs::test::TempDir dir("gaussian_batches");
  const std::string plyBytes = gs::test::readBytes(splatData("bunny_small.ply"));
  const fs::path be = dir.path / "bunny_be.ply";
  std::ofstream(be, std::ios::binary) << bigEndian(plyBytes);
  // v3 as two gzip members (RFC 1952 2.2), the second starting inside the positions.
  const std::string v3 =
      gs::base::gunzip(gs::test::readBytes(splatData("bunny_small_v3.spz")), 1u << 24);
  const fs::path members = dir.path / "members.spz";
  std::ofstream(members, std::ios::binary)
      << gs::test::gzip(v3.substr(0, 1000)) << gs::test::gzip(v3.substr(1000));
  const fs::path sogMeta = splatData("bunny_small_sog/meta.json");
  // glTF: the GLB; the mesh instanced by a second node whose scale is not uniform (the
  // covariance path), beside the first; a .gltf whose buffer is a file beside it.
  const std::string glb = gs::test::readBytes(splatData("bunny_small.glb"));
  const fs::path instanced = dir.path / "instanced.glb";
  std::ofstream(instanced, std::ios::binary) << editedGlb(glb, [](std::string& json) {
    replaceOnce(json, "\"nodes\":[{\"mesh\":0}]",
                "\"nodes\":[{\"mesh\":0,\"children\":[1]},{\"mesh\":0,\"translation\":[1,2,3],"
                "\"rotation\":[0,0.6,0,0.8],\"scale\":[2,1,0.5]}]");
  });
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  std::string gltfJson = glb.substr(20, jsonLength);
  replaceOnce(gltfJson, "\"buffers\":[{\"byteLength\":288000}]",
              "\"buffers\":[{\"byteLength\":288000,\"uri\":\"bunny%20small.bin\"}]");
  const fs::path gltf = dir.path / "bunny.gltf";
  std::ofstream(gltf, std::ios::binary) << gltfJson;
  std::ofstream(dir.path / "bunny small.bin", std::ios::binary) << glb.substr(20 + jsonLength + 8);
  for (const fs::path& path :
       {splatData("bunny_small.ply"), splatData("bunny_small.splat"), be,
        splatData("bunny_small.compressed.ply"), splatData("bunny_small.spz"),
        splatData("bunny_small_v3.spz"), members, splatData("bunny_small.sog"), sogMeta,
        splatData("bunny_small.glb"), instanced, gltf}) {
    INFO(path.string());
    const GaussianCloud whole =
        readGaussians(gs::test::readBytes(path), path.string(), besideFiles(path));
    const auto reader = openGaussianBatches(path.string(), besideFiles(path));
    CHECK(reader->size() == whole.size());
    CHECK(reader->shDegree() == whole.shDegree);
    CHECK(reader->rowBytes() > 0);
    for (const std::size_t size :
         {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1u << 20}}) {
      INFO(size);
      checkSameBits(readInBatches(*reader, size), whole);
    }
  }
}

TEST_CASE("GaussianFrameBuilder over batches is gaussianFrame of the whole scene",
          "[splats][ooc]") {
  const fs::path ply = splatData("bunny_small.ply");
  GaussianCloud whole = readPlyGaussians(gs::test::readBytes(ply), ply.string());
  whole.opacities[5] = 0.0f;  // two splats the stream leaves out
  whole.scales[9] = glm::vec3(0.0f);
  const GaussianFrame frame = gaussianFrame(whole);
  REQUIRE(frame.kept.size() == whole.size() - 2);
  GaussianFrameBuilder builder(whole.shDegree, whole.size());
  for (std::size_t i = 0; i < whole.size(); ++i)
    CHECK(builder.addExtent(whole, i) == (i != 5 && i != 9));
  builder.finishExtent();
  CHECK(builder.keptCount() == frame.kept.size());
  for (std::size_t k = 0; k < frame.kept.size(); ++k)
    CHECK(builder.importanceOf(whole, frame.kept[k]) == frame.importance[k]);
  const gs::qnv::StreamHeader& h = builder.finish();
  CHECK(h.boundsMin == frame.header.boundsMin);
  CHECK(h.boundsMax == frame.header.boundsMax);
  CHECK(h.valueMin == frame.header.valueMin);
  CHECK(h.valueMax == frame.header.valueMax);
  CHECK(h.magnitudeMin == frame.header.magnitudeMin);
  CHECK(h.magnitudeMax == frame.header.magnitudeMax);
  CHECK(h.packetBytes == frame.header.packetBytes);
}

TEST_CASE("openGaussianBatches refuses what it does not read piecewise, naming the file",
          "[splats][ooc]") {
  gs::test::TempDir dir("gaussian_batches_bad");
  // A glTF of sparse accessors is read whole.
  const fs::path sparse = dir.path / "sparse.glb";
  std::ofstream(sparse, std::ios::binary)
      << editedGlb(gs::test::readBytes(splatData("bunny_small.glb")), [](std::string& json) {
           replaceOnce(json, "\"accessors\":[{",
                       "\"accessors\":[{\"sparse\":{\"count\":1,"
                       "\"indices\":{\"bufferView\":0,\"componentType\":5125},"
                       "\"values\":{\"bufferView\":0}},");
         });
  CHECK_THROWS_AS(openGaussianBatches(sparse.string()), NotPiecewiseError);
  CHECK_THROWS_WITH(openGaussianBatches(sparse.string()),
                    Catch::Contains("sparse.glb: read piecewise are binary") &&
                        Catch::Contains("not a glTF scene of sparse accessors"));
  // A GLB cut in its BIN chunk: a FormatError naming it, before any batch.
  const std::string glb = gs::test::readBytes(splatData("bunny_small.glb"));
  const fs::path cutGlb = dir.path / "cut.glb";
  std::ofstream(cutGlb, std::ios::binary) << glb.substr(0, glb.size() - 1000);
  CHECK_THROWS_WITH(openGaussianBatches(cutGlb.string()), Catch::Contains("cut.glb: GLB length"));
  // A .gltf whose buffer file is not its byteLength: refused as tinygltf refuses it.
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  std::string json = glb.substr(20, jsonLength);
  replaceOnce(json, "\"buffers\":[{\"byteLength\":288000}]",
              "\"buffers\":[{\"byteLength\":288000,\"uri\":\"short.bin\"}]");
  std::ofstream(dir.path / "short.gltf", std::ios::binary) << json;
  std::ofstream(dir.path / "short.bin", std::ios::binary) << glb.substr(20 + jsonLength + 8, 1000);
  CHECK_THROWS_WITH(openGaussianBatches((dir.path / "short.gltf").string()),
                    Catch::Contains("short.bin: expected 288000 bytes, got 1000"));
  const fs::path ascii = dir.path / "ascii.ply";
  std::ofstream(ascii) << "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                          "property float f_dc_0\nproperty float opacity\nproperty float "
                          "scale_0\nproperty float rot_0\nend_header\n0 0 0 0 1\n";
  CHECK_THROWS_WITH(openGaussianBatches(ascii.string()), Catch::Contains("not an ascii PLY"));
  // Not there, or cut short: a FormatError of its own (not a usage error).
  try {
    openGaussianBatches((dir.path / "missing.ply").string());
    FAIL("no error");
  } catch (const NotPiecewiseError&) {
    FAIL("a missing file is not a format refused");
  } catch (const FormatError& e) {
    CHECK_THAT(e.what(), Catch::Contains("missing.ply: cannot open"));
  }
  const std::string bytes = gs::test::readBytes(splatData("bunny_small.ply"));
  const fs::path cut = dir.path / "cut.ply";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() - 5);
  CHECK_THROWS_WITH(openGaussianBatches(cut.string()), Catch::Contains("cut.ply: expected"));
}

TEST_CASE("openGaussianBatches reports damaged SPZ and compressed PLY data, naming the file",
          "[splats][ooc]") {
  gs::test::TempDir dir("gaussian_batches_damaged");
  const auto readAll = [](const fs::path& path) {
    const auto reader = openGaussianBatches(path.string());
    GaussianCloud batch;
    while (reader->read(batch, 500) > 0) {
    }
  };
  const auto write = [&](const char* name, const std::string& bytes) {
    const fs::path path = dir.path / name;
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  };
  // v3 (gzip) cut short: the header reads, the SH block (the last) runs out.
  const std::string v3 = gs::test::readBytes(splatData("bunny_small_v3.spz"));
  CHECK_THROWS_WITH(
      readAll(write("cut_v3.spz", v3.substr(0, v3.size() * 3 / 4))),
      Catch::Contains("cut_v3.spz: corrupt gzip data") && Catch::Contains("truncated"));
  // The gzip trailer damaged (CRC-32) or missing: the whole reader refuses the file, and
  // so does the last batch.
  std::string crc = v3;
  crc[crc.size() - 8] ^= 0x5a;
  const std::string trailerless = v3.substr(0, v3.size() - 8);
  for (const auto& [file, bytes] :
       {std::pair{"crc.spz", crc}, std::pair{"trailerless.spz", trailerless}}) {
    INFO(file);
    CHECK_THROWS_AS(readSpzGaussians(bytes, file), FormatError);
    CHECK_THROWS_WITH(readAll(write(file, bytes)),
                      Catch::Contains(file) && Catch::Contains("gzip"));
  }
  // A gzip header claiming more splats than its bytes can hold at deflate's 1032:1.
  std::string raw = gs::base::gunzip(v3, 1u << 24);
  const std::uint32_t many = 1u << 26;
  std::memcpy(raw.data() + 8, &many, 4);
  CHECK_THROWS_WITH(openGaussianBatches(write("many.spz", gs::test::gzip(raw)).string()),
                    Catch::Contains("many.spz") && Catch::Contains("cannot hold"));
  // v4 (zstd): the file cut inside its last stream, and the first stream's frame magic
  // damaged.
  std::string v4 = gs::test::readBytes(splatData("bunny_small.spz"));
  CHECK_THROWS_WITH(openGaussianBatches(write("cut_v4.spz", v4.substr(0, v4.size() - 10)).string()),
                    Catch::Contains("cut_v4.spz: stream"));
  const std::uint32_t toc = gs::base::loadLe<std::uint32_t>(v4.data() + 16);
  const std::size_t streams = static_cast<std::uint8_t>(v4[15]);
  v4[toc + streams * 16] ^= 0x55;
  CHECK_THROWS_WITH(readAll(write("bad_v4.spz", v4)),
                    Catch::Contains("bad_v4.spz: stream 0: zstd:"));
  // A compressed PLY without its last records.
  const std::string packed = gs::test::readBytes(splatData("bunny_small.compressed.ply"));
  CHECK_THROWS_WITH(
      openGaussianBatches(
          write("cut.compressed.ply", packed.substr(0, packed.size() - 100)).string()),
      Catch::Contains("cut.compressed.ply: expected"));
}
