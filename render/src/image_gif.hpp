// Private to render/: GIF decoding through giflib, used by decodeImage.
#pragma once

#include "render/image.hpp"

#include <string>
#include <string_view>

namespace gs::render::detail {

/// True when `bytes` start with a GIF signature ("GIF87a" or "GIF89a").
bool looksLikeGif(std::string_view bytes);

/// Decodes the first image of a GIF file (GIF87a / GIF89a, interlaced or not) onto its
/// logical screen as 8-bit RGBA, rows top to bottom. Pixels of the transparent colour index
/// of the image's Graphics Control Extension, and screen pixels the image does not cover,
/// get alpha 0; all others alpha 255. `components` (when not null) receives 4 when some
/// pixel is transparent, else 3 (ISO/IEC 14772-1 6.22: RGB or RGBA). Throws
/// std::runtime_error naming `name` for truncated or corrupt data, a screen or image larger
/// than kMaxImageSide, or no image. Safe for untrusted input.
Image decodeGif(std::string_view bytes, const std::string& name, int* components);

}  // namespace gs::render::detail
