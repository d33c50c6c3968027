// Private to render/: JPEG decoding through libjpeg-turbo (Debian's libjpeg62-turbo),
// used by decodeImage instead of stb_image's JPEG decoder, which writes out of bounds on
// a corrupt Huffman table (found by tests/fuzz/fuzz_image.cpp; regression input
// tests/data/regressions/image/jpeg_dht_counts_over_256.jpg).
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gs::render::detail {

/// True when `bytes` start with a JPEG SOI marker and a further marker (FF D8 FF).
bool looksLikeJpeg(std::string_view bytes);

/// Decodes a baseline or progressive JPEG (grayscale, YCbCr/RGB) into RGBA8 rows, top row
/// first. Images wider or taller than `maxSide` (error "size") or with more than
/// `maxPixels` pixels (error "pixels") are refused before any pixel is decoded.
/// Returns false with `error` set (libjpeg's message otherwise) on any failure;
/// `components` becomes 1 for grayscale, else 3.
bool decodeJpeg(std::string_view bytes, int maxSide, std::size_t maxPixels,
                std::vector<std::uint8_t>& rgba, int& width, int& height, int& components,
                std::string& error);

}  // namespace gs::render::detail
