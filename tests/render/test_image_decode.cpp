// render::decodeImage on JPEG through libjpeg-turbo, and the inputs that fuzz_image found
// (tests/data/regressions/image, docs/fuzzing.md).
#include <catch2/catch.hpp>

#include <stdexcept>

#include "render/image.hpp"
#include "test_support.hpp"

using gs::test::readBytes;
using gs::test::sourceDir;

TEST_CASE("decodeImage reads a JPEG texture with libjpeg-turbo", "[render][image]") {
  const std::string bytes = readBytes(sourceDir() / "tests/fuzz/seeds/image/MTimage004.jpg");
  REQUIRE(!bytes.empty());
  int components = 0;
  const gs::render::Image image = gs::render::decodeImage(bytes, "MTimage004.jpg", &components);
  CHECK(image.width > 0);
  CHECK(image.height > 0);
  CHECK(image.rgba.size() == static_cast<std::size_t>(image.width) * image.height * 4);
  CHECK((components == 1 || components == 3));
  // Every alpha is opaque.
  bool opaque = true;
  for (std::size_t i = 3; i < image.rgba.size(); i += 4) opaque = opaque && image.rgba[i] == 255;
  CHECK(opaque);
  // A truncated copy is an error naming the input, not a crash.
  CHECK_THROWS_WITH(gs::render::decodeImage(bytes.substr(0, 40), "cut.jpg"),
                    Catch::Contains("cut.jpg"));
}

TEST_CASE("regression: a JPEG Huffman table counting more than 256 codes is refused",
          "[render][image][regression]") {
  // stb_image v2.27 wrote past h->size[257] for this file (fuzz_image, UBSan).
  const std::string bytes =
      readBytes(sourceDir() / "tests/data/regressions/image/jpeg_dht_counts_over_256.jpg");
  REQUIRE(bytes.size() == 786);
  CHECK_THROWS_AS(gs::render::decodeImage(bytes, "dht.jpg"), std::runtime_error);
}

TEST_CASE("regression: a 12-byte GIF claiming 16247 x 16247 pixels is refused at once",
          "[render][image][regression]") {
  // stb_image allocated and cleared 2.3 GB for it before reading a pixel (fuzz_image:
  // time-out after 14 s, 1.6 GB resident).
  const std::string bytes =
      readBytes(sourceDir() / "tests/data/regressions/image/gif_12_bytes_claims_16247x16247.gif");
  REQUIRE(bytes.size() == 12);
  CHECK_THROWS_WITH(gs::render::decodeImage(bytes, "big.gif"),
                    Catch::Contains("16247x16247 pixels is more than 12 bytes can hold") &&
                        Catch::Contains("kMaxImagePixelsPerByte"));
}

TEST_CASE("regression: a PNG whose first IDAT chunk is empty", "[render][image][regression]") {
  // stb_image passed a null pointer to memcpy for it (fuzz_image, UBSan). libpng reads it
  // or refuses it with a message; either way no undefined behaviour.
  const std::string bytes =
      readBytes(sourceDir() / "tests/data/regressions/image/png_empty_first_idat.png");
  REQUIRE(!bytes.empty());
  try {
    const gs::render::Image image = gs::render::decodeImage(bytes, "idat.png");
    CHECK(image.rgba.size() == static_cast<std::size_t>(image.width) * image.height * 4);
  } catch (const std::runtime_error& e) {
    CHECK_THAT(e.what(), Catch::Contains("idat.png"));
  }
}

TEST_CASE("decodeImage reads a grey + alpha PNG with libpng", "[render][image]") {
  const std::string bytes = readBytes(sourceDir() / "tests/fuzz/seeds/image/palmsh.png");
  int components = 0;
  const gs::render::Image image = gs::render::decodeImage(bytes, "palmsh.png", &components);
  CHECK(image.width == 128);
  CHECK(image.height == 128);
  CHECK(components == 2);
}
