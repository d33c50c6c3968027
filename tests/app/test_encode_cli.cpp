// `ghostspace encode` and `ghostspace info FILE.qnv` end to end.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "process.hpp"
#include "qnv/decoder.hpp"
#include "qnv/encoder.hpp"
#include "qnv/record.hpp"
#include "qnv/stream.hpp"
#include "test_support.hpp"

using gs::test::runGhostspace;

namespace {

std::filesystem::path scratch(const std::string& name) {
  const auto dir = std::filesystem::temp_directory_path() / "gs_test_encode";
  std::filesystem::create_directories(dir);
  return dir / name;
}

std::uint64_t decodedVectors(const std::string& bytes) {
  gs::qnv::StreamDecoder d("out.qnv");
  std::uint64_t n = 0;
  const auto sink = [&](std::uint64_t, std::span<const gs::qnv::DecodedVector> v) {
    n += v.size();
  };
  d.feed(bytes, sink);
  REQUIRE(d.finish(sink));
  return n;
}

// The records of a plain stream, in stream order.
std::vector<std::uint64_t> plainRecords(const std::string& bytes) {
  std::vector<std::uint64_t> records;
  for (std::size_t at = gs::qnv::kHeaderBytes; at + gs::qnv::kPacketHeaderBytes <= bytes.size();) {
    std::uint16_t count = 0, payload = 0;
    std::memcpy(&count, bytes.data() + at + 2, 2);
    std::memcpy(&payload, bytes.data() + at + 8, 2);
    REQUIRE(payload == count * 8u);
    for (std::size_t i = 0; i < count; ++i) {
      std::uint64_t r = 0;
      std::memcpy(&r, bytes.data() + at + gs::qnv::kPacketHeaderBytes + 8 * i, 8);
      records.push_back(r);
    }
    at += gs::qnv::kPacketHeaderBytes + payload;
  }
  return records;
}

}  // namespace

TEST_CASE("encode turns a VRML world into a stream that info describes", "[app][encode]") {
  const auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  const auto out = scratch("welcome.qnv");
  auto r = runGhostspace({"encode", world.string(), "-o", out.string()});
  REQUIRE(r.exitCode == 0);
  CHECK_THAT(r.out, Catch::Contains("triangles"));
  CHECK_THAT(r.out, Catch::Contains("bits per vector"));
  const std::string bytes = gs::test::readBytes(out);
  const std::uint64_t all = decodedVectors(bytes);
  CHECK(all > 100);

  auto info = runGhostspace({"info", out.string()});
  REQUIRE(info.exitCode == 0);
  CHECK_THAT(info.out, Catch::Contains("surface stream"));
  CHECK_THAT(info.out, Catch::Contains("magnitude histogram"));
  CHECK_THAT(info.out, Catch::Contains("0 damaged, 0 missing"));

  // Half of the triangles, in packets of the paper's 48-byte cell, compact.
  auto half = runGhostspace({"encode", world.string(), "-o", out.string(), "--fraction", "0.5",
                             "--packet-bytes", "48", "--compact"});
  REQUIRE(half.exitCode == 0);
  const std::uint64_t some = decodedVectors(gs::test::readBytes(out));
  CHECK(some < all);
  CHECK(some > all / 3);

  // Every triangle again, entropy-coded: the same count in fewer bytes.
  auto entropy =
      runGhostspace({"encode", world.string(), "-o", out.string(), "--coding", "entropy"});
  REQUIRE(entropy.exitCode == 0);
  const std::string small = gs::test::readBytes(out);
  CHECK(small.size() < bytes.size());
  CHECK(decodedVectors(small) == all);
  auto entropyInfo = runGhostspace({"info", out.string()});
  CHECK_THAT(entropyInfo.out, Catch::Contains("(entropy)"));
  CHECK_THAT(entropyInfo.out, Catch::Contains("0 damaged, 0 missing"));
  auto badCoding =
      runGhostspace({"encode", world.string(), "-o", out.string(), "--coding", "lzma"});
  CHECK(badCoding.exitCode != 0);

  // A cut-off copy: info reports what arrived and what did not.
  const std::string cut = bytes.substr(0, bytes.size() * 2 / 3);
  std::ofstream(scratch("cut.qnv"), std::ios::binary) << cut;
  auto cutInfo = runGhostspace({"info", scratch("cut.qnv").string()});
  CHECK(cutInfo.exitCode == 0);
  CHECK_THAT(cutInfo.out, Catch::Contains("stream ends after"));
}

TEST_CASE("encode --magnitude-bits rounds every magnitude code, and entropy streams shrink",
          "[app][encode]") {
  const auto world = (gs::test::sourceDir() / "assets/worlds/welcome.wrl").string();
  const auto out = scratch("rounded.qnv").string();
  const auto encoded = [&](std::vector<std::string> extra) {
    std::vector<std::string> args = {"encode", world, "-o", out};
    args.insert(args.end(), extra.begin(), extra.end());
    const auto r = runGhostspace(args);
    REQUIRE(r.exitCode == 0);
    return gs::test::readBytes(out);
  };
  const std::vector<std::uint64_t> exact = plainRecords(encoded({"--coding", "plain"}));
  const std::vector<std::uint64_t> rounded =
      plainRecords(encoded({"--coding", "plain", "--magnitude-bits", "10"}));
  REQUIRE(rounded.size() == exact.size());
  REQUIRE(exact.size() > 100);
  // The exact stream's records rounded, each run of equal codes in Morton order: what
  // coarsenMagnitudes gives (tests/qnv/test_entropy_low_bits.cpp).
  std::vector<std::uint64_t> expected = exact;
  gs::qnv::coarsenMagnitudes(expected, 10);
  CHECK(rounded == expected);
  std::size_t changed = 0;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    CHECK((gs::qnv::magnitudeCode(rounded[i]) & 31u) == 16u);  // low 5 bits 10000
    changed += rounded[i] != exact[i];
  }
  CHECK(changed > exact.size() / 2);
  // Entropy packets send the shared low bits once: about 5 bits per vector less.
  const std::size_t exactBytes = encoded({"--coding", "entropy"}).size();
  const std::string small = encoded({"--coding", "entropy", "--magnitude-bits", "10"});
  CHECK(decodedVectors(small) == exact.size());
  CHECK(small.size() + exact.size() * 4 / 8 < exactBytes);
  const std::string fast = encoded({"--coding", "entropy-fast", "--magnitude-bits", "10"});
  CHECK(decodedVectors(fast) == exact.size());
  CHECK(fast.size() + exact.size() * 4 / 8 < encoded({"--coding", "entropy-fast"}).size());

  // info tells how many bits the codes were rounded to, and says nothing of exact ones.
  encoded({"--coding", "entropy", "--magnitude-bits", "10"});
  const auto roundedInfo = runGhostspace({"info", out});
  CHECK_THAT(roundedInfo.out, Catch::Contains("codes rounded to 10 of 15 bits"));
  encoded({"--coding", "entropy"});
  const auto exactInfo = runGhostspace({"info", out});
  CHECK_THAT(exactInfo.out, Catch::Contains("magnitude   logarithmic"));
  CHECK_THAT(exactInfo.out, !Catch::Contains("codes rounded"));
  for (const char* bad : {"0", "16"}) {
    const auto r = runGhostspace({"encode", world, "-o", out, "--magnitude-bits", bad});
    CHECK(r.exitCode == 2);
  }
  const auto tileset = runGhostspace(
      {"encode", world, "--tileset", scratch("rounded").string(), "--magnitude-bits", "10"});
  CHECK(tileset.exitCode == 2);
  CHECK_THAT(tileset.err, Catch::Contains("--magnitude-bits is for streams"));
}

TEST_CASE("encode rejects bad options and unreadable inputs with a reason", "[app][encode]") {
  const auto world = (gs::test::sourceDir() / "assets/worlds/welcome.wrl").string();
  auto noOutput = runGhostspace({"encode", world});
  CHECK(noOutput.exitCode == 2);
  auto badPacket =
      runGhostspace({"encode", world, "-o", scratch("x.qnv").string(), "--packet-bytes", "50"});
  CHECK(badPacket.exitCode == 2);
  CHECK_THAT(badPacket.err, Catch::Contains("multiple of 8"));
  auto badFraction =
      runGhostspace({"encode", world, "-o", scratch("x.qnv").string(), "--fraction", "1.5"});
  CHECK(badFraction.exitCode == 2);
  auto missing =
      runGhostspace({"encode", "/nonexistent/none.wrl", "-o", scratch("x.qnv").string()});
  CHECK(missing.exitCode == 1);
  CHECK_THAT(missing.err, Catch::Contains("/nonexistent/none.wrl"));
  auto notQnv = runGhostspace({"info", scratch("not.qnv").string()});
  CHECK(notQnv.exitCode == 1);
  // --sh-bits is for Gaussian splatting scenes only, and within 1..5.
  auto shBitsWorld =
      runGhostspace({"encode", world, "-o", scratch("x.qnv").string(), "--sh-bits", "4"});
  CHECK(shBitsWorld.exitCode == 2);
  CHECK_THAT(shBitsWorld.err, Catch::Contains("--sh-bits and --sh-full are for streams"));
  const auto splats = (gs::test::sourceDir() / "tests/data/splats/bunny_small.ply").string();
  auto shBitsRange =
      runGhostspace({"encode", splats, "-o", scratch("x.qnv").string(), "--sh-bits", "6"});
  CHECK(shBitsRange.exitCode == 2);
  // --sh-full alone would change nothing: said so.
  auto shFullAlone =
      runGhostspace({"encode", splats, "-o", scratch("x.qnv").string(), "--sh-full", "0.5"});
  CHECK(shFullAlone.exitCode == 2);
  CHECK_THAT(shFullAlone.err, Catch::Contains("give --sh-bits"));
  // A LAS cloud is read whole: no out-of-core encode of it (test_ooc_tileset_cli.cpp has
  // the formats read piecewise).
  const auto las = (gs::test::sourceDir() / "tests/data/las/simple.las").string();
  auto splatMemory = runGhostspace(
      {"encode", las, "--tileset", scratch("splat_tileset").string(), "--memory", "64"});
  CHECK(splatMemory.exitCode == 2);
  CHECK_THAT(splatMemory.err, Catch::Contains("read piecewise are binary INRIA .ply") &&
                                  Catch::Contains("not a LAS point cloud"));
}

TEST_CASE("a Gaussian tileset encoded in shares merges to the unsplit run's files",
          "[app][encode][splat][tileset]") {
  const auto splats = (gs::test::sourceDir() / "tests/data/splats/bunny_small.ply").string();
  const auto whole = scratch("splat_whole"), split = scratch("splat_split");
  std::filesystem::remove_all(whole);
  std::filesystem::remove_all(split);
  // 512 splats a brick: 8 leaves under a root with a merged brick.
  REQUIRE(
      runGhostspace({"encode", splats, "--tileset", whole.string() + "/", "--brick-vectors", "512"})
          .exitCode == 0);
  for (const char* share : {"2/3", "0/3", "1/3"}) {
    const auto r = runGhostspace({"encode", splats, "--tileset", split.string() + "/",
                                  "--brick-vectors", "512", "--bricks", share});
    INFO(r.err);
    REQUIRE(r.exitCode == 0);
    CHECK_THAT(r.out, Catch::Contains("After every share: ghostspace tileset index"));
  }
  const auto merge = runGhostspace({"tileset", "index", split.string() + "/"});
  INFO(merge.err);
  REQUIRE(merge.exitCode == 0);
  CHECK_THAT(merge.out, Catch::Contains("3000 splats"));
  const auto files = [](const std::filesystem::path& dir) {
    std::map<std::string, std::string> out;
    for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
      if (e.is_regular_file())
        out[std::filesystem::relative(e.path(), dir).string()] = gs::test::readBytes(e.path());
    return out;
  };
  const auto a = files(whole), b = files(split);
  CHECK(a.size() == 11);  // the index, 9 bricks (the root and 8 leaves), the merged root
  CHECK(a.count("merged/0/0_0_0.qnv") == 1);
  CHECK(a == b);  // byte for byte; the parts are removed
  // Shares encoded with other SH options: the bricks differ, the headers do not.
  std::filesystem::remove_all(split);
  for (const char* share : {"0/2", "1/2"}) {
    std::vector<std::string> args{"encode",          splats, "--tileset", split.string() + "/",
                                  "--brick-vectors", "512",  "--bricks",  share};
    if (share[0] == '1') args.insert(args.end(), {"--sh-bits", "3"});
    REQUIRE(runGhostspace(args).exitCode == 0);
  }
  const auto mixed = runGhostspace({"tileset", "index", split.string() + "/"});
  CHECK(mixed.exitCode != 0);
  CHECK_THAT(mixed.err, Catch::Contains("other SH options than share 0's (sh-bits 3"));
  // A share missing: the merge names it.
  std::filesystem::remove_all(split);
  REQUIRE(runGhostspace({"encode", splats, "--tileset", split.string() + "/", "--brick-vectors",
                         "512", "--bricks", "1/2"})
              .exitCode == 0);
  const auto missing = runGhostspace({"tileset", "index", split.string() + "/"});
  CHECK(missing.exitCode != 0);
  CHECK_THAT(missing.err, Catch::Contains("share 0 of 2 is missing"));
}

TEST_CASE("encode --sh-bits writes a smaller Gaussian stream that opens as any other",
          "[app][encode][splat][corpus]") {
  if (!gs::test::haveCorpus("splat")) return;
  // CThead's capture: SH bands 1-3, on SPZ's grid (the bunny's SH are all 0).
  const auto splats = (gs::test::corpusDir() / "splat/cthead.spz").string();
  const auto full = scratch("cthead_sh5.qnv"), coarse = scratch("cthead_sh4.qnv");
  REQUIRE(runGhostspace({"encode", splats, "-o", full.string()}).exitCode == 0);
  const auto r = runGhostspace({"encode", splats, "-o", coarse.string(), "--sh-bits", "4"});
  REQUIRE(r.exitCode == 0);
  // 19.9 -> 12.2 bytes per splat (docs/splats.md, "Bytes and pictures").
  CHECK(std::filesystem::file_size(coarse) < std::filesystem::file_size(full) * 3 / 4);
  // The most important 40% with every bit: between the two (15.3 bytes per splat).
  const auto mixed = scratch("cthead_sh4_full40.qnv");
  REQUIRE(
      runGhostspace({"encode", splats, "-o", mixed.string(), "--sh-bits", "4", "--sh-full", "0.4"})
          .exitCode == 0);
  CHECK(std::filesystem::file_size(mixed) > std::filesystem::file_size(coarse));
  CHECK(std::filesystem::file_size(mixed) < std::filesystem::file_size(full));
  const auto info = runGhostspace({"info", coarse.string()});
  CHECK(info.exitCode == 0);
  const auto shot = runGhostspace(
      {"--snapshot", scratch("cthead_sh4.png").string(), "--size", "64x64", coarse.string()});
  CHECK(shot.exitCode == 0);
}

TEST_CASE("encode keeps the paper's top 9.1% of CThead's voxels", "[app][encode][corpus]") {
  if (!gs::test::haveCorpus("volume/cthead")) return;
  const auto out = scratch("head.qnv");
  auto r = runGhostspace({"encode", (gs::test::corpusDir() / "volume/cthead/CThead.nhdr").string(),
                          "-o", out.string(), "--fraction", "0.091"});
  REQUIRE(r.exitCode == 0);
  // 256 * 256 * 113 = 7,405,568 voxels; 9.1% of them is 673,907.
  CHECK_THAT(r.out, Catch::Contains("7,405,568 voxels"));
  CHECK_THAT(r.out, Catch::Contains("kept 673,907"));
  CHECK(decodedVectors(gs::test::readBytes(out)) == 673907);
  auto info = runGhostspace({"info", out.string()});
  CHECK_THAT(info.out, Catch::Contains("256 x 256 x 113 voxels, spacing 1 1 2"));
}

TEST_CASE(
    "encoding bytes of no format the program reads fails, writes nothing, quotes no raw "
    "bytes",
    "[app][encode]") {
  // Found on a first day: random bytes were parsed as VRML, an empty stream was written
  // and the exit status was 0 (issue 42, frictions 1 and 2).
  const auto garbage = scratch("garbage.bin");
  std::string bytes;
  for (int i = 0; i < 4096; ++i) bytes.push_back(static_cast<char>((i * 7919 + 13) % 256));
  std::ofstream(garbage, std::ios::binary) << bytes;
  const auto out = scratch("garbage.qnv");
  std::filesystem::remove(out);
  const auto r = runGhostspace({"encode", garbage.string(), "-o", out.string()});
  CHECK(r.exitCode == 1);
  CHECK_FALSE(std::filesystem::exists(out));
  CHECK(r.err.find("unsupported format (.bin)") != std::string::npos);
  for (char c : r.err + r.out) {
    const auto b = static_cast<unsigned char>(c);
    CHECK((b == '\n' || (b >= 0x20 && b < 0x7f)));
  }
  // A mesh file GhostSpace does not read, opened as a snapshot: the same sentence, exit 1.
  const auto stl = scratch("landscape.stl");
  std::ofstream(stl, std::ios::binary) << "solid landscape\n facet normal 0 0 1\n\x1b[31m\x01";
  const auto s = runGhostspace(
      {"--snapshot", scratch("landscape.png").string(), "--size", "16x16", stl.string()});
  CHECK(s.exitCode == 1);
  CHECK(s.err.find("unsupported format (.stl)") != std::string::npos);
  CHECK(s.err.find('\x1b') == std::string::npos);

  // A mesh whose every triangle is degenerate: nothing to encode, exit 1, no file.
  const auto flat = scratch("flat.obj");
  std::ofstream(flat) << "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n";
  const auto flatOut = scratch("flat.qnv");
  std::filesystem::remove(flatOut);
  const auto f = runGhostspace({"encode", flat.string(), "-o", flatOut.string()});
  CHECK(f.exitCode == 1);
  CHECK(f.err.find("nothing to encode") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(flatOut));
}

TEST_CASE("a snapshot of a stream that holds no vectors fails", "[app][encode]") {
  gs::qnv::EncodedVectors none;
  none.header.boundsMax = glm::vec3(1.0f);
  const auto empty = scratch("empty.qnv");
  std::ofstream(empty, std::ios::binary) << gs::qnv::writeStream(none);
  const auto r = runGhostspace(
      {"--snapshot", scratch("empty.png").string(), "--size", "16x16", empty.string()});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("nothing to draw") != std::string::npos);
}

TEST_CASE("a truncated stream says so once", "[app][encode]") {
  // Issue 42, friction 8: the decoder's "stream ends after ..." came twice.
  const auto obj = scratch("quad.obj");
  std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n";
  for (int i = 0; i < 200; ++i) std::ofstream(obj, std::ios::app) << "f 1 2 3\nf 1 3 4\n";
  const auto full = scratch("quad.qnv");
  REQUIRE(runGhostspace({"encode", obj.string(), "-o", full.string(), "--packet-bytes", "48"})
              .exitCode == 0);
  const std::string bytes = gs::test::readBytes(full);
  const auto cut = scratch("quad_cut.qnv");
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const auto r =
      runGhostspace({"--snapshot", scratch("cut.png").string(), "--size", "16x16", cut.string()});
  const std::string line = "stream ends after";
  const std::size_t first = r.err.find(line);
  REQUIRE(first != std::string::npos);
  CHECK(r.err.find(line, first + 1) == std::string::npos);
}

TEST_CASE("encoding a splat scene with nothing to draw fails and writes nothing", "[app][encode]") {
  // Two Gaussians, both transparent (logit opacity -100).
  const auto ply = scratch("transparent.ply");
  std::ofstream(ply) << "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\n"
                        "property float y\nproperty float z\nproperty float f_dc_0\n"
                        "property float f_dc_1\nproperty float f_dc_2\nproperty float opacity\n"
                        "property float scale_0\nproperty float scale_1\nproperty float scale_2\n"
                        "property float rot_0\nproperty float rot_1\nproperty float rot_2\n"
                        "property float rot_3\nend_header\n"
                        "0 0 0 0 0 0 -100 -3 -3 -3 1 0 0 0\n1 0 0 0 0 0 -100 -3 -3 -3 1 0 0 0\n";
  const auto out = scratch("transparent.qnv");
  std::filesystem::remove(out);
  const auto r = runGhostspace({"encode", ply.string(), "-o", out.string()});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("nothing to encode") != std::string::npos);
  CHECK_FALSE(std::filesystem::exists(out));
}
