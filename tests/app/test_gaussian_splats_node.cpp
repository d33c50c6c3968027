// X_ITE's GaussianSplats node (docs/splats.md, "The GaussianSplats node"): Gaussians given
// as fields and a capture named by url, placed under Transforms beside polygons, in the
// Classic VRML and XML encodings of one world (tests/data/splats/gaussian_splats_node.*).
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "baseline.hpp"
#include "process.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;

namespace {

std::string splatData(const std::string& name) {
  return (gs::test::sourceDir() / "tests" / "data" / "splats" / name).string();
}

}  // namespace

TEST_CASE("a GaussianSplats node draws its field Gaussians and its url's capture",
          "[app][render][splat]") {
  // Three anisotropic Gaussians (red along x, green turned 90 degrees about z, a small
  // blue one), the corpus bunny's capture from bunny_small.spz, and a Box.
  gs::test::checkBaseline("gaussian_splats_node",
                          {"--size", "320x240", splatData("gaussian_splats_node.x3dv")});
  // The XML encoding of the same world gives the same picture.
  const std::string classic = gs::test::snapshot(
      "gaussian_splats_node_x3dv", {"--size", "160x120", splatData("gaussian_splats_node.x3dv")});
  const std::string xml = gs::test::snapshot(
      "gaussian_splats_node_x3d", {"--size", "160x120", splatData("gaussian_splats_node.x3d")});
  CHECK(gs::test::fractionDiffering(classic, xml) == 0.0);
}

TEST_CASE("a GaussianSplats node without Gaussians draws nothing; a bad url is an error",
          "[app][render][splat]") {
  const fs::path dir = fs::path(GS_BINARY_DIR) / "render-actual";
  fs::create_directories(dir);
  const fs::path empty = dir / "gaussian_splats_empty.x3dv";
  std::ofstream(empty) << "#X3D V4.0 utf8\nViewpoint { position 0 0 6 }\nGaussianSplats { }\n";
  const std::string png =
      gs::test::snapshot("gaussian_splats_empty", {"--size", "64x48", empty.string()});
  const auto c = gs::test::centrePixel(png);
  CHECK(c[0] + c[1] + c[2] == 0);
  const fs::path bad = dir / "gaussian_splats_bad_url.x3dv";
  std::ofstream(bad) << "#X3D V4.0 utf8\nGaussianSplats { url \"missing.spz\" }\n"
                     << "Shape { geometry Box { } }\n";
  // The rest of the world is drawn and the error printed, naming the file (README:
  // --snapshot's exit codes, 0 for a world with diagnostics).
  const auto r = gs::test::runGhostspace(
      {"--snapshot", (dir / "gaussian_splats_bad.png").string(), bad.string()});
  CHECK(r.exitCode == 0);
  CHECK_THAT(r.err, Catch::Matchers::Contains("missing.spz"));
  CHECK_THAT(r.err, Catch::Matchers::Contains("GaussianSplats: no url could be loaded"));
}
