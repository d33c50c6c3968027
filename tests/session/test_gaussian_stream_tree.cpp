// A Gaussian QNV stream (splats/qnv_gaussians.hpp) opened in a session gets its
// level-of-detail tree once it has arrived whole (StreamingSession::pump), as a capture
// read whole does; the session is not settled until the tree is attached, so a snapshot
// draws the same cut on every machine.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "base/file.hpp"
#include "qnv/stream.hpp"
#include "render/splat_renderer.hpp"
#include "session/streaming_session.hpp"
#include "splats/qnv_gaussians.hpp"
#include "splats/readers.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

TEST_CASE("a Gaussian stream gets its level-of-detail tree once it has arrived whole",
          "[session][splat][qnv]") {
  std::string bytes, error;
  const fs::path ply = gs::test::sourceDir() / "tests/data/splats/bunny_small.ply";
  REQUIRE(gs::base::readFile(ply.string(), bytes, error, std::size_t{1} << 26));
  const gs::splats::GaussianCloud cloud =
      gs::splats::readGaussians(bytes, ply.string(), gs::splats::SideFileReader{});
  const gs::qnv::EncodedVectors encoded = gs::splats::encodeGaussianStream(cloud);
  const fs::path qnv = fs::temp_directory_path() / "gs_gaussian_stream_tree.qnv";
  {
    std::ofstream out(qnv, std::ios::binary);
    out << gs::qnv::writeStream(encoded,
                                {encoded.header.packetBytes, gs::qnv::PacketEncoding::compact});
  }
  gs::session::StreamingSession s;
  auto scene = s.open(qnv.string(), error);
  REQUIRE(scene);
  auto options = s.rendererOptions({});
  auto set = options.splatLoader(qnv.string(), "", error);
  REQUIRE(set);
  set->wantedVectors = std::uint64_t{1} << 40;  // a view that asks for every splat
  bool settled = false;
  for (int i = 0; i < 100000 && !settled; ++i) {
    s.pump();
    settled = s.settled();
    if (!settled) s.loader().wait(0.01);
  }
  REQUIRE(settled);
  REQUIRE(set->gaussians);
  CHECK(set->gaussians->size() == cloud.size());
  // Settled means the tree is attached: over the stream's splats, with merged nodes.
  REQUIRE(set->lodTree);
  CHECK(set->lodTree->merged.size() > 0);
  CHECK(set->lodTree->merged.size() < set->gaussians->size());
  fs::remove(qnv);
}

TEST_CASE("a Gaussian stream resting at its views' prefix gets a tree over that prefix",
          "[session][splat][qnv]") {
  std::string bytes, error;
  const fs::path ply = gs::test::sourceDir() / "tests/data/splats/bunny_small.ply";
  REQUIRE(gs::base::readFile(ply.string(), bytes, error, std::size_t{1} << 26));
  const gs::splats::GaussianCloud bunny =
      gs::splats::readGaussians(bytes, ply.string(), gs::splats::SideFileReader{});
  // Ten bunnies side by side: a stream of many requests (each at least 64 KiB).
  gs::splats::GaussianCloud cloud;
  cloud.shDegree = bunny.shDegree;
  for (int k = 0; k < 10; ++k)
    for (std::size_t i = 0; i < bunny.size(); ++i) {
      cloud.append(bunny, i);
      cloud.positions.back().x += 0.3f * static_cast<float>(k);
    }
  const gs::qnv::EncodedVectors encoded = gs::splats::encodeGaussianStream(cloud);
  const fs::path qnv = fs::temp_directory_path() / "gs_gaussian_stream_prefix_tree.qnv";
  {
    // Packets of 64 splats, so that a quarter of them is a prefix of several packets.
    std::ofstream out(qnv, std::ios::binary);
    out << gs::qnv::writeStream(
        encoded, {8 * 64 * encoded.header.recordsPerElement(), gs::qnv::PacketEncoding::compact});
  }
  gs::session::StreamingSession s;
  auto scene = s.open(qnv.string(), error);
  REQUIRE(scene);
  auto options = s.rendererOptions({});
  auto set = options.splatLoader(qnv.string(), "", error);
  REQUIRE(set);
  const auto settle = [&] {
    bool settled = false;
    for (int i = 0; i < 100000 && !settled; ++i) {
      s.pump();
      settled = s.settled();
      if (!settled) s.loader().wait(0.01);
    }
    return settled;
  };
  // A far view asks for a quarter: the stream rests there, and its tree covers what came.
  set->wantedVectors = cloud.size() / 4;
  REQUIRE(settle());
  REQUIRE(set->gaussians);
  const std::size_t prefix = set->gaussians->size();
  CHECK(prefix >= cloud.size() / 4);
  CHECK(prefix < cloud.size());
  REQUIRE(set->lodTree);
  CHECK(set->lodTree->splatCount == prefix);
  CHECK(set->lodTree->merged.size() > 0);
  // A nearer view asks for every splat: a tree over all of them replaces it.
  const auto* first = set->lodTree.get();
  set->wantedVectors = std::uint64_t{1} << 40;
  REQUIRE(settle());
  CHECK(set->gaussians->size() == cloud.size());
  REQUIRE(set->lodTree);
  CHECK(set->lodTree.get() != first);
  CHECK(set->lodTree->splatCount == cloud.size());
  fs::remove(qnv);
}
