// Reading a Gaussian splatting scene piecewise (splats/readers.hpp: openGaussianBatches,
// the out-of-core tileset encode's input): every batch size gives the whole reader's
// splats, bit for bit, in either byte order and for .splat; the frame built over batches
// is gaussianFrame's; the formats not read piecewise are refused by name.
#include <catch2/catch.hpp>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>

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

}  // namespace

TEST_CASE("openGaussianBatches gives the whole reader's splats for every batch size",
          "[splats][ooc]") {
  const fs::path ply = splatData("bunny_small.ply"), splat = splatData("bunny_small.splat");
  const std::string plyBytes = gs::test::readBytes(ply);
  const GaussianCloud wholePly = readPlyGaussians(plyBytes, ply.string());
  const GaussianCloud wholeSplat = readSplatGaussians(gs::test::readBytes(splat), splat.string());
  gs::test::TempDir dir("gaussian_batches");
  const fs::path be = dir.path / "bunny_be.ply";
  std::ofstream(be, std::ios::binary) << bigEndian(plyBytes);
  for (const auto& [path, whole] :
       {std::pair{ply, &wholePly}, std::pair{splat, &wholeSplat}, std::pair{be, &wholePly}}) {
    INFO(path.string());
    const auto reader = openGaussianBatches(path.string());
    CHECK(reader->size() == whole->size());
    CHECK(reader->shDegree() == whole->shDegree);
    for (const std::size_t size :
         {std::size_t{1}, std::size_t{7}, std::size_t{1000}, std::size_t{1u << 20}}) {
      INFO(size);
      checkSameBits(readInBatches(*reader, size), *whole);
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
  for (const char* file :
       {"bunny_small.spz", "bunny_small.compressed.ply", "bunny_small.sog", "bunny_small.glb"}) {
    INFO(file);
    CHECK_THROWS_AS(openGaussianBatches(splatData(file).string()), NotPiecewiseError);
    CHECK_THROWS_WITH(openGaussianBatches(splatData(file).string()),
                      Catch::Contains(file) && Catch::Contains("read piecewise are binary"));
  }
  gs::test::TempDir dir("gaussian_batches_bad");
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
