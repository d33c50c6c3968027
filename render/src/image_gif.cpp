// GIF decoding with giflib (Debian's libgif): the first image of the file on its logical
// screen, its transparent colour index (Graphics Control Extension) as alpha 0.
#include "image_gif.hpp"

#include "render/image.hpp"

#include <gif_lib.h>

#include <algorithm>
#include <cstring>
#include <memory>
#include <stdexcept>

namespace gs::render::detail {
namespace {

struct Reader {
  std::string_view bytes;
  std::size_t at = 0;
};

int readBytes(GifFileType* gif, GifByteType* out, int wanted) {
  auto* r = static_cast<Reader*>(gif->UserData);
  const std::size_t n =
      std::min<std::size_t>(static_cast<std::size_t>(std::max(wanted, 0)), r->bytes.size() - r->at);
  std::memcpy(out, r->bytes.data() + r->at, n);
  r->at += n;
  return static_cast<int>(n);
}

struct Closer {
  void operator()(GifFileType* gif) const {
    int error = 0;
    DGifCloseFile(gif, &error);
  }
};

[[noreturn]] void fail(const std::string& name, const char* what) {
  throw std::runtime_error("cannot decode GIF " + name + ": " + (what ? what : "corrupt data"));
}

}  // namespace

bool looksLikeGif(std::string_view bytes) {
  return bytes.size() >= 6 && (bytes.substr(0, 6) == "GIF87a" || bytes.substr(0, 6) == "GIF89a");
}

Image decodeGif(std::string_view bytes, const std::string& name, int* components) {
  Reader reader{bytes};
  int error = 0;
  std::unique_ptr<GifFileType, Closer> gif(DGifOpen(&reader, readBytes, &error));
  if (!gif) fail(name, GifErrorString(error));
  const int width = gif->SWidth, height = gif->SHeight;
  if (width <= 0 || height <= 0 || width > kMaxImageSide || height > kMaxImageSide)
    throw std::runtime_error("cannot decode GIF " + name + ": size " + std::to_string(width) + "x" +
                             std::to_string(height) + " is empty or exceeds the limit of " +
                             std::to_string(kMaxImageSide) + " pixels per side");
  int transparent = NO_TRANSPARENT_COLOR;
  for (;;) {
    GifRecordType type = UNDEFINED_RECORD_TYPE;
    if (DGifGetRecordType(gif.get(), &type) == GIF_ERROR) fail(name, GifErrorString(gif->Error));
    if (type == TERMINATE_RECORD_TYPE) fail(name, "the file holds no image");
    if (type == EXTENSION_RECORD_TYPE) {
      int code = 0;
      GifByteType* block = nullptr;
      if (DGifGetExtension(gif.get(), &code, &block) == GIF_ERROR)
        fail(name, GifErrorString(gif->Error));
      if (code == GRAPHICS_EXT_FUNC_CODE && block != nullptr && block[0] >= 4) {
        GraphicsControlBlock gcb;
        if (DGifExtensionToGCB(block[0], block + 1, &gcb) == GIF_OK)
          transparent = gcb.TransparentColor;
      }
      while (block != nullptr)
        if (DGifGetExtensionNext(gif.get(), &block) == GIF_ERROR)
          fail(name, GifErrorString(gif->Error));
      continue;
    }
    if (type != IMAGE_DESC_RECORD_TYPE) continue;
    if (DGifGetImageDesc(gif.get()) == GIF_ERROR) fail(name, GifErrorString(gif->Error));
    const GifImageDesc& desc = gif->Image;
    const ColorMapObject* map = desc.ColorMap ? desc.ColorMap : gif->SColorMap;
    if (map == nullptr || map->Colors == nullptr) fail(name, "no colour table");
    if (desc.Width <= 0 || desc.Height <= 0 || desc.Width > kMaxImageSide ||
        desc.Height > kMaxImageSide)
      fail(name, "bad image size");
    // The logical screen starts transparent; the first image is drawn onto it, clipped.
    Image image(width, height, 0, 0, 0, 0);
    std::vector<GifPixelType> line(static_cast<std::size_t>(desc.Width));
    // Interlaced images arrive in four passes (rows 0, 4, 2, 1 mod 8, 8, 4, 2).
    static constexpr int kStart[4] = {0, 4, 2, 1}, kStep[4] = {8, 8, 4, 2};
    const int passes = desc.Interlace ? 4 : 1;
    bool covered = desc.Left == 0 && desc.Top == 0 && desc.Width >= width && desc.Height >= height;
    bool anyTransparent = false;
    for (int pass = 0; pass < passes; ++pass) {
      const int start = desc.Interlace ? kStart[pass] : 0, step = desc.Interlace ? kStep[pass] : 1;
      for (int row = start; row < desc.Height; row += step) {
        if (DGifGetLine(gif.get(), line.data(), desc.Width) == GIF_ERROR)
          fail(name, GifErrorString(gif->Error));
        const int y = desc.Top + row;
        if (y < 0 || y >= height) continue;
        for (int col = 0; col < desc.Width; ++col) {
          const int x = desc.Left + col;
          if (x < 0 || x >= width) continue;
          const int index = line[static_cast<std::size_t>(col)];
          if (index == transparent) {
            anyTransparent = true;
            continue;  // stays transparent
          }
          std::uint8_t* p = image.pixel(x, y);
          if (index < map->ColorCount) {
            const GifColorType& c = map->Colors[index];
            p[0] = c.Red;
            p[1] = c.Green;
            p[2] = c.Blue;
          }
          p[3] = 255;
        }
      }
    }
    if (components != nullptr) *components = anyTransparent || !covered ? 4 : 3;
    return image;
  }
}

}  // namespace gs::render::detail
