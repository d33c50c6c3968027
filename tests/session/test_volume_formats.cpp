// The volume formats of issue 42 through the session's loader (session/volume_input.hpp),
// as the window, --snapshot and encode reach them: a DICOM series folder, a DICOMDIR, an
// OME-TIFF, a folder of TIFF slices; and a folder that holds no tileset
// index is not taken for a tileset.
#include <catch2/catch.hpp>

#include <string>

#include "formats/input_kind.hpp"
#include "session/splat_inputs.hpp"
#include "session/volume_input.hpp"
#include "session/world.hpp"
#include "test_support.hpp"

using namespace gs;

namespace {

std::string formatData(const std::string& rel) {
  return (test::sourceDir() / "tests" / "data" / rel).string();
}

}  // namespace

TEST_CASE("DICOM and TIFF inputs load as volumes and open as worlds", "[volume_formats]") {
  struct Case {
    std::string path;
    glm::uvec3 dims;
  };
  const Case cases[] = {
      {formatData("dicom/cthead/series"), {128, 128, 29}},
      {formatData("dicom/cthead/series/"), {128, 128, 29}},
      {formatData("dicom/pydicom/dicomdirtests/DICOMDIR"), {16, 16, 5}},
      {formatData("dicom/cthead/multiframe.dcm"), {64, 64, 8}},
      {formatData("tiff/cthead/cthead.ome.tif"), {128, 128, 29}},
      {formatData("tiff/cthead/slices"), {64, 64, 8}},
  };
  for (const Case& c : cases) {
    INFO(c.path);
    CHECK(formats::isVolume(formats::classifyFile(c.path)));
    CHECK(session::tilesetIndexOf(c.path).empty());
    CHECK(session::isSplatInput(c.path));
    CHECK(session::loadVolumeFile(c.path).dims == c.dims);
    const session::LoadedWorld w = session::loadWorld(c.path);
    CHECK(w.readable);
  }
}
