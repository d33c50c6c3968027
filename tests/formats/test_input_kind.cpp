// formats/input_kind.hpp: one classifier for every input, content first, then the name.
#include <catch2/catch.hpp>

#include <string>

#include "formats/input_kind.hpp"
#include "qnv/stream.hpp"
#include "qnv/tileset.hpp"
#include "test_support.hpp"

using gs::formats::classifyFile;
using gs::formats::classifyInput;
using gs::formats::InputKind;
using gs::formats::kindFromContent;
using gs::formats::kindFromName;

TEST_CASE("kindFromName: extensions in any case, URLs without query", "[formats][kind]") {
  CHECK(kindFromName("a.wrl") == InputKind::world);
  CHECK(kindFromName("a.WRL") == InputKind::world);
  CHECK(kindFromName("dir/a.Wrl") == InputKind::world);
  CHECK(kindFromName("a.wrl.gz") == InputKind::world);
  CHECK(kindFromName("a.WRZ") == InputKind::world);
  CHECK(kindFromName("http://h/a.wrl?x=1#vp") == InputKind::world);
  CHECK(kindFromName("http://h/s.QNV") == InputKind::qnv);
  CHECK(kindFromName("http://h/ct/index.qnvt") == InputKind::qnvTileset);
  CHECK(kindFromName("m.ply.GZ") == InputKind::ply);
  CHECK(kindFromName("m.obj") == InputKind::obj);
  CHECK(kindFromName("m.glb") == InputKind::gltf);
  CHECK(kindFromName("m.gltf.gz") == InputKind::gltf);
  CHECK(kindFromName("v.NHDR") == InputKind::nrrd);
  CHECK(kindFromName("v.nii.gz") == InputKind::nifti);
  for (const char* no : {"", "wrl", ".wrl", "a.gz", "a.nrrd.bz2", "a.stl", "http://h/dir/"})
    CHECK(kindFromName(no) == InputKind::unknown);
}

TEST_CASE("kindFromName: an SOG scene's meta.json by its fixed name", "[formats][kind]") {
  CHECK(kindFromName("meta.json") == InputKind::gaussianSplats);
  CHECK(kindFromName("http://h/scene/meta.json?x=1") == InputKind::gaussianSplats);
  CHECK(kindFromName("C:\\scene\\META.JSON") == InputKind::gaussianSplats);
  CHECK(kindFromName("http://h/scene/xmeta.json") == InputKind::unknown);
  CHECK(kindFromName("http://h/scene/other.json") == InputKind::unknown);
}

TEST_CASE("kindFromContent: magic bytes, also inside gzip", "[formats][kind]") {
  CHECK(kindFromContent("#VRML V2.0 utf8\nGroup {}\n") == InputKind::world);
  CHECK(kindFromContent(gs::test::gzip("#VRML V2.0 utf8\nGroup {}\n")) == InputKind::world);
  const std::string qnvMagic(gs::qnv::kMagic.begin(), gs::qnv::kMagic.end());
  CHECK(kindFromContent(qnvMagic + "rest") == InputKind::qnv);
  const std::string indexMagic(gs::qnv::kTilesetMagic.begin(), gs::qnv::kTilesetMagic.end());
  CHECK(kindFromContent(indexMagic + "rest") == InputKind::qnvTileset);
  CHECK(kindFromContent(indexMagic.substr(0, 7)) == InputKind::unknown);
  CHECK(kindFromContent("ply\nformat ascii 1.0\n") == InputKind::ply);
  CHECK(kindFromContent("ply\r\nformat ascii 1.0\n") == InputKind::ply);
  CHECK(kindFromContent(gs::test::gzip("ply\nformat ascii 1.0\n")) == InputKind::ply);
  CHECK(kindFromContent("glTF\x02\0\0\0") == InputKind::gltf);
  CHECK(kindFromContent("NRRD0004\ntype: uint8\n") == InputKind::nrrd);
  // PlayCanvas SOG's meta.json (as splat-transform writes it); a glTF's JSON is not one.
  CHECK(kindFromContent("{\"version\":2,\"asset\":{\"generator\":\"splat-transform v3.7.0\"},"
                        "\"count\":3000,\"means\":{\"mins\":[0,0,0]") == InputKind::gaussianSplats);
  CHECK(kindFromContent("{\"asset\":{\"version\":\"2.0\"},\"scene\":0}") == InputKind::unknown);
  std::string nifti(352, '\0');
  nifti.replace(344, 4, std::string("n+1\0", 4));
  CHECK(kindFromContent(nifti) == InputKind::nifti);
  CHECK(kindFromContent(gs::test::gzip(nifti)) == InputKind::nifti);
  for (const std::string no : {"", "plywood", "#VRML V1.0 ascii", "NRRD0009", "hello"})
    CHECK(kindFromContent(no) == InputKind::unknown);
  CHECK(kindFromContent(gs::test::gzip("hello")) == InputKind::unknown);
  CHECK(kindFromContent(std::string("\x1f\x8b", 2)) == InputKind::unknown);  // cut gzip
}

TEST_CASE("classify: content wins over a missing or lying extension", "[formats][kind]") {
  CHECK(classifyInput("bunny", "ply\nformat ascii 1.0\n") == InputKind::ply);
  CHECK(classifyInput("world.qnv", "#VRML V2.0 utf8\n") == InputKind::world);
  CHECK(classifyInput("mesh.obj", "v 0 0 0\n") == InputKind::obj);  // no magic: the name
  gs::test::TempDir dir("kind");
  CHECK(classifyFile(dir.write("noext", "#VRML V2.0 utf8\n")) == InputKind::world);
  CHECK(classifyFile(dir.write("head", "NRRD0005\ntype: uint8\n")) == InputKind::nrrd);
  CHECK(classifyFile(dir.write("x.Wrl", "")) == InputKind::world);
  CHECK(classifyFile((dir.path / "missing.ply").string()) == InputKind::ply);
  CHECK(classifyFile((dir.path / "missing").string()) == InputKind::unknown);
}

TEST_CASE("the open dialog lists every kind of file the program opens", "[formats][kind]") {
  // Issue 42, friction 6: it listed worlds only and hid the streams, meshes and volumes.
  for (const char* name :
       {"w.wrl", "w.x3d", "w.x3dv", "w.x3dj", "w.x3dvz", "head.qnv", "index.qnvt", "bunny.ply",
        "m.obj", "a.glb", "a.gltf", "ct.nhdr", "ct.nrrd", "brain.nii", "brain.nii.gz", "s.spz",
        "s.sog", "s.splat", "s.compressed.ply"})
    CHECK(gs::formats::isOpenableName(name));
  for (const char* name : {"notes.txt", "landscape.stl", "photo.jpg", "Makefile"})
    CHECK_FALSE(gs::formats::isOpenableName(name));
}
