// End-to-end tests of the command line: the real binary, its exit codes and messages.
#include "process.hpp"
#include "render/image.hpp"
#include "test_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using gs::test::runGhostspace;

TEST_CASE("the help option describes the options and exits 0", "[app][cli]") {
  auto r = runGhostspace({"--help"});
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("--snapshot") != std::string::npos);
  CHECK(r.out.find("--size") != std::string::npos);
  CHECK(r.out.find("info") != std::string::npos);
}

TEST_CASE("the version option prints the version", "[app][cli]") {
  auto r = runGhostspace({"--version"});
  CHECK(r.exitCode == 0);
  CHECK(r.out.rfind("ghostspace ", 0) == 0);
}

TEST_CASE("an unknown option is an error that names it", "[app][cli]") {
  auto r = runGhostspace({"--frobnicate", "x.wrl"});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("--frobnicate") != std::string::npos);
}

TEST_CASE("the size option must be WxH", "[app][cli]") {
  auto r = runGhostspace({"--snapshot", "/tmp/x.png", "--size", "800by600", "a.wrl"});
  CHECK(r.exitCode == 2);
  CHECK(r.err.find("800by600") != std::string::npos);
}

TEST_CASE("snapshot of a missing file fails with one line naming it", "[app][cli]") {
  auto out = std::filesystem::temp_directory_path() / "gs_missing.png";
  std::filesystem::remove(out);
  auto r = runGhostspace({"--snapshot", out.string(), "/nonexistent/world.wrl"});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("/nonexistent/world.wrl") != std::string::npos);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK_FALSE(std::filesystem::exists(out));
}

TEST_CASE("snapshot of a VRML 1.0 file says it is not supported", "[app][cli]") {
  auto in = std::filesystem::temp_directory_path() / "gs_v1.wrl";
  {
    std::ofstream f(in);
    f << "#VRML V1.0 ascii\nSeparator { Cube {} }\n";
  }
  auto r = runGhostspace({"--snapshot", "/tmp/gs_v1.png", in.string()});
  CHECK(r.exitCode == 1);
  CHECK(r.err.find("VRML 1.0 is not supported") != std::string::npos);
}

TEST_CASE("info prints counts, triangles, bounds and timing", "[app][cli]") {
  auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto r = runGhostspace({"info", world.string()});
  CHECK(r.exitCode == 0);
  CHECK(r.out.find("Transform") != std::string::npos);
  CHECK(r.out.find("triangles") != std::string::npos);
  CHECK(r.out.find("bounding box") != std::string::npos);
  CHECK(r.out.find("parse") != std::string::npos);
}

TEST_CASE("README.md names every option --help lists", "[app][cli]") {
  // The command line (CLI11) is where options are declared; the README's table must not
  // fall behind it.
  const std::string readme = gs::test::readBytes(gs::test::sourceDir() / "README.md");
  REQUIRE_FALSE(readme.empty());
  for (const std::vector<std::string>& args : {std::vector<std::string>{"--help"},
                                               {"info", "--help"},
                                               {"encode", "--help"},
                                               {"convert", "--help"}}) {
    const auto r = runGhostspace(args);
    REQUIRE(r.exitCode == 0);
    std::size_t at = 0, found = 0;
    while ((at = r.out.find("--", at)) != std::string::npos) {
      std::size_t end = at + 2;
      while (end < r.out.size() &&
             (std::isalnum(static_cast<unsigned char>(r.out[end])) || r.out[end] == '-'))
        ++end;
      const std::string option = r.out.substr(at, end - at);
      at = end;
      if (option.size() < 4 || !std::isalpha(static_cast<unsigned char>(option[2]))) continue;
      ++found;
      INFO(args.front() << ": " << option);
      CHECK(readme.find(option) != std::string::npos);
    }
    CHECK(found > 0);
  }
}

TEST_CASE("README.md's option table is what --help-markdown prints", "[app][cli]") {
  // One table (app/src/option_table.cpp) declares every option: CLI11, --help and
  // README.md's table between the marker comments. Regenerate it with
  // `ghostspace --help-markdown` when an option changes.
  const std::string readme = gs::test::readBytes(gs::test::sourceDir() / "README.md");
  const std::string begin = "<!-- options:begin (ghostspace --help-markdown) -->\n";
  const std::string end = "<!-- options:end -->";
  const std::size_t from = readme.find(begin), to = readme.find(end);
  REQUIRE(from != std::string::npos);
  REQUIRE(to != std::string::npos);
  REQUIRE(from < to);
  const auto r = runGhostspace({"--help-markdown"});
  REQUIRE(r.exitCode == 0);
  CHECK(readme.substr(from + begin.size(), to - from - begin.size()) == r.out);
}

TEST_CASE("info exits 1 for a world with errors unless --exit-zero", "[app][cli]") {
  gs::test::TempDir dir("info");
  const std::string bad = dir.write(
      "bad.wrl", "#VRML V2.0 utf8\nShape { geometry Box { size 1 1 1 } }\nNoSuchNode { }\n");
  const auto strict = runGhostspace({"info", bad});
  CHECK(strict.exitCode == 1);
  CHECK(strict.out.find("1 errors") != std::string::npos);
  CHECK(strict.out.find("NoSuchNode") != std::string::npos);
  const auto lenient = runGhostspace({"info", "--exit-zero", bad});
  CHECK(lenient.exitCode == 0);
  CHECK(lenient.out.find("NoSuchNode") != std::string::npos);  // the same report
  // A clean world gives 0; one world with errors among several gives 1.
  const auto good = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  CHECK(runGhostspace({"info", good.string()}).exitCode == 0);
  CHECK(runGhostspace({"info", good.string(), bad}).exitCode == 1);
}

TEST_CASE("snapshot writes a PNG of the bundled scene", "[app][cli][snapshot]") {
  auto world = gs::test::sourceDir() / "assets/worlds/welcome.wrl";
  auto out = std::filesystem::temp_directory_path() / "gs_welcome_test.png";
  std::filesystem::remove(out);
  auto r = runGhostspace({"--snapshot", out.string(), "--size", "160x120", world.string()});
  INFO(r.err);
  CHECK(r.exitCode == 0);
  REQUIRE(std::filesystem::exists(out));
  CHECK(std::filesystem::file_size(out) > 100);
}

TEST_CASE("convert writes a world in the encoding OUT's extension names", "[app][cli]") {
  gs::test::TempDir dir("convert");
  const auto x3dv = gs::test::sourceDir() / "assets/worlds/x3d_features.x3dv";
  // X3D Classic -> XML -> JSON -> Classic: each step reads back with no diagnostic.
  const std::string xml = (dir.path / "w.x3d").string();
  const std::string json = (dir.path / "w.x3dj").string();
  const std::string classic = (dir.path / "w.x3dv").string();
  auto r = runGhostspace({"convert", x3dv.string(), "-o", xml});
  INFO(r.err);
  REQUIRE(r.exitCode == 0);
  CHECK(r.out.find("X3D XML") != std::string::npos);
  CHECK(gs::test::readBytes(xml).find("<X3D ") != std::string::npos);
  CHECK(runGhostspace({"convert", xml, "-o", json}).exitCode == 0);
  CHECK(gs::test::readBytes(json).starts_with("{ \"X3D\": {"));
  CHECK(runGhostspace({"convert", json, "-o", classic}).exitCode == 0);
  CHECK(gs::test::readBytes(classic).starts_with("#X3D V"));
  const auto info = runGhostspace({"info", classic});
  CHECK(info.exitCode == 0);
  CHECK(info.out.find("0 errors, 0 warnings") != std::string::npos);

  // X3D as VRML97: what VRML97 lacks is a warning naming it, on stderr; exit 0.
  const std::string wrl = (dir.path / "w.wrl").string();
  const auto lossy = runGhostspace({"convert", x3dv.string(), "-o", wrl});
  CHECK(lossy.exitCode == 0);
  CHECK(lossy.err.find("warning: ") != std::string::npos);
  CHECK(lossy.err.find("no VRML97 form") != std::string::npos);
  CHECK(gs::test::readBytes(wrl).starts_with("#VRML V2.0 utf8\n"));
  CHECK(runGhostspace({"info", wrl}).exitCode == 0);

  // An OUT that names no encoding is a usage error; a missing -o too.
  const auto bad = runGhostspace({"convert", x3dv.string(), "-o", (dir.path / "w.txt").string()});
  CHECK(bad.exitCode == 2);
  CHECK(bad.err.find(".wrl, .x3dv, .x3d or .x3dj") != std::string::npos);
  CHECK(runGhostspace({"convert", x3dv.string()}).exitCode == 2);
  // An input with errors is still written, with exit status 1.
  const std::string broken =
      dir.write("broken.wrl", "#VRML V2.0 utf8\nGroup { }\nNoSuchNode { }\n");
  const auto partial = runGhostspace({"convert", broken, "-o", (dir.path / "b.x3d").string()});
  CHECK(partial.exitCode == 1);
  CHECK(partial.err.find("NoSuchNode") != std::string::npos);
  CHECK(gs::test::readBytes(dir.path / "b.x3d").find("<Group/>") != std::string::npos);
}

TEST_CASE("snapshots with the castle camera start a world without a Viewpoint as castle does",
          "[app][cli]") {
  // A 2 m white box at the origin: from VRML97's default viewpoint (0 0 10) its front face
  // spans 2 / 9 of the view's height at tan(pi / 8); from castle's camera (z = 1 + 2 * 2)
  // it spans 2 / 4 of it: about 21 and 48 of 80 pixels.
  const auto dir = std::filesystem::temp_directory_path() / "gs_castle_camera";
  std::filesystem::create_directories(dir);
  std::ofstream(dir / "box.wrl") << "#VRML V2.0 utf8\nNavigationInfo { headlight FALSE }\n"
                                    "Shape { appearance Appearance { material Material {"
                                    " emissiveColor 1 1 1 } } geometry Box { } }\n";
  const auto rows = [&](const std::vector<std::string>& extra) {
    std::vector<std::string> args = {"--snapshot", (dir / "out.png").string(), "--size", "80x80"};
    args.insert(args.end(), extra.begin(), extra.end());
    args.push_back((dir / "box.wrl").string());
    REQUIRE(runGhostspace(args).exitCode == 0);
    const gs::render::Image image = gs::render::readPng((dir / "out.png").string());
    int white = 0;
    for (int y = 0; y < image.height; ++y) white += image.pixel(40, y)[0] > 128 ? 1 : 0;
    return white;
  };
  const int vrml97 = rows({});
  const int castle = rows({"--castle-camera"});
  CHECK(std::abs(vrml97 - 21) <= 2);
  CHECK(std::abs(castle - 48) <= 2);
}
