// Reading a Gaussian splatting scene piecewise (splats/readers.hpp: openGaussianBatches,
// the out-of-core tileset encode's input): every batch size gives the whole reader's
// splats, bit for bit, in either byte order, for .splat, .compressed.ply, SPZ (v3 gzip in
// one or two members, v4 zstd) and SOG (bundle and meta.json); the frame built over
// batches is gaussianFrame's; the formats not read piecewise are refused by name, and
// damaged compressed data is an error naming the file. An SPZ v4 file read by columns, as
// a remote one is (openGaussianColumns), gives the whole reader's splats for every piece
// size and names the stream that is damaged; an SPZ v2/v3 file read as a stream
// (openGaussianStream) does too, with SH and without, in one gzip member or two.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "base/byte_order.hpp"
#include "base/data_url.hpp"
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

namespace {

// The splats of `bytes` read by columns as a remote scene is (openGaussianColumns): each
// column fed `piece` bytes at a time (from `bytes`, or from the buffer file of `files` it
// names), the splats decoded at most `step` at a time as their records come, then each
// column finished.
GaussianCloud readByColumns(const std::string& bytes, const std::string& name, std::size_t piece,
                            std::size_t step,
                            const std::map<std::string, std::string>& files = {}) {
  GaussianColumns found = openGaussianColumns(bytes, name, bytes.size());
  REQUIRE(found.decoder);
  GaussianColumnDecoder& d = *found.decoder;
  std::vector<std::unique_ptr<ColumnRecords>> columns;
  std::vector<ColumnRecords*> records;
  for (const auto& c : d.columns()) {
    columns.push_back(
        std::make_unique<ColumnRecords>(c, d.size(), name, static_cast<int>(columns.size())));
    records.push_back(columns.back().get());
  }
  GaussianCloud all, batch;
  all.shDegree = d.shDegree();
  for (std::uint64_t at = 0; all.size() < d.size(); at += piece) {
    bool more = false;
    for (std::size_t k = 0; k < columns.size(); ++k) {
      const auto& c = d.columns()[k];
      const std::string& source = c.file.empty() ? bytes : files.at(c.file);
      // (A column of unknown size, an SOG's image: its whole file.)
      const std::uint64_t size = c.bytes == 0 ? source.size() : c.bytes;
      if (at < size) {
        columns[k]->feed(std::string_view(source).substr(
            c.offset + at, std::min<std::uint64_t>(piece, size - at)));
        more = true;
      }
    }
    const std::size_t n = decodeColumns(d, records, all.size(), step, batch);
    REQUIRE(n <= step);
    for (const auto& c : columns) {
      if (!d.columns()[static_cast<std::size_t>(&c - columns.data())].whole)
        CHECK(c->first() == all.size() + n);
    }
    if (n == 0) {
      if (!more) break;  // every byte fed and no splat: finish() says why
      continue;
    }
    REQUIRE(batch.size() == n);
    all.appendRange(batch, 0, n);
  }
  for (const auto& c : columns) c->finish();
  return all;
}

}  // namespace

TEST_CASE("an SPZ v4 file read by columns gives the whole reader's splats", "[splats]") {
  const fs::path spz = splatData("bunny_small.spz");
  const std::string bytes = gs::test::readBytes(spz);
  const GaussianCloud whole = readSpzGaussians(bytes, spz.string());
  const GaussianColumns found = openGaussianColumns(bytes, "a.spz", bytes.size());
  REQUIRE(found.decoder);
  CHECK(found.decoder->columns().size() == 6);  // SH band 1: six zstd streams
  CHECK(found.decoder->size() == 3000);
  CHECK(found.decoder->shDegree() == 1);
  for (const auto& [piece, step] : {std::pair<std::size_t, std::size_t>{1, 7},
                                    {333, 97},
                                    {4096, 1000},
                                    {bytes.size(), 100000}}) {
    INFO("pieces of " << piece << ", splats " << step << " at a time");
    checkSameBits(readByColumns(bytes, "a.spz", piece, step), whole);
  }
  // Its head: more is needed until the table of contents came; other scenes are not read
  // by columns; nor is an SPZ whose size is not known.
  CHECK(openGaussianColumns(bytes.substr(0, 2), "a.spz", bytes.size()).needMore);
  CHECK(openGaussianColumns(bytes.substr(0, 40), "a.spz", bytes.size()).needMore);
  CHECK_FALSE(openGaussianColumns(bytes.substr(0, 40), "a.spz", bytes.size()).decoder);
  CHECK_FALSE(openGaussianColumns(bytes, "a.spz", 0).decoder);
  for (const char* other : {"bunny_small_v3.spz", "bunny_small.ply", "bunny_small.sog"}) {
    INFO(other);
    const std::string head = gs::test::readBytes(splatData(other));
    const GaussianColumns none = openGaussianColumns(head, other, head.size());
    CHECK_FALSE(none.decoder);
    CHECK_FALSE(none.needMore);
  }
}

TEST_CASE("an SPZ v4 file read by columns reports damage naming the file and stream", "[splats]") {
  const std::string bytes = gs::test::readBytes(splatData("bunny_small.spz"));
  const std::uint32_t toc = gs::base::loadLe<std::uint32_t>(bytes.data() + 16);
  const std::size_t streams = static_cast<std::uint8_t>(bytes[15]);
  // A stream said to reach past the file's end.
  CHECK_THROWS_WITH(openGaussianColumns(bytes, "short.spz", bytes.size() - 10),
                    Catch::Contains("short.spz: stream 5"));
  // The first stream's frame magic damaged.
  std::string bad = bytes;
  bad[toc + streams * 16] ^= 0x55;
  CHECK_THROWS_WITH(readByColumns(bad, "bad.spz", 4096, 1000),
                    Catch::Contains("bad.spz: stream 0: zstd:"));
  // The last stream without its last bytes: the splats before it decode, then finish()
  // says the stream is short.
  const GaussianColumns found = openGaussianColumns(bytes, "cut.spz", bytes.size());
  const auto& last = found.decoder->columns().back();
  ColumnRecords records(last, found.decoder->size(), "cut.spz", 5);
  records.feed(std::string_view(bytes).substr(last.offset, last.bytes - 4));
  records.decodeUpTo(found.decoder->size());
  CHECK(records.available() < found.decoder->size());
  CHECK_THROWS_WITH(records.finish(),
                    Catch::Contains("cut.spz: stream 5: expected 27 bytes in the file, got 23"));
  // More bytes than the column holds.
  ColumnRecords first(found.decoder->columns().front(), found.decoder->size(), "over.spz", 0);
  CHECK_THROWS_WITH(first.feed(std::string(found.decoder->columns().front().bytes + 1, 'x')),
                    Catch::Contains("over.spz: column 0: more than"));
}

TEST_CASE("a GLB capture read by columns gives the whole reader's splats", "[splats]") {
  const fs::path glb = splatData("bunny_small.glb");
  const std::string bytes = gs::test::readBytes(glb);
  const GaussianCloud whole = readGltfGaussians(bytes, glb.string(), {});
  const GaussianColumns found = openGaussianColumns(bytes, "a.glb", bytes.size());
  REQUIRE(found.decoder);
  // POSITION, ROTATION, SCALE, OPACITY, the DC and band 1's three: its COLOR_0, which the
  // DC stands in for, is not fetched.
  const auto& columns = found.decoder->columns();
  REQUIRE(columns.size() == 8);
  CHECK(columns[0].recordBytes == 12);
  CHECK(columns[3].recordBytes == 4);
  std::uint64_t fetched = 0;
  for (const auto& c : columns) fetched += c.bytes;
  CHECK(fetched == 3000 * (12 + 16 + 12 + 4 + 12 + 3 * 12));
  for (const auto& [piece, step] :
       {std::pair<std::size_t, std::size_t>{5, 3}, {4096, 1000}, {bytes.size(), 100000}}) {
    INFO("pieces of " << piece << ", splats " << step << " at a time");
    const GaussianCloud read = readByColumns(bytes, "a.glb", piece, step);
    checkSameBits(read, whole);
    CHECK(read.kernel == whole.kernel);
  }
  // More is needed until the JSON chunk and the BIN chunk's header came.
  const std::uint32_t json = gs::base::loadLe<std::uint32_t>(bytes.data() + 12);
  CHECK(openGaussianColumns(bytes.substr(0, 3), "a.glb", bytes.size()).needMore);
  CHECK(openGaussianColumns(bytes.substr(0, 20 + json), "a.glb", bytes.size()).needMore);
  CHECK(openGaussianColumns(bytes.substr(0, 28 + json), "a.glb", bytes.size()).decoder);
  // A GLB that says another length is refused as the batch reader refuses it.
  CHECK_THROWS_WITH(openGaussianColumns(bytes, "long.glb", bytes.size() + 4),
                    Catch::Contains("long.glb: GLB length"));
}

TEST_CASE("a .gltf capture read by columns from its buffer file gives the whole reader's splats",
          "[splats]") {
  const std::string glb = gs::test::readBytes(splatData("bunny_small.glb"));
  const std::uint32_t jsonLength = gs::base::loadLe<std::uint32_t>(glb.data() + 12);
  const std::string bin = glb.substr(20 + jsonLength + 8);
  const auto gltfNaming = [&](const std::string& uri) {
    std::string json = glb.substr(20, jsonLength);
    replaceOnce(json, "\"buffers\":[{\"byteLength\":288000}]",
                "\"buffers\":[{\"byteLength\":288000,\"uri\":\"" + uri + "\"}]");
    return json;
  };
  const std::string json = gltfNaming("bunny%20small.bin");
  const GaussianCloud whole = readGltfGaussians(
      json, "a.gltf", [&](const std::string& uri, std::string& out, std::string&) {
        CHECK(uri == "bunny small.bin");
        out = bin;
        return true;
      });
  const GaussianColumns found = openGaussianColumns(json, "a.gltf", json.size());
  REQUIRE(found.decoder);
  // Every column in the buffer file, named as the scene names it, percent-decoded.
  for (const auto& c : found.decoder->columns()) {
    CHECK(c.file == "bunny small.bin");
    CHECK(c.fileBytes == bin.size());
    CHECK(c.offset + c.bytes <= bin.size());
  }
  for (const auto& [piece, step] :
       {std::pair<std::size_t, std::size_t>{5, 3}, {4096, 1000}, {bin.size(), 100000}}) {
    INFO("pieces of " << piece << ", splats " << step << " at a time");
    checkSameBits(readByColumns(json, "a.gltf", piece, step, {{"bunny small.bin", bin}}), whole);
  }
  // A uri read as RFC 3986 reads it, by the whole reader too (tinygltf would read '+' as a
  // space and "%zz" as a NUL): "a+b%zz.bin" names the file "a+b%zz.bin".
  {
    const std::string odd = gltfNaming("a+b%zz.bin");
    std::string asked;
    readGltfGaussians(odd, "odd.gltf", [&](const std::string& uri, std::string& out, std::string&) {
      asked = uri;
      out = bin;
      return true;
    });
    CHECK(asked == "a+b%zz.bin");
    const GaussianColumns columns = openGaussianColumns(odd, "odd.gltf", odd.size());
    REQUIRE(columns.decoder);
    CHECK(columns.decoder->columns().front().file == "a+b%zz.bin");
  }
  // The whole JSON is needed (a .gltf of at most 1 MiB), even before its "asset" came.
  CHECK(openGaussianColumns(json.substr(0, json.size() - 1), "a.gltf", json.size()).needMore);
  CHECK(openGaussianColumns(json.substr(0, 1), "a.gltf", json.size()).needMore);
  CHECK_FALSE(openGaussianColumns(json.substr(0, 100), "a.gltf", 2u << 20).needMore);
  // A buffer file outside the scene's folder, or named by a URL, is refused; a data:
  // buffer is read whole.
  for (const char* outside : {"../x.bin", "http://elsewhere/x.bin", "%2Fetc%2Fx.bin"}) {
    INFO(outside);
    const std::string bad = gltfNaming(outside);
    CHECK_THROWS_WITH(openGaussianColumns(bad, "a.gltf", bad.size()),
                      Catch::Contains("not a file beside the scene"));
  }
  const std::string inMemory = gltfNaming(gs::base::makeDataUrl("application/octet-stream", bin));
  const GaussianColumns none = openGaussianColumns(inMemory, "a.gltf", inMemory.size());
  CHECK_FALSE(none.decoder);
  CHECK_FALSE(none.needMore);
}

TEST_CASE("an SOG meta.json read by columns from its WebP images gives the whole reader's splats",
          "[splats]") {
  const fs::path metaPath = splatData("bunny_small_sog/meta.json");
  const std::string meta = gs::test::readBytes(metaPath);
  std::map<std::string, std::string> files;
  for (const char* f : {"means_l.webp", "means_u.webp", "quats.webp", "scales.webp", "sh0.webp",
                        "shN_centroids.webp", "shN_labels.webp"})
    files[f] = gs::test::readBytes(splatData("bunny_small_sog") / f);
  const GaussianCloud whole = readGaussians(meta, metaPath.string(), besideFiles(metaPath));
  // Its "asset" does not make it a .gltf; its "means" and "quats" make it an SOG.
  CHECK(openGaussianColumns(meta.substr(0, 10), "meta.json", meta.size()).needMore);
  GaussianColumns found = openGaussianColumns(meta, "meta.json", meta.size());
  REQUIRE(found.decoder);
  const auto& columns = found.decoder->columns();
  REQUIRE(columns.size() == 7);
  for (const auto& c : columns) {
    INFO(c.file);
    CHECK(files.count(c.file) == 1);
    CHECK(c.webp);
    CHECK(c.bytes == 0);  // fetched whole: meta.json does not say their sizes
    CHECK(c.whole == (c.file == "shN_centroids.webp"));
  }
  for (const auto& [piece, step] :
       {std::pair<std::size_t, std::size_t>{7, 3}, {1000, 1000}, {1u << 20, 100000}}) {
    INFO("pieces of " << piece << ", splats " << step << " at a time");
    checkSameBits(readByColumns(meta, "meta.json", piece, step, files), whole);
  }
  // Its splats come a band of rows at a time: 60% of each image gives some, not all.
  {
    GaussianColumns part = openGaussianColumns(meta, "meta.json", meta.size());
    std::vector<std::unique_ptr<ColumnRecords>> held;
    std::vector<ColumnRecords*> records;
    for (const auto& c : part.decoder->columns()) {
      held.push_back(
          std::make_unique<ColumnRecords>(c, 3000, "meta.json", static_cast<int>(held.size())));
      const std::string& bytes = files.at(c.file);
      // (The labels, all zero, are 44 bytes: whole, as the centroids.)
      held.back()->feed(c.whole || bytes.size() < 1000 ? bytes
                                                       : bytes.substr(0, bytes.size() * 6 / 10));
      records.push_back(held.back().get());
    }
    GaussianCloud batch;
    const std::size_t early = decodeColumns(*part.decoder, records, 0, 100000, batch);
    CHECK(early > 0);
    CHECK(early < 3000);
    CHECK(early % 56 == 0);  // whole rows of its 56-texel images
  }
  // Damage as the whole reader names it.
  const auto damaged = [&](const std::string& file, const std::string& bytes) {
    std::map<std::string, std::string> bad = files;
    bad[file] = bytes;
    readByColumns(meta, "meta.json", 1000, 1000, bad);
  };
  CHECK_THROWS_WITH(damaged("quats.webp",
                            "not a picture, not at all: sixty-four bytes or more "
                            "of something else entirely"),
                    Catch::Contains("meta.json: 'quats.webp' is not a WebP image"));
  CHECK_THROWS_WITH(damaged("sh0.webp", files["sh0.webp"].substr(0, 5000)),
                    Catch::Contains("meta.json: 'sh0.webp': damaged WebP data"));
  // A file outside the scene's folder is refused before anything is fetched.
  std::string outside = meta;
  const std::string from = "\"quats.webp\"";
  outside.replace(outside.find(from), from.size(), "\"../quats.webp\"");
  CHECK_THROWS_WITH(openGaussianColumns(outside, "meta.json", outside.size()),
                    Catch::Contains("cannot read '../quats.webp'") &&
                        Catch::Contains("not a file beside the scene"));
}

namespace {

// The splats of the SPZ v2/v3 `bytes` read as a remote one is (openGaussianStream): fed
// `piece` bytes at a time, the splats taken at most `step` at a time as they come; each
// batch is checked to follow the last.
GaussianCloud readByStream(const std::string& bytes, const std::string& name, std::size_t piece,
                           std::size_t step) {
  const GaussianStream found = openGaussianStream(bytes, name, bytes.size());
  REQUIRE(found.decoder);
  GaussianStreamDecoder& d = *found.decoder;
  GaussianCloud all, batch;
  all.shDegree = d.shDegree();
  for (std::size_t at = 0; at < bytes.size(); at += piece) {
    d.feed(std::string_view(bytes).substr(at, piece));
    while (const std::size_t n = d.next(batch, step)) {
      REQUIRE(n <= step);
      REQUIRE(batch.size() == n);
      all.appendRange(batch, 0, n);
      CHECK(d.decoded() == all.size());
    }
  }
  d.finish();
  return all;
}

// `v3` (an SPZ v3 file's decompressed bytes) as SH degree 0: its header says so and its
// SH block is gone (the rotations are then the last block); as version 2 too, with
// 3-byte rotations (the first three bytes of each 4-byte one).
std::string withoutSh(const std::string& v3, bool version2) {
  const std::uint32_t count = gs::base::loadLe<std::uint32_t>(v3.data() + 8);
  std::string out = v3.substr(0, 16 + count * (9 + 1 + 3 + 3));
  out[12] = 0;
  if (!version2) return out + v3.substr(out.size(), count * 4);
  out[4] = 2;
  for (std::uint32_t i = 0; i < count; ++i) out += v3.substr(16 + count * 16 + i * 4, 3);
  return out;
}

}  // namespace

TEST_CASE("an SPZ v2 or v3 file read as a stream gives the whole reader's splats", "[splats]") {
  const std::string file = gs::test::readBytes(splatData("bunny_small_v3.spz"));
  const std::string v3 = gs::base::gunzip(file, 1u << 24);
  const std::pair<const char*, std::string> cases[] = {
      {"v3 with SH", file},
      {"v3 in two gzip members and padding",
       gs::test::gzip(v3.substr(0, 1000)) + gs::test::gzip(v3.substr(1000)) + std::string(3, '\0')},
      {"v3 without SH", gs::test::gzip(withoutSh(v3, false))},
      {"v2 without SH", gs::test::gzip(withoutSh(v3, true))}};
  for (const auto& [what, bytes] : cases) {
    INFO(what);
    const GaussianCloud whole = readSpzGaussians(bytes, "a.spz");
    CHECK(whole.size() == 3000);
    for (const auto& [piece, step] : {std::pair<std::size_t, std::size_t>{1, 7},
                                      {333, 97},
                                      {4096, 1000},
                                      {bytes.size(), 100000}}) {
      INFO("pieces of " << piece << ", splats " << step << " at a time");
      checkSameBits(readByStream(bytes, "a.spz", piece, step), whole);
    }
  }
  // With SH that vary, as a capture's (the bunny's are all zero, a few bytes of gzip),
  // the first splats come before the last block ends: three quarters of the file give
  // some and not all.
  {
    std::string varied = v3;
    gs::test::fillPseudoRandom(varied, 16 + 3000 * 20, 12345);
    const std::string gz = gs::test::gzip(varied);
    const GaussianStream found = openGaussianStream(gz, "a.spz", gz.size());
    REQUIRE(found.decoder);
    CHECK(found.decoder->size() == 3000);
    CHECK(found.decoder->shDegree() == 1);
    found.decoder->feed(std::string_view(gz).substr(0, gz.size() * 3 / 4));
    GaussianCloud batch;
    const std::size_t early = found.decoder->next(batch, 100000);
    CHECK(early > 0);
    CHECK(early < 3000);
    CHECK(found.decoder->inflated() > 16 + 3000 * 20);  // past the blocks before the SH
    CHECK(found.decoder->inflated() < varied.size());
  }
  // The head: more is needed until 16 bytes decompress; other scenes are not streams.
  CHECK(openGaussianStream(file.substr(0, 1), "a.spz", file.size()).needMore);
  CHECK(openGaussianStream(file.substr(0, 12), "a.spz", file.size()).needMore);
  CHECK_FALSE(openGaussianStream(file.substr(0, 12), "a.spz", file.size()).decoder);
  for (const char* other : {"bunny_small.spz", "bunny_small.ply", "bunny_small.sog"}) {
    INFO(other);
    const std::string head = gs::test::readBytes(splatData(other));
    const GaussianStream none = openGaussianStream(head, other, head.size());
    CHECK_FALSE(none.decoder);
    CHECK_FALSE(none.needMore);
  }
  const GaussianStream gzippedPly =
      openGaussianStream(gs::test::gzip("ply\nformat binary_little_endian 1.0\n"), "a.ply.gz", 0);
  CHECK_FALSE(gzippedPly.decoder);
  CHECK_FALSE(gzippedPly.needMore);
}

TEST_CASE("an SPZ v2 or v3 file read as a stream reports damage naming the file", "[splats]") {
  const std::string file = gs::test::readBytes(splatData("bunny_small_v3.spz"));
  const auto whyOf = [](const std::string& bytes) {
    try {
      (void)readByStream(bytes, "bad.spz", 4096, 1000);
    } catch (const FormatError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  // Cut short: the gzip data end inside their member.
  CHECK(whyOf(file.substr(0, file.size() - 100)) == "bad.spz: corrupt gzip data: truncated");
  // Bytes after the data.
  CHECK(whyOf(file + "junk") == "bad.spz: corrupt gzip data: trailing bytes after the gzip data");
  // Whole gzip data that hold fewer bytes than the header's splats need.
  const std::string v3 = gs::base::gunzip(file, 1u << 24);
  CHECK_THAT(whyOf(gs::test::gzip(v3.substr(0, v3.size() - 10))),
             Catch::Contains("bad.spz: expected") && Catch::Contains("for 3000 splats"));
  // More than 1 MiB after the blocks.
  CHECK_THAT(
      whyOf(gs::test::gzip(v3 + std::string((1u << 20) + 1, 'x'))),
      Catch::Contains("bad.spz: decompressed data exceeds the SPZ blocks by more than 1 MiB"));
  // A header the whole reader refuses; a count no gzip data of this size can hold.
  std::string v9 = v3;
  v9[4] = 9;
  CHECK_THROWS_WITH(openGaussianStream(gs::test::gzip(v9), "v9.spz", 0),
                    Catch::Contains("v9.spz: unsupported SPZ version 9"));
  CHECK_THROWS_WITH(openGaussianStream(file, "big.spz", 50),
                    Catch::Contains("big.spz: 50 bytes of gzip data cannot hold"));
}
