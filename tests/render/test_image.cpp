// Images: PNG round trip, decoding guards and the comparison metric. No context needed.
#include "render/image.hpp"

#include <catch2/catch.hpp>

#include "test_support.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

using gs::render::Image;

namespace {
std::filesystem::path tempPath(const std::string& name) {
  return std::filesystem::temp_directory_path() / ("gs_render_test_" + name);
}
Image gradient(int w, int h) {
  Image img(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      std::uint8_t* p = img.pixel(x, y);
      p[0] = static_cast<std::uint8_t>(x * 255 / std::max(w - 1, 1));
      p[1] = static_cast<std::uint8_t>(y * 255 / std::max(h - 1, 1));
      p[2] = static_cast<std::uint8_t>((x * 7 + y * 13) & 0xFF);
      p[3] = static_cast<std::uint8_t>(255 - x);
    }
  return img;
}
}  // namespace

TEST_CASE("PNG write then read is exact", "[render][image]") {
  const Image img = gradient(37, 23);
  const auto path = tempPath("roundtrip.png");
  gs::render::writePng(path.string(), img);
  const Image back = gs::render::readPng(path.string());
  CHECK(back.width == 37);
  CHECK(back.height == 23);
  CHECK(back.rgba == img.rgba);
  // stb_image decodes the same file to the same pixels.
  int components = 0;
  const Image decoded =
      gs::render::decodeImage(gs::test::readBytes(path), "roundtrip", &components);
  CHECK(components == 4);
  CHECK(decoded.rgba == img.rgba);
  std::filesystem::remove(path);
}

TEST_CASE("PNG errors name the file and the reason", "[render][image]") {
  const auto missing = tempPath("does_not_exist.png");
  CHECK_THROWS_WITH(gs::render::readPng(missing.string()),
                    Catch::Contains(missing.string()) && Catch::Contains("no such file"));
  const auto text = tempPath("not_a_png.png");
  std::ofstream(text) << "hello";
  CHECK_THROWS_WITH(gs::render::readPng(text.string()), Catch::Contains("not a PNG"));
  // A truncated PNG: libpng's longjmp becomes an exception.
  const auto good = tempPath("good.png");
  gs::render::writePng(good.string(), gradient(64, 64));
  const std::string bytes = gs::test::readBytes(good);
  const auto truncated = tempPath("truncated.png");
  std::ofstream(truncated, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  CHECK_THROWS_WITH(gs::render::readPng(truncated.string()), Catch::Contains(truncated.string()));
  CHECK_THROWS(gs::render::writePng("/nonexistent-dir/x.png", gradient(2, 2)));
  CHECK_THROWS(gs::render::writePng(good.string(), Image{}));
  for (const auto& p : {text, good, truncated}) std::filesystem::remove(p);
}

TEST_CASE("decodeImage rejects garbage and huge images", "[render][image]") {
  CHECK_THROWS_WITH(gs::render::decodeImage("", "empty"), Catch::Contains("empty"));
  CHECK_THROWS_WITH(gs::render::decodeImage("not an image at all", "junk"),
                    Catch::Contains("junk"));
  // A PNG header claiming 20000 x 10 pixels (no data): rejected before any allocation.
  std::string png("\x89PNG\r\n\x1a\n", 8);
  const unsigned char ihdr[] = {0, 0, 0,  13, 'I', 'H', 'D', 'R', 0, 0, 0x4e, 0x20, 0,
                                0, 0, 10, 8,  6,   0,   0,   0,   0, 0, 0,    0};
  png.append(reinterpret_cast<const char*>(ihdr), sizeof ihdr);
  CHECK_THROWS(gs::render::decodeImage(png, "huge"));
  CHECK_THROWS(gs::render::loadImageFile(tempPath("no_such_texture.png").string()));
}

TEST_CASE("compareImages: the baseline metric", "[render][image]") {
  const Image a(10, 10, 100, 100, 100);
  Image b = a;
  auto same = gs::render::compareImages(a, b);
  CHECK(same.meanAbsolute == 0.0);
  CHECK(same.fractionDiffering == 0.0);
  CHECK(std::isinf(same.psnr));
  // 10 pixels with a red difference of 40 (> 16), 10 with a difference of 10 (<= 16).
  for (int x = 0; x < 10; ++x) {
    b.pixel(x, 0)[0] = 140;
    b.pixel(x, 1)[1] = 110;
  }
  b.pixel(5, 5)[3] = 0;  // alpha is ignored
  const auto d = gs::render::compareImages(a, b, 16);
  CHECK(d.fractionDiffering == Approx(0.10));
  CHECK(d.meanAbsolute == Approx((10 * 40 + 10 * 10) / 300.0));
  CHECK(d.psnr == Approx(10 * std::log10(255.0 * 255.0 / ((10 * 1600 + 10 * 100) / 300.0))));
  CHECK(gs::render::compareImages(a, b, 50).fractionDiffering == 0.0);
  CHECK_THROWS_AS(gs::render::compareImages(a, Image(10, 11)), std::invalid_argument);
}
