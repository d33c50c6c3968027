// Issue 12: images (GIF through giflib, grey and alpha PNGs as ISO/IEC 14772-1 4.14 /
// table 4.6 says), Background colours and panoramas (6.5), and exact bounds of rotated
// shapes. Worlds are written at test time and rendered off-screen at 64x64.
#include "encodings/parser.hpp"
#include "render/context.hpp"
#include "render/image.hpp"
#include "render/scene_renderer.hpp"

#include <catch2/catch.hpp>

#include <gif_lib.h>

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wshadow"
#pragma GCC diagnostic ignored "-Wcast-align"
#pragma GCC diagnostic ignored "-Wnull-dereference"
#pragma GCC diagnostic ignored "-Wunused-function"
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wimplicit-fallthrough"
#pragma GCC diagnostic ignored "-Wconversion"
#pragma GCC diagnostic ignored "-Wsign-conversion"
#pragma GCC diagnostic ignored "-Wdouble-promotion"
#if !defined(__clang__)
#pragma GCC diagnostic ignored "-Wuseless-cast"
#endif
#pragma GCC diagnostic ignored "-Wold-style-cast"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STBI_WRITE_NO_STDIO
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using gs::render::Image;

namespace {

constexpr int kSize = 64;

fs::path dir() {
  const fs::path d = fs::temp_directory_path() / "gs_render_media";
  fs::create_directories(d);
  return d;
}

void writeBytes(const fs::path& p, const std::string& bytes) {
  std::ofstream(p, std::ios::binary) << bytes;
}

void appendBytes(void* context, void* data, int size) {
  static_cast<std::string*>(context)->append(static_cast<const char*>(data),
                                             static_cast<std::size_t>(size));
}

/// A PNG of `components` channels (1 grey, 2 grey+alpha, 3 RGB, 4 RGBA) from stb_image_write.
std::string pngBytes(int w, int h, int components, const std::vector<std::uint8_t>& pixels) {
  std::string out;
  REQUIRE(stbi_write_png_to_func(appendBytes, &out, w, h, components, pixels.data(),
                                 w * components) != 0);
  return out;
}

std::string jpegBytes(int w, int h, int components, const std::vector<std::uint8_t>& pixels) {
  std::string out;
  REQUIRE(stbi_write_jpg_to_func(appendBytes, &out, w, h, components, pixels.data(), 95) != 0);
  return out;
}

int gifWrite(GifFileType* gif, const GifByteType* data, int size) {
  static_cast<std::string*>(gif->UserData)
      ->append(reinterpret_cast<const char*>(data), static_cast<std::size_t>(size));
  return size;
}

/// A GIF89a of w x h palette indices (0 red, 1 green, 2 blue, 3 white), index
/// `transparent` (or -1) transparent, written with giflib.
std::string gifBytes(int w, int h, const std::vector<GifPixelType>& indices, int transparent,
                     bool interlace = false) {
  std::string out;
  int error = 0;
  GifFileType* gif = EGifOpen(&out, gifWrite, &error);
  REQUIRE(gif != nullptr);
  GifColorType colors[4] = {{255, 0, 0}, {0, 255, 0}, {0, 0, 255}, {255, 255, 255}};
  ColorMapObject* map = GifMakeMapObject(4, colors);
  EGifSetGifVersion(gif, true);
  REQUIRE(EGifPutScreenDesc(gif, w, h, 2, 0, map) == GIF_OK);
  GraphicsControlBlock gcb{};
  gcb.DisposalMode = DISPOSAL_UNSPECIFIED;
  gcb.TransparentColor = transparent;
  GifByteType ext[4];
  const std::size_t extLength = EGifGCBToExtension(&gcb, ext);
  REQUIRE(EGifPutExtension(gif, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(extLength), ext) ==
          GIF_OK);
  REQUIRE(EGifPutImageDesc(gif, 0, 0, w, h, interlace, nullptr) == GIF_OK);
  std::vector<GifPixelType> row(static_cast<std::size_t>(w));
  // Interlaced files carry rows in the four-pass order.
  std::vector<int> order;
  if (interlace) {
    constexpr int kStart[4] = {0, 4, 2, 1}, kStep[4] = {8, 8, 4, 2};
    for (int pass = 0; pass < 4; ++pass)
      for (int y = kStart[pass]; y < h; y += kStep[pass]) order.push_back(y);
  } else {
    for (int y = 0; y < h; ++y) order.push_back(y);
  }
  for (int y : order) {
    std::copy_n(indices.begin() + static_cast<std::ptrdiff_t>(y) * w, w, row.begin());
    REQUIRE(EGifPutLine(gif, row.data(), w) == GIF_OK);
  }
  REQUIRE(EGifCloseFile(gif, &error) == GIF_OK);
  GifFreeMapObject(map);
  return out;
}

Image render(const std::string& name, const std::string& world,
             gs::vrml::Diagnostics* diagnostics = nullptr) {
  static auto context = gs::render::createOffscreenContext(kSize, kSize);
  context->makeCurrent();
  const fs::path file = dir() / name;
  writeBytes(file, world);
  auto scene = std::make_shared<gs::vrml::Scene>(gs::vrml::loadVrmlFile(file.string()));
  for (const auto& d : scene->diagnostics.items) WARN(d.format());
  gs::render::SceneRenderer r(scene);
  r.draw(r.initialCamera(1.0f), 0, 0, kSize, kSize);
  if (diagnostics != nullptr) *diagnostics = r.diagnostics();
  return gs::render::readPixels(0, 0, kSize, kSize);
}

bool close(const std::uint8_t* p, int r, int g, int b, int tolerance = 6) {
  INFO("pixel " << int(p[0]) << " " << int(p[1]) << " " << int(p[2]) << ", expected " << r << " "
                << g << " " << b);
  return std::abs(p[0] - r) <= tolerance && std::abs(p[1] - g) <= tolerance &&
         std::abs(p[2] - b) <= tolerance;
}

/// An unlit quad filling the view, coloured by a Color node (red), textured with `url`.
std::string texturedQuad(const std::string& url, const std::string& sky = "0 0 1") {
  return R"(#VRML V2.0 utf8
Background { skyColor )" +
         sky + R"( }
Viewpoint { position 0 0 2 fieldOfView 1.5 }
Shape {
  appearance Appearance { texture ImageTexture { url ")" +
         url + R"(" } }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -1 -1 0, 1 -1 0, 1 1 0, -1 1 0 ] }
    coordIndex [ 0 1 2 3 ]
    color Color { color [ 1 0 0 ] } colorPerVertex FALSE
    texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0 1 ] }
  }
}
)";
}

}  // namespace

TEST_CASE("a GIF decodes through giflib with its transparent index", "[render][image][gif]") {
  // 4 x 2: red green blue white / white transparent(green) red red.
  const std::vector<GifPixelType> indices = {0, 1, 2, 3, 3, 1, 0, 0};
  for (bool interlace : {false, true}) {
    INFO("interlace " << interlace);
    int components = 0;
    const Image image =
        gs::render::decodeImage(gifBytes(4, 2, indices, 1, interlace), "t.gif", &components);
    REQUIRE(image.width == 4);
    REQUIRE(image.height == 2);
    CHECK(components == 4);
    const std::uint8_t* p = image.pixel(0, 0);
    CHECK((p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255));
    CHECK(image.pixel(1, 0)[3] == 0);  // index 1 is transparent everywhere
    CHECK(image.pixel(1, 1)[3] == 0);
    p = image.pixel(2, 0);
    CHECK((p[0] == 0 && p[1] == 0 && p[2] == 255 && p[3] == 255));
    p = image.pixel(3, 1);
    CHECK((p[0] == 255 && p[1] == 0 && p[2] == 0 && p[3] == 255));
  }
  int components = 0;
  const Image opaque = gs::render::decodeImage(gifBytes(4, 2, indices, -1), "o.gif", &components);
  CHECK(components == 3);
  CHECK(opaque.pixel(1, 1)[3] == 255);
  CHECK(opaque.pixel(1, 1)[1] == 255);
}

TEST_CASE("truncated and corrupt GIFs are errors naming the data, never crashes",
          "[render][image][gif]") {
  const std::string whole = gifBytes(4, 2, {0, 1, 2, 3, 3, 1, 0, 0}, 1);
  for (std::size_t n = 6; n < whole.size() - 1; ++n) {
    INFO("length " << n);
    CHECK_THROWS_WITH(gs::render::decodeImage(whole.substr(0, n), "cut.gif"),
                      Catch::Contains("cut.gif"));
  }
  std::string huge = whole;
  huge[6] = huge[7] = '\xff';  // logical screen 65535 wide
  CHECK_THROWS_WITH(gs::render::decodeImage(huge, "huge.gif"), Catch::Contains("limit"));
}

TEST_CASE("PNG and JPEG report their components", "[render][image]") {
  const std::vector<std::uint8_t> grey = {0, 128, 255, 64};
  int components = 0;
  Image g = gs::render::decodeImage(pngBytes(2, 2, 1, grey), "g.png", &components);
  CHECK(components == 1);
  CHECK((g.pixel(1, 0)[0] == 128 && g.pixel(1, 0)[1] == 128 && g.pixel(1, 0)[3] == 255));
  const std::vector<std::uint8_t> greyAlpha = {10, 0, 20, 255, 30, 128, 40, 255};
  g = gs::render::decodeImage(pngBytes(2, 2, 2, greyAlpha), "ga.png", &components);
  CHECK(components == 2);
  CHECK(g.pixel(0, 0)[3] == 0);
  CHECK(g.pixel(0, 1)[3] == 128);
  const std::vector<std::uint8_t> rgb(2 * 2 * 3, 200);
  g = gs::render::decodeImage(jpegBytes(2, 2, 3, rgb), "c.jpg", &components);
  CHECK(components == 3);
  CHECK(std::abs(g.pixel(1, 1)[0] - 200) <= 3);
}

TEST_CASE("texture components follow table 4.6: intensity modulates, RGB replaces",
          "[render][offscreen][image]") {
  const fs::path d = dir();
  // 1 component: intensity 128 times the Color red = (128, 0, 0).
  writeBytes(d / "grey.png", pngBytes(1, 1, 1, {128}));
  Image img = render("grey.wrl", texturedQuad("grey.png"));
  CHECK(close(img.pixel(32, 32), 128, 0, 0));
  // 2 components: intensity 255, alpha 128: red blended half over the blue sky.
  writeBytes(d / "grey_alpha.png", pngBytes(1, 1, 2, {255, 128}));
  img = render("grey_alpha.wrl", texturedQuad("grey_alpha.png"));
  CHECK(close(img.pixel(32, 32), 128, 0, 127));
  // 3 components: the texture's colour replaces the Color.
  writeBytes(d / "green.jpg", jpegBytes(1, 1, 3, {0, 255, 0}));
  img = render("rgb.wrl", texturedQuad("green.jpg"));
  CHECK(close(img.pixel(32, 32), 0, 255, 0));
  // 4 components: colour and alpha.
  writeBytes(d / "rgba.png", pngBytes(1, 1, 4, {0, 255, 0, 64}));
  img = render("rgba.wrl", texturedQuad("rgba.png"));
  CHECK(close(img.pixel(32, 32), 0, 64, 191));
  // GIF: a transparent texel shows the sky behind, an opaque one its colour (left half
  // blue, right half transparent; pixels 25 and 39 are at s = 0.3 and 0.7).
  writeBytes(d / "half.gif", gifBytes(8, 1, {2, 2, 2, 2, 1, 1, 1, 1}, 1));
  img = render("gif.wrl", texturedQuad("half.gif", "1 1 0"));
  CHECK(close(img.pixel(25, 32), 0, 0, 255));
  CHECK(close(img.pixel(39, 32), 255, 255, 0));
}

TEST_CASE("Background panorama: faces where clause 6.5 puts them, alpha shows the sky",
          "[render][offscreen][background]") {
  const fs::path d = dir();
  // Left half opaque red, right half transparent.
  writeBytes(d / "half_red.png", pngBytes(2, 1, 4, {255, 0, 0, 255, 0, 0, 0, 0}));
  writeBytes(d / "green.png", pngBytes(1, 1, 3, {0, 255, 0}));
  const std::string viewpoint = "Viewpoint { position 0 0 0 fieldOfView 1.5707963 }\n";
  // Looking down -Z: the front face; its right half shows the sky colour.
  Image img = render("front.wrl",
                     "#VRML V2.0 utf8\nBackground { skyColor 0 0 1 "
                     "frontUrl \"half_red.png\" backUrl \"green.png\" }\n" +
                         viewpoint);
  CHECK(close(img.pixel(10, 32), 255, 0, 0));
  CHECK(close(img.pixel(54, 32), 0, 0, 255));
  // Turned around (looking down +Z): the back face.
  img = render("back.wrl",
               "#VRML V2.0 utf8\nBackground { frontUrl \"half_red.png\" backUrl \"green.png\" }\n"
               "Viewpoint { position 0 0 0 fieldOfView 1.5 orientation 0 1 0 3.14159265 }\n");
  CHECK(close(img.pixel(32, 32), 0, 255, 0));
  // The viewer's translation does not move the panorama; a rotated Background does: turned
  // by 90 degrees about Y its right face (+X) lies along world -Z.
  img = render("rotated.wrl",
               "#VRML V2.0 utf8\nTransform { rotation 0 1 0 1.5707963 children Background {"
               " rightUrl \"green.png\" frontUrl \"half_red.png\" } }\n"
               "Viewpoint { position 100 50 -20 fieldOfView 1.5 }\n");
  CHECK(close(img.pixel(32, 32), 0, 255, 0));
  // A missing image is reported and the colours show.
  gs::vrml::Diagnostics diagnostics;
  img =
      render("missing.wrl",
             "#VRML V2.0 utf8\nBackground { skyColor 1 1 0 topUrl \"nowhere.png\" }\n" + viewpoint,
             &diagnostics);
  CHECK(close(img.pixel(32, 32), 255, 255, 0));
  REQUIRE(diagnostics.items.size() == 1);
  CHECK(diagnostics.items[0].message.find("topUrl") != std::string::npos);
  CHECK(diagnostics.items[0].message.find("nowhere.png") != std::string::npos);
}

TEST_CASE("Background bands: skyAngle and groundAngle colours per clause 6.5",
          "[render][offscreen][background]") {
  // Looking straight along the horizon with a 90 degree view: the centre row is at 90
  // degrees from the zenith, the top row at 45, the bottom row at 135 (45 from the nadir).
  const Image img = render("bands.wrl", R"(#VRML V2.0 utf8
Background {
  skyColor [ 1 0 0, 0 1 0, 0 0 1 ] skyAngle [ 0.7853982, 1.5707963 ]
  groundColor [ 1 1 0, 1 1 1 ] groundAngle [ 1.0 ]
}
Viewpoint { position 0 0 0 fieldOfView 1.5707963 }
)");
  // Top centre: 45 degrees from the zenith = skyAngle[0]: exactly green.
  CHECK(close(img.pixel(32, 0), 0, 255, 0, 12));
  // Just above the horizon: blue (skyAngle[1] = 90 degrees).
  CHECK(close(img.pixel(32, 30), 0, 20, 235, 24));
  // Bottom centre: 45 degrees from the nadir, below groundAngle 1.0 (57 degrees): between
  // yellow (nadir) and white (57 degrees), 45/57 of the way.
  CHECK(close(img.pixel(32, 63), 255, 255, 201, 14));
  // Just below the horizon: beyond the last groundAngle the ground is transparent and
  // the sky's last colour shows (blue).
  CHECK(close(img.pixel(32, 34), 0, 0, 255, 24));
}

TEST_CASE("bounds of rotated shapes come from their points, not their boxes",
          "[render][traversal][bounds]") {
  // A unit sphere rotated 45 degrees: its box is still about [-1, 1]^3 (the corners of the
  // rotated box would reach sqrt(2) = 1.414).
  auto sphere = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#VRML V2.0 utf8\nTransform { rotation 0 1 0 0.7853982 children Shape { geometry "
      "Sphere { } } }\n",
      "/tmp/sphere.wrl"));
  gs::scene::SceneTraversal t(sphere);
  const gs::vrml::Bounds b = t.worldBounds();
  CHECK(b.max.x == Approx(1.0f).epsilon(0.01));
  CHECK(b.min.z == Approx(-1.0f).epsilon(0.01));
  CHECK(b.max.y == Approx(1.0f).epsilon(0.01));
  // A 2 x 2 x 2 Box turned 45 degrees about Y: x and z reach sqrt(2), y stays 1 (by hand).
  auto box = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#VRML V2.0 utf8\nTransform { rotation 0 1 0 0.7853982 translation 5 0 0 children Shape {"
      " geometry Box { } } }\n",
      "/tmp/box.wrl"));
  gs::scene::SceneTraversal u(box);
  const gs::vrml::Bounds c = u.worldBounds();
  CHECK(c.max.x == Approx(5.0f + std::sqrt(2.0f)).epsilon(1e-4));
  CHECK(c.min.x == Approx(5.0f - std::sqrt(2.0f)).epsilon(1e-4));
  CHECK(c.max.z == Approx(std::sqrt(2.0f)).epsilon(1e-4));
  CHECK(c.max.y == Approx(1.0f).epsilon(1e-4));
  // Rotated twice by 45 degrees (90 in all) the Box's corners are exact again: [-1, 1].
  auto twice = std::make_shared<gs::vrml::Scene>(gs::vrml::parseVrml(
      "#VRML V2.0 utf8\nTransform { rotation 0 1 0 0.7853982 children Transform { rotation 0 1 "
      "0 0.7853982 children Shape { geometry Box { size 2 4 6 } } } }\n",
      "/tmp/twice.wrl"));
  gs::scene::SceneTraversal v(twice);
  CHECK(v.worldBounds().max.x == Approx(3.0f).epsilon(1e-4));
  CHECK(v.worldBounds().max.z == Approx(1.0f).epsilon(1e-4));
}

namespace {

/// An unlit quad filling the view, as texturedQuad draws it, whose texture node is
/// `texture` (a PROTO body's text).
std::string protoQuad(const std::string& texture) {
  return R"(Shape {
  appearance Appearance { texture )" +
         texture + R"( }
  geometry IndexedFaceSet {
    coord Coordinate { point [ -1 -1 0, 1 -1 0, 1 1 0, -1 1 0 ] }
    coordIndex [ 0 1 2 3 ]
    color Color { color [ 1 0 0 ] } colorPerVertex FALSE
    texCoord TextureCoordinate { point [ 0 0, 1 0, 1 1, 0 1 ] }
  }
})";
}

}  // namespace

TEST_CASE("a url in an EXTERNPROTO's body resolves against the PROTO's file",
          "[render][offscreen][image][proto]") {
  // tex.png is green beside the PROTOs (extern_sub/) and blue beside the world: a node
  // written in extern_sub/protos.wrl finds the green one, also when its url came through
  // IS from the world; a texture node written in the world (an SFNode value) the blue one.
  const fs::path d = dir();
  fs::create_directories(d / "extern_sub");
  writeBytes(d / "extern_sub" / "tex.png", pngBytes(1, 1, 3, {0, 255, 0}));
  writeBytes(d / "tex.png", pngBytes(1, 1, 3, {0, 0, 255}));
  writeBytes(d / "extern_sub" / "protos.wrl",
             "#VRML V2.0 utf8\nPROTO Body [] { " + protoQuad("ImageTexture { url \"tex.png\" }") +
                 " }\nPROTO ByIs [ field MFString u [] ] { " +
                 protoQuad("ImageTexture { url IS u }") +
                 " }\nPROTO ByNode [ field SFNode t NULL ] { " + protoQuad("IS t") + " }\n");
  const std::string head = R"(#VRML V2.0 utf8
EXTERNPROTO Body [] "extern_sub/protos.wrl#Body"
EXTERNPROTO ByIs [ field MFString u ] "extern_sub/protos.wrl#ByIs"
EXTERNPROTO ByNode [ field SFNode t ] "extern_sub/protos.wrl#ByNode"
Background { skyColor 1 1 0 }
Viewpoint { position 0 0 2 fieldOfView 1.5 }
)";
  gs::vrml::Diagnostics diagnostics;
  Image img = render("extern_body.wrl", head + "Body {}\n", &diagnostics);
  CHECK(diagnostics.items.empty());
  CHECK(close(img.pixel(32, 32), 0, 255, 0));
  img = render("extern_is.wrl", head + "ByIs { u \"tex.png\" }\n", &diagnostics);
  CHECK(diagnostics.items.empty());
  CHECK(close(img.pixel(32, 32), 0, 255, 0));
  img = render("extern_node.wrl", head + "ByNode { t ImageTexture { url \"tex.png\" } }\n",
               &diagnostics);
  CHECK(diagnostics.items.empty());
  CHECK(close(img.pixel(32, 32), 0, 0, 255));
}
