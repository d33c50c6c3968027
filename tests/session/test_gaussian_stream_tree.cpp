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

namespace {

/// tests/data/splats/bunny_small.ply (3,000 splats).
gs::splats::GaussianCloud smallBunny() {
  std::string bytes, error;
  const fs::path ply = gs::test::sourceDir() / "tests/data/splats/bunny_small.ply";
  REQUIRE(gs::base::readFile(ply.string(), bytes, error, std::size_t{1} << 26));
  return gs::splats::readGaussians(bytes, ply.string(), gs::splats::SideFileReader{});
}

/// `cloud` written as a compact Gaussian stream to the temporary file `name`, in packets of
/// `packetSplats` splats (0: the encoder's own size).
fs::path writeGaussianStream(const gs::splats::GaussianCloud& cloud, const std::string& name,
                             std::uint32_t packetSplats = 0) {
  const gs::qnv::EncodedVectors encoded = gs::splats::encodeGaussianStream(cloud);
  const fs::path qnv = fs::temp_directory_path() / name;
  const std::uint32_t packetBytes = packetSplats == 0
                                        ? encoded.header.packetBytes
                                        : 8 * packetSplats * encoded.header.recordsPerElement();
  std::ofstream out(qnv, std::ios::binary);
  out << gs::qnv::writeStream(encoded, {packetBytes, gs::qnv::PacketEncoding::compact});
  return qnv;
}

/// A session streaming one Gaussian stream, and its splat set.
struct StreamedSet {
  gs::session::StreamingSession session;
  std::shared_ptr<const gs::render::SplatSet> set;

  explicit StreamedSet(const fs::path& qnv) {
    std::string error;
    REQUIRE(session.open(qnv.string(), error));
    set = session.rendererOptions({}).splatLoader(qnv.string(), "", error);
    REQUIRE(set);
  }
  /// Pumps until the session settles (at most 100,000 rounds); whether it did.
  bool settle() {
    bool settled = false;
    for (int i = 0; i < 100000 && !settled; ++i) {
      session.pump();
      settled = session.settled();
      if (!settled) session.loader().wait(0.01);
    }
    return settled;
  }
};

}  // namespace

TEST_CASE("a Gaussian stream gets its level-of-detail tree once it has arrived whole",
          "[session][splat][qnv]") {
  const gs::splats::GaussianCloud cloud = smallBunny();
  const fs::path qnv = writeGaussianStream(cloud, "gs_gaussian_stream_tree.qnv");
  StreamedSet streamed(qnv);
  const auto& set = streamed.set;
  set->wantedVectors = std::uint64_t{1} << 40;  // a view that asks for every splat
  REQUIRE(streamed.settle());
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
  const gs::splats::GaussianCloud bunny = smallBunny();
  // Ten bunnies side by side: a stream of many requests (each at least 64 KiB).
  gs::splats::GaussianCloud cloud;
  cloud.shDegree = bunny.shDegree;
  for (int k = 0; k < 10; ++k)
    for (std::size_t i = 0; i < bunny.size(); ++i) {
      cloud.append(bunny, i);
      cloud.positions.back().x += 0.3f * static_cast<float>(k);
    }
  // Packets of 64 splats, so that a quarter of them is a prefix of several packets.
  const fs::path qnv = writeGaussianStream(cloud, "gs_gaussian_stream_prefix_tree.qnv", 64);
  StreamedSet streamed(qnv);
  const auto& set = streamed.set;
  // A far view asks for a quarter: the stream rests there, and its tree covers what came.
  set->wantedVectors = cloud.size() / 4;
  REQUIRE(streamed.settle());
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
  REQUIRE(streamed.settle());
  CHECK(set->gaussians->size() == cloud.size());
  REQUIRE(set->lodTree);
  CHECK(set->lodTree.get() != first);
  CHECK(set->lodTree->splatCount == cloud.size());
  fs::remove(qnv);
}
