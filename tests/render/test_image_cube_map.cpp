// DDS files (render/src/dds_images.hpp): uncompressed and S3TC-compressed images, cube
// maps; ImageCubeMapTexture (X3D 4.0 clause 34.4.2) drawn as castle-model-viewer draws
// it, and bad files as warnings.
#include "../../render/src/dds_images.hpp"
#include "../../render/src/environment_maps.hpp"
#include "test_support.hpp"
#include "world_files.hpp"

#include <catch2/catch.hpp>

#include <array>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;
using gs::render::detail::DdsImages;
using gs::render::detail::decodeDdsImages;
using gs::test::close;
using gs::test::Rendered;
using gs::test::renderFile;
using gs::test::worldDir;
using gs::test::writeText;

namespace {

void put32(std::string& b, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) b[at + static_cast<std::size_t>(i)] = static_cast<char>(v >> (8 * i));
}

/// A DDS header for `width` x `height`: uncompressed 32-bit BGRA, or the FourCC `fourCC`;
/// `caps2` 0x200 | 0xFC00 for a cube map with all faces.
std::string ddsHeader(int width, int height, std::uint32_t caps2, const char* fourCC = nullptr) {
  std::string b(128, '\0');
  b.replace(0, 4, "DDS ");
  put32(b, 4, 124);
  put32(b, 8, 0x1007);
  put32(b, 12, static_cast<std::uint32_t>(height));
  put32(b, 16, static_cast<std::uint32_t>(width));
  put32(b, 28, 1);
  put32(b, 76, 32);
  if (fourCC != nullptr) {
    put32(b, 80, 0x4);
    b.replace(84, 4, fourCC);
  } else {
    put32(b, 80, 0x41);
    put32(b, 88, 32);
    put32(b, 92, 0x00FF0000);
    put32(b, 96, 0x0000FF00);
    put32(b, 100, 0x000000FF);
    put32(b, 104, 0xFF000000);
  }
  put32(b, 108, 0x1008);
  put32(b, 112, caps2);
  return b;
}

/// The six face colours of the test cube map (RGB), in DDS order +X, -X, +Y, -Y, +Z, -Z.
constexpr std::array<std::uint32_t, 6> kFaceRgb = {0xFF0000, 0x00FFFF, 0x00FF00,
                                                   0xFF00FF, 0x0000FF, 0xFFFF00};

/// A 2x2 uncompressed cube map, each face one colour of kFaceRgb.
std::string cubeDds() {
  std::string b = ddsHeader(2, 2, 0x200 | 0xFC00);
  for (std::uint32_t rgb : kFaceRgb)
    for (int i = 0; i < 4; ++i) {
      const std::uint32_t bgra = 0xFF000000u | rgb;  // bytes B, G, R, A
      std::string texel(4, '\0');
      put32(texel, 0, bgra);
      b += texel;
    }
  return b;
}

}  // namespace

TEST_CASE("DDS: an uncompressed cube map gives its six faces in DDS order", "[render][dds]") {
  const DdsImages d = decodeDdsImages(cubeDds(), "cube.dds");
  REQUIRE(d.cube());
  CHECK(d.faces == 63u);
  CHECK(d.width == 2);
  CHECK(d.height == 2);
  CHECK(d.components == 4);
  REQUIRE(d.rgba.size() == 6u * 2 * 2 * 4);
  for (std::size_t f = 0; f < 6; ++f) {
    const std::uint8_t* t = d.rgba.data() + f * 16;
    CHECK(t[0] == ((kFaceRgb[f] >> 16) & 0xFF));
    CHECK(t[1] == ((kFaceRgb[f] >> 8) & 0xFF));
    CHECK(t[2] == (kFaceRgb[f] & 0xFF));
    CHECK(t[3] == 255);
  }
}

TEST_CASE("DDS: DXT1 and DXT5 blocks decode to their interpolated colours and alphas",
          "[render][dds]") {
  // One 4x4 DXT1 block: colour0 red (0xF800), colour1 blue (0x001F); colour0 > colour1,
  // so index 2 is 2/3 red + 1/3 blue = (170, 0, 85), index 3 is (85, 0, 170). Texel i
  // takes index (bits >> 2i) & 3: texels 0..3 take 0, 1, 2, 3, the rest 0.
  std::string dxt1 = ddsHeader(4, 4, 0, "DXT1");
  dxt1 += std::string("\x00\xF8\x1F\x00", 4);
  dxt1 += std::string("\xE4\x00\x00\x00", 4);  // 0b11100100: indices 0, 1, 2, 3
  const DdsImages a = decodeDdsImages(dxt1, "a.dds");
  REQUIRE(a.rgba.size() == 4u * 4 * 4);
  CHECK(a.components == 3);
  const auto texel = [](const DdsImages& d, int i) {
    const std::uint8_t* t = d.rgba.data() + 4 * i;
    return std::array<int, 4>{t[0], t[1], t[2], t[3]};
  };
  CHECK(texel(a, 0) == std::array<int, 4>{255, 0, 0, 255});
  CHECK(texel(a, 1) == std::array<int, 4>{0, 0, 255, 255});
  CHECK(texel(a, 2) == std::array<int, 4>{170, 0, 85, 255});
  CHECK(texel(a, 3) == std::array<int, 4>{85, 0, 170, 255});
  CHECK(texel(a, 15) == std::array<int, 4>{255, 0, 0, 255});

  // DXT5: alpha0 200, alpha1 100 (> : seven steps), texel 0 index 0 (200), texel 1 index 1
  // (100), texel 2 index 2 ((6 * 200 + 1 * 100 + 3) / 7 = 186); colours as above.
  std::string dxt5 = ddsHeader(4, 4, 0, "DXT5");
  dxt5 += std::string("\xC8\x64", 2);
  dxt5 += std::string("\x88\x00\x00\x00\x00\x00", 6);  // 3-bit indices 0, 1, 2, 0, ...
  dxt5 += std::string("\x00\xF8\x1F\x00\xE4\x00\x00\x00", 8);
  const DdsImages b = decodeDdsImages(dxt5, "b.dds");
  CHECK(b.components == 4);
  CHECK(texel(b, 0)[3] == 200);
  CHECK(texel(b, 1)[3] == 100);
  CHECK(texel(b, 2)[3] == 186);
  CHECK(texel(b, 2)[0] == 170);
}

TEST_CASE("DDS: what is not read throws with the file's name and the reason", "[render][dds]") {
  const auto message = [](const std::string& bytes) {
    try {
      decodeDdsImages(bytes, "x.dds");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  CHECK(message("DDS nonsense") == "x.dds: not a DDS file");
  CHECK(message(ddsHeader(4, 4, 0, "DX10")).find("DDS format 'DX10' is not read") !=
        std::string::npos);
  CHECK(message(ddsHeader(0, 4, 0)) == "x.dds: DDS size out of range");
  CHECK(message(ddsHeader(1 << 16, 1 << 16, 0)) == "x.dds: DDS size out of range");
  CHECK(message(ddsHeader(4, 4, 0)) == "x.dds: DDS data shorter than its size says");
  std::string cut = cubeDds();
  cut.resize(cut.size() - 1);
  CHECK(message(cut) == "x.dds: DDS data shorter than its size says");
}

TEST_CASE(
    "ImageCubeMapTexture draws a DDS cube map as castle-model-viewer does; a file that "
    "is no cube map is a warning",
    "[render][offscreen][world][dds]") {
  const fs::path dir = worldDir();
  {
    std::ofstream out(dir / "cube.dds", std::ios::binary);
    out << cubeDds();
  }
  // As in the ComposedCubeMapTexture case of test_texture_generation: the viewer looks
  // along world -X at a quad facing it, whose world-space reflection at the centre is +X;
  // castle-model-viewer shows a DDS cube map's face +X there (docs/x3d.md, "CubeMapTexturing").
  const auto world = [](const std::string& url) {
    return R"(#X3D V3.2 utf8
PROFILE Interchange
COMPONENT CubeMapTexturing:2
NavigationInfo { headlight FALSE }
Viewpoint { position 0 0 0 orientation 0 1 0 1.5708 fieldOfView 1.5708 }
Transform { rotation 0 1 0 1.5708 children Transform { translation 0 0 -1 children Shape {
  appearance Appearance { texture ImageCubeMapTexture { url ")" +
           url + R"(" } }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] } } } }
)";
  };
  writeText(dir / "image_cube.x3dv", world("cube.dds"));
  const Rendered drawn = renderFile(dir / "image_cube.x3dv");
  CHECK(drawn.diagnostics.items.empty());
  const auto p = drawn.image.pixel(32, 32);
  INFO(int(p[0]) << " " << int(p[1]) << " " << int(p[2]));
  CHECK(close(p, 255, 0, 0, 8));  // DDS face +X

  writeText(dir / "not_cube.dds", ddsHeader(1, 1, 0) + std::string(4, '\x7F'));
  writeText(dir / "image_cube_bad.x3dv", world("not_cube.dds"));
  const Rendered bad = renderFile(dir / "image_cube_bad.x3dv");
  REQUIRE(bad.diagnostics.items.size() == 1);
  CHECK(bad.diagnostics.items[0].message.find("a DDS file but no cube map") != std::string::npos);
  CHECK(close(bad.image.pixel(32, 32), 255, 255, 255, 4));  // untextured, unlit white
}

namespace {

/// A 64 x 32 panorama: grey, with columns of red at its centre, green at 3/4 of its width
/// and blue at 1/4, and a white top.
gs::render::Image testPanorama() {
  gs::render::Image pano(64, 32, 128, 128, 128);
  for (int y = 0; y < 32; ++y)
    for (int x = 0; x < 64; ++x) {
      std::uint8_t* p = pano.pixel(x, y);
      const auto paint = [&](std::uint8_t r, std::uint8_t g, std::uint8_t b) {
        p[0] = r;
        p[1] = g;
        p[2] = b;
      };
      if (y < 4)
        paint(255, 255, 255);
      else if (x >= 28 && x < 36)
        paint(255, 0, 0);
      else if (x >= 44 && x < 52)
        paint(0, 255, 0);
      else if (x >= 12 && x < 20)
        paint(0, 0, 255);
    }
  return pano;
}

}  // namespace

TEST_CASE("ImageCubeMapTexture: a 2:1 panorama and a 4:3 cross give the six X3D faces",
          "[render][dds]") {
  using gs::render::detail::cubeFacesOfImage;
  // Faces in resampleCubeFaces' order: back (+Z), bottom, front (-Z), left (-X), right
  // (+X), top. X_ITE puts the panorama's centre at +Z, +X at 3/4 of its width.
  const std::vector<gs::render::Image> faces = cubeFacesOfImage(testPanorama());
  REQUIRE(faces.size() == 6);
  for (const auto& f : faces) CHECK(f.width == 16);
  CHECK(close(faces[0].pixel(8, 8), 255, 0, 0, 8));      // back: the centre column
  CHECK(close(faces[4].pixel(8, 8), 0, 255, 0, 8));      // right: 3/4
  CHECK(close(faces[3].pixel(8, 8), 0, 0, 255, 8));      // left: 1/4
  CHECK(close(faces[2].pixel(8, 8), 128, 128, 128, 8));  // front: the seam, grey
  CHECK(close(faces[5].pixel(8, 8), 255, 255, 255, 8));  // top: the top rows
  CHECK(close(faces[0].pixel(8, 0), 255, 0, 0,
              8));  // back's top edge: 45 degrees up, below the white

  // The cross: each cell of an 8 x 6 image its own colour.
  gs::render::Image cross(8, 6);
  for (int y = 0; y < 6; ++y)
    for (int x = 0; x < 8; ++x) {
      std::uint8_t* p = cross.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(40 * (x / 2));
      p[1] = static_cast<std::uint8_t>(80 * (y / 2));
      p[2] = 7;
    }
  const std::vector<gs::render::Image> cells = cubeFacesOfImage(cross);
  REQUIRE(cells.size() == 6);
  const std::array<std::array<int, 2>, 6> where = {
      {{3, 1}, {1, 2}, {1, 1}, {0, 1}, {2, 1}, {1, 0}}};
  for (std::size_t f = 0; f < 6; ++f) {
    INFO("face " << f);
    CHECK(cells[f].width == 2);
    CHECK(close(cells[f].pixel(1, 1), 40 * where[f][0], 80 * where[f][1], 7, 0));
  }
  CHECK(cubeFacesOfImage(gs::render::Image(30, 20)).empty());  // 3:2: no cube map
}

TEST_CASE(
    "ImageCubeMapTexture: a panorama PNG on a shape, read at its TextureCoordinate3D as "
    "X_ITE reads it",
    "[render][offscreen][world][dds]") {
  const fs::path dir = worldDir();
  gs::render::writePng((dir / "panorama.png").string(), testPanorama());
  // The viewer looks at a quad whose four texture coordinates all point one way.
  const auto world = [](const char* direction) {
    return std::string(R"(#X3D V4.0 utf8
PROFILE Interchange
COMPONENT CubeMapTexturing:2
COMPONENT Texturing3D:2
Viewpoint { position 0 0 2 }
Shape {
  appearance Appearance { texture ImageCubeMapTexture { url "panorama.png" } }
  geometry IndexedFaceSet { coord Coordinate { point [-1 -1 0, 1 -1 0, 1 1 0, -1 1 0] }
    coordIndex [0 1 2 3 -1] texCoord TextureCoordinate3D { point [ )") +
           direction + " " + direction + " " + direction + " " + direction + " ] } } }\n";
  };
  writeText(dir / "panorama_z.x3dv", world("0 0 1,"));
  writeText(dir / "panorama_x.x3dv", world("1 0 0,"));
  const Rendered z = renderFile(dir / "panorama_z.x3dv");
  const Rendered x = renderFile(dir / "panorama_x.x3dv");
  CHECK(z.diagnostics.items.empty());
  CHECK(x.diagnostics.items.empty());
  const auto pz = z.image.pixel(32, 32), px = x.image.pixel(32, 32);
  INFO(int(pz[0]) << " " << int(pz[1]) << " " << int(pz[2]) << " / " << int(px[0]) << " "
                  << int(px[1]) << " " << int(px[2]));
  CHECK(close(pz, 255, 0, 0, 12));  // +Z: the panorama's centre
  CHECK(close(px, 0, 255, 0, 12));  // +X: 3/4 of its width
}
