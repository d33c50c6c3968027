// DDS files (render/src/dds_images.hpp): uncompressed and S3TC-compressed images, cube
// maps; ImageCubeMapTexture (X3D 4.0 clause 34.4.2) drawn as castle-model-viewer draws
// it, and bad files as warnings.
#include "../../render/src/dds_images.hpp"
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
