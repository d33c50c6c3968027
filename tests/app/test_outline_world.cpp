// `ghostspace encode --outline`: the outline-group world writer (paper section 1.1), end to
// end with the real binary: reparse, triangle counts, outlines first, same picture.
#include "encodings/parser.hpp"
#include "outline/outline_world.hpp"
#include "process.hpp"
#include "render/image.hpp"
#include "scene/traversal.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

using gs::test::runGhostspace;
namespace fs = std::filesystem;

namespace {

/// Triangles drawn from the bound viewpoint (outline shapes counted apart).
struct Counts {
  std::size_t triangles = 0, outlineTriangles = 0;
};
Counts countTriangles(std::shared_ptr<const gs::vrml::Scene> scene) {
  gs::scene::SceneTraversal t(std::move(scene));
  gs::scene::TraversalFrame frame;
  t.collect(t.boundViewpointCamera(), frame);
  Counts c;
  for (const auto& s : frame.shapes)
    (s.geometry->typeName() == "OutlineGroup" ? c.outlineTriangles : c.triangles) +=
        t.mesh(*s.geometry).triangleCount();
  return c;
}

double snapshotDifference(const fs::path& a, const fs::path& b, const std::string& tag) {
  const fs::path dir = fs::temp_directory_path();
  const fs::path pa = dir / ("gs_outline_" + tag + "_a.png");
  const fs::path pb = dir / ("gs_outline_" + tag + "_b.png");
  const auto ra = runGhostspace({"--snapshot", pa.string(), "--size", "200x200", a.string()});
  const auto rb = runGhostspace({"--snapshot", pb.string(), "--size", "200x200", b.string()});
  REQUIRE(ra.exitCode == 0);
  REQUIRE(rb.exitCode == 0);
  const auto d =
      gs::render::compareImages(gs::render::readPng(pa.string()), gs::render::readPng(pb.string()));
  return d.fractionDiffering;
}

/// Encodes `input` with --outline and checks the output; returns its path.
fs::path encodeAndCheck(const fs::path& input, const std::string& tag) {
  const fs::path out = fs::temp_directory_path() / ("gs_outline_" + tag + ".wrl");
  fs::remove(out);
  const auto r = runGhostspace({"encode", "--outline", input.string(), "-o", out.string()});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("groups") != std::string::npos);
  CHECK(r.out.find("outline vertices") != std::string::npos);
  const std::string text = gs::test::readBytes(out);
  REQUIRE(text.rfind("#VRML V2.0 utf8", 0) == 0);

  auto reparsed = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(text, out.string()));
  for (const auto& d : reparsed->diagnostics.items) FAIL_CHECK(d.format());
  CHECK(reparsed->diagnostics.items.empty());

  auto original = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile(input.string()));
  const Counts before = countTriangles(original);
  const Counts after = countTriangles(reparsed);
  CHECK(after.triangles == before.triangles);
  CHECK(after.outlineTriangles == 0);  // every group's polygons are there

  // Outlines first: no polygon before the last outline.
  const auto firstPolygon = text.find("children [");
  const auto lastOutline = text.rfind("outline [");
  REQUIRE(firstPolygon != std::string::npos);
  REQUIRE(lastOutline != std::string::npos);
  CHECK(lastOutline < firstPolygon);
  return out;
}

}  // namespace

TEST_CASE("encode --outline rewrites the welcome world outlines first", "[app][outline]") {
  const fs::path in = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  const fs::path out = encodeAndCheck(in, "welcome");
  // Textures are dropped by design (the checker-textured box turns plain white).
  const double diff = snapshotDifference(in, out, "welcome");
  WARN("welcome.wrl: differing pixels, outline world vs input (texture dropped): " << diff);
  CHECK(diff <= 0.10);
  // Without its one texture the world must render the same.
  std::string text = gs::test::readBytes(in);
  const auto at = text.find("texture ImageTexture");
  REQUIRE(at != std::string::npos);
  text.erase(at, text.find('}', at) + 1 - at);
  const fs::path plain = fs::temp_directory_path() / "gs_outline_input_untextured.wrl";
  {
    std::ofstream f(plain, std::ios::binary);
    f << text;
  }
  const fs::path plainOut = encodeAndCheck(plain, "welcome_untextured");
  const double plainDiff = snapshotDifference(plain, plainOut, "welcome_untextured");
  WARN("welcome.wrl without texture: differing pixels, outline world vs input: " << plainDiff);
  CHECK(plainDiff <= 0.01);
}

TEST_CASE("encode --outline on a KiCad world: same picture, outline-only prefix",
          "[app][outline][corpus]") {
  if (!gs::test::haveCorpus("vrml/kicad")) return;
  const fs::path in =
      gs::test::corpusDir() / "vrml/kicad/Capacitor_THT__CP_Radial_D10.0mm_P3.80mm.wrl";
  if (!fs::exists(in)) return;
  const fs::path out = encodeAndCheck(in, "kicad");
  const double diff = snapshotDifference(in, out, "kicad");
  WARN("KiCad world: differing pixels, outline world vs input: " << diff);
  CHECK(diff <= 0.01);

  // The prefix before the first polygon is a world of outlines only.
  const std::string text = gs::test::readBytes(out);
  const std::size_t prefixBytes = text.find("OutlineGroup { groupId 0 children");
  REQUIRE(prefixBytes != std::string::npos);
  const fs::path prefix = fs::temp_directory_path() / "gs_outline_kicad_prefix.wrl";
  {
    std::ofstream f(prefix, std::ios::binary);
    f << text.substr(0, prefixBytes);
  }
  auto scene = std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml(text.substr(0, prefixBytes), prefix.string()));
  CHECK(scene->diagnostics.items.empty());
  const Counts c = countTriangles(scene);
  CHECK(c.triangles == 0);
  CHECK(c.outlineTriangles > 0);
  const double prefixDiff = snapshotDifference(in, prefix, "kicad_prefix");
  WARN("KiCad world: input " << fs::file_size(in) << " bytes, outline world " << text.size()
                             << " bytes, outline prefix " << prefixBytes
                             << " bytes; prefix picture differs in " << prefixDiff
                             << " of the pixels");
  CHECK(prefixDiff < 0.5);
}

TEST_CASE("writeOutlineWorld keeps the viewpoint and background", "[app][outline]") {
  const std::string text =
      "#VRML V2.0 utf8\n"
      "Background { skyColor [ 0.1 0.2 0.3 ] groundColor [ 0.3 0.2 0.1 ] groundAngle [] }\n"
      "Transform { translation 1 0 0 children [\n"
      "  Viewpoint { position 0 0 5 fieldOfView 0.5 description \"front\" }\n"
      "  Shape { appearance Appearance { material Material { diffuseColor 1 0 0 } }\n"
      "          geometry Box {} } ] }\n";
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(text, "/tmp/vp.wrl"));
  gs::outline::OutlineWorldSummary sum;
  const std::string out = gs::outline::writeOutlineWorld(scene, {}, &sum);
  CHECK(sum.groups == 6);
  CHECK(sum.triangles == 12);
  CHECK(sum.appearances == 1);
  CHECK(sum.outlineBytes < sum.bytes);
  CHECK(out.find("position 1 0 5") != std::string::npos);
  CHECK(out.find("fieldOfView 0.5") != std::string::npos);
  CHECK(out.find("skyColor [\n    0.1 0.2 0.3 ]") != std::string::npos);
  CHECK(out.find("DEF A0 Appearance") < out.find("USE A0"));
  auto re = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(out, "/tmp/vp2.wrl"));
  CHECK(re->diagnostics.items.empty());
  gs::scene::SceneTraversal t(re);
  REQUIRE(t.viewpoints().size() == 1);
  CHECK(t.viewpoints()[0].camera.position.x == Approx(1.0f));
  CHECK(t.background().skyColor.front().z == Approx(0.3f));
}
