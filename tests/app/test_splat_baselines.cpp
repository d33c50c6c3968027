// Splat rendering baselines (paper sections 3.1-3.5; docs/rendering-tests.md): CThead as
// QNV at the paper's figure 2 fractions and whole, the bunny as splats against the bunny
// as polygons, and a KiCad world as polygons and as splats.
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "baseline.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

namespace fs = std::filesystem;
using gs::test::checkBaseline;

namespace {

// CThead has 7,405,568 voxels of which 5,879,563 have a gradient: a stream of all of
// them drawn at --lod F * 7405568 / 5879563 shows the top F of the voxels.
std::string ctheadLod(double fractionOfVoxels) {
  return std::to_string(fractionOfVoxels * 7405568.0 / 5879563.0);
}

std::string ctheadStream() {
  const fs::path out = fs::path(GS_BINARY_DIR) / "render-actual" / "cthead_all.qnv";
  if (!fs::exists(out)) {
    // Tests running side by side may both encode it: each writes its own file and renames
    // it into place, so that no test ever reads a half-written stream.
    fs::create_directories(out.parent_path());
    const fs::path mine = out.string() + "." + std::to_string(::getpid());
    const auto r = gs::test::runGhostspace(
        {"encode", (gs::test::corpusDir() / "volume/cthead/CThead.nhdr").string(), "-o",
         mine.string(), "--no-progress"});
    REQUIRE(r.exitCode == 0);
    fs::rename(mine, out);
  }
  return out.string();
}

}  // namespace

TEST_CASE("CThead as QNV at the paper's fractions matches its baselines",
          "[heavy][app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("volume/cthead")) return;
  const std::string stream = ctheadStream();
  for (const auto& [name, fraction] :
       {std::pair{"cthead_qnv_1_2", 0.012}, std::pair{"cthead_qnv_3_5", 0.035},
        std::pair{"cthead_qnv_9_1", 0.091}}) {
    SECTION(name) {
      checkBaseline(name, {"--size", "200x200", "--lod", ctheadLod(fraction), stream});
    }
  }
  SECTION("cthead_qnv_all") {
    checkBaseline("cthead_qnv_all", {"--size", "200x200", stream});
  }
}

TEST_CASE("the top 9.1% of CThead's vectors look like all of them",
          "[heavy][app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("volume/cthead")) return;
  const std::string stream = ctheadStream();
  const std::string top = gs::test::snapshot(
      "cthead_top_9_1", {"--size", "200x200", "--lod", ctheadLod(0.091), stream});
  const std::string all = gs::test::snapshot("cthead_top_all", {"--size", "200x200", stream});
  const std::string few = gs::test::snapshot(
      "cthead_top_1_2", {"--size", "200x200", "--lod", ctheadLod(0.012), stream});
  const double topVsAll = gs::test::fractionDiffering(top, all);
  const double fewVsAll = gs::test::fractionDiffering(few, all);
  WARN("CThead 9.1% against 100%: " << topVsAll * 100
                                    << "% of pixels differ; 1.2%: " << fewVsAll * 100);
  CHECK(topVsAll < fewVsAll);  // more vectors, closer to the whole picture
}

TEST_CASE("a volume snapshots straight from its NRRD file", "[heavy][app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("volume/cthead")) return;
  const std::string direct = gs::test::snapshot(
      "cthead_direct", {"--size", "200x200", "--lod", ctheadLod(0.091),
                        (gs::test::corpusDir() / "volume/cthead/CThead.nhdr").string()});
  const std::string viaStream = gs::test::snapshot(
      "cthead_via_stream", {"--size", "200x200", "--lod", ctheadLod(0.091), ctheadStream()});
  CHECK(gs::test::fractionDiffering(direct, viaStream) <= gs::test::kMaxFractionDiffering);
}

TEST_CASE("the bunny as splats looks like the bunny as polygons",
          "[heavy][app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("mesh/bunny")) return;
  const std::string bunny = (gs::test::corpusDir() / "mesh/bunny/bun_zipper.ply").string();
  checkBaseline("bunny_polygons", {"--size", "200x200", bunny});
  checkBaseline("bunny_splats", {"--size", "200x200", "--mode", "splats", bunny});
  // Flat-shaded splats against smooth-shaded polygons: the shapes agree, the shading
  // differs by a few levels over most of the body (docs/rendering-tests.md).
  const std::string polygons = gs::test::snapshot("bunny_polygons", {"--size", "200x200", bunny});
  const std::string splats =
      gs::test::snapshot("bunny_splats", {"--size", "200x200", "--mode", "splats", bunny});
  const double at16 = gs::test::fractionDiffering(polygons, splats, 16);
  const double at48 = gs::test::fractionDiffering(polygons, splats, 48);
  WARN("bunny splats against polygons: " << at16 * 100 << "% of pixels differ by more than 16/255, "
                                         << at48 * 100 << "% by more than 48/255");
  CHECK(at48 <= 0.05);
}

TEST_CASE("a KiCad world as polygons and as splats", "[app][render][splat][corpus]") {
  if (!gs::test::haveCorpus("vrml/kicad")) return;
  const std::string world =
      (gs::test::corpusDir() / "vrml/kicad/Capacitor_SMD__CP_Elec_5x3.wrl").string();
  checkBaseline("kicad_cp_elec_polygons", {"--size", "200x200", "--fit", world});
  checkBaseline("kicad_cp_elec_splats", {"--size", "200x200", "--fit", "--mode", "splats", world});
  // Outlines only: the world written outlines-first (section 1.1), drawn without polygons.
  const fs::path outlined =
      fs::path(GS_BINARY_DIR) / "render-actual" / "kicad_cp_elec_outlined.wrl";
  const auto r = gs::test::runGhostspace({"encode", "--outline", world, "-o", outlined.string()});
  REQUIRE(r.exitCode == 0);
  checkBaseline("kicad_cp_elec_outlines",
                {"--size", "200x200", "--fit", "--mode", "outlines", outlined.string()});
}

TEST_CASE("a volume opens in the front view: along +Y, slices upright", "[app][render][splat]") {
  // Issue 42, friction 9: a CT stack opened looking down its slice axis (CThead from
  // above). A slab of the rows' plane (y = 1..3 of 16, its gradients along y) fills the
  // front view and is a thin line from above.
  gs::test::TempDir dir("front_view");
  std::string voxels(16 * 16 * 16, '\0');
  for (int z = 0; z < 16; ++z)
    for (int x = 0; x < 16; ++x)
      for (const auto& [y, value] : {std::pair{1, '\x80'}, {2, '\xff'}, {3, '\x80'}})
        voxels[static_cast<std::size_t>(x + 16 * (y + 16 * z))] = value;
  const std::string volume =
      dir.write("slab.nrrd",
                "NRRD0004\ntype: uint8\ndimension: 3\nsizes: 16 16 16\nencoding: raw\n\n" + voxels);
  const std::string png = (dir.path / "slab.png").string();
  const auto r = gs::test::runGhostspace({"--snapshot", png, "--size", "64x64", volume});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  const gs::render::Image image = gs::render::readPng(png);
  std::size_t lit = 0;
  for (std::size_t i = 0; i < image.rgba.size(); i += 4)
    lit += image.rgba[i] > 16 || image.rgba[i + 1] > 16 || image.rgba[i + 2] > 16;
  CHECK(lit > 64 * 64 / 4);  // seen face on, not edge on
}
