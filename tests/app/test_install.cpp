// `cmake --install` to a temporary prefix: the binary, the .desktop entry (validated by
// desktop-file-validate), the shared-mime-info XML (well-formed by xmllint, and compiled
// by update-mime-database into a model/x-qnv type) and the icon.
#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

int shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string quoted(const fs::path& p) {
  return "'" + p.string() + "'";
}

}  // namespace

TEST_CASE("cmake --install writes the helper-application files", "[app][install]") {
  const fs::path prefix = fs::temp_directory_path() / ("gs_install_" + std::to_string(::getpid()));
  fs::remove_all(prefix);
  REQUIRE(shell(std::string("'") + GS_CMAKE_COMMAND + "' --install " + quoted(GS_BINARY_DIR) +
                " --prefix " + quoted(prefix) + " > /dev/null") == 0);
  const fs::path bin = prefix / "bin/ghostspace";
  const fs::path desktop = prefix / "share/applications/ghostspace.desktop";
  const fs::path mime = prefix / "share/mime/packages/ghostspace-qnv.xml";
  const fs::path icon = prefix / "share/icons/hicolor/scalable/apps/ghostspace.svg";
  CHECK(fs::exists(bin));
  REQUIRE(fs::exists(desktop));
  REQUIRE(fs::exists(mime));
  CHECK(fs::exists(icon));

  const std::string entry = gs::test::readBytes(desktop);
  CHECK(entry.find("Exec=ghostspace %U") != std::string::npos);
  for (const char* type : {"model/vrml", "x-world/x-vrml", "model/x-qnv", "model/x3d+xml",
                           "model/x3d-vrml", "model/x3d+json"})
    CHECK(entry.find(type) != std::string::npos);
  // The X3D media types are defined with their extensions and magic (helper application
  // for X3D links).
  const std::string types = gs::test::readBytes(mime);
  for (const char* x3d :
       {"model/x3d+xml", "model/x3d-vrml", "model/x3d+json", "*.x3dv", "*.x3dz", "#X3D V"})
    CHECK(types.find(x3d) != std::string::npos);

  if (fs::exists("/usr/bin/desktop-file-validate"))
    CHECK(shell("desktop-file-validate " + quoted(desktop) + " > /dev/null") == 0);
  else
    gs::test::missingFixture("desktop-file-validate is absent (install desktop-file-utils)");
  if (fs::exists("/usr/bin/xmllint")) {
    CHECK(shell("xmllint --noout " + quoted(mime)) == 0);
    CHECK(shell("xmllint --noout " + quoted(icon)) == 0);
  } else {
    gs::test::missingFixture("xmllint is absent (install libxml2-utils)");
  }
  if (fs::exists("/usr/bin/update-mime-database")) {
    // The MIME database compiled from our XML knows the type, its glob and its magic.
    REQUIRE(shell("update-mime-database " + quoted(prefix / "share/mime") + " > /dev/null 2>&1") ==
            0);
    const fs::path compiled = prefix / "share/mime/model/x-qnv.xml";
    CHECK(fs::exists(compiled));
    const std::string globs = gs::test::readBytes(prefix / "share/mime/globs2");
    CHECK(globs.find("model/x-qnv:*.qnv") != std::string::npos);
    CHECK(gs::test::readBytes(prefix / "share/mime/magic").find("model/x-qnv") !=
          std::string::npos);
  } else {
    gs::test::missingFixture("update-mime-database is absent (install shared-mime-info)");
  }
  fs::remove_all(prefix);
}
