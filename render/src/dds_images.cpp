#include "dds_images.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>

namespace gs::render::detail {

namespace {

std::uint32_t readLe32(std::string_view b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i)
    v = (v << 8) | static_cast<std::uint8_t>(b[at + static_cast<std::size_t>(i)]);
  return v;
}

std::uint32_t readLe16(std::string_view b, std::size_t at) {
  return static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[at])) |
         (static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[at + 1])) << 8);
}

/// The channel a bit mask selects, scaled to 8 bits (255 when there is no mask).
std::uint8_t channel(std::uint32_t pixel, std::uint32_t mask) {
  if (mask == 0) return 255;
  int shift = 0;
  while (((mask >> shift) & 1u) == 0) ++shift;
  const std::uint64_t max = mask >> shift;
  return static_cast<std::uint8_t>(((pixel & mask) >> shift) * 255u / max);
}

// Header fields (offsets in bytes; DDS_HEADER and DDS_PIXELFORMAT).
constexpr std::size_t kHeaderBytes = 128;
constexpr std::uint32_t kPixelFourCC = 0x4, kPixelLuminance = 0x20000, kPixelRgb = 0x40,
                        kPixelAlphaOnly = 0x2;
constexpr std::uint32_t kCaps2Cube = 0x200, kCaps2Volume = 0x200000;

enum class Format { uncompressed, dxt1, dxt3, dxt5 };

/// RGB565 to 8-bit RGB.
std::array<std::uint8_t, 3> rgb565(std::uint32_t c) {
  const std::uint32_t r = (c >> 11) & 31, g = (c >> 5) & 63, b = c & 31;
  return {static_cast<std::uint8_t>((r * 255 + 15) / 31),
          static_cast<std::uint8_t>((g * 255 + 31) / 63),
          static_cast<std::uint8_t>((b * 255 + 15) / 31)};
}

/// One S3TC colour block (8 bytes at `at`) into the 4x4 texels at (bx, by) of `out`
/// (width w, height h: blocks on the edge keep only their texels inside). `fourColours`:
/// DXT3 and DXT5 always interpolate two colours between the end points; DXT1 does when
/// colour0 > colour1, else one and transparent black.
void colourBlock(std::string_view b, std::size_t at, bool fourColours, int bx, int by, int w, int h,
                 std::uint8_t* out) {
  const std::uint32_t c0 = readLe16(b, at), c1 = readLe16(b, at + 2);
  const auto e0 = rgb565(c0), e1 = rgb565(c1);
  std::array<std::array<std::uint8_t, 4>, 4> palette{};
  palette[0] = {e0[0], e0[1], e0[2], 255};
  palette[1] = {e1[0], e1[1], e1[2], 255};
  for (int k = 0; k < 3; ++k) {
    if (fourColours || c0 > c1) {
      palette[2][k] = static_cast<std::uint8_t>((2 * e0[k] + e1[k] + 1) / 3);
      palette[3][k] = static_cast<std::uint8_t>((e0[k] + 2 * e1[k] + 1) / 3);
    } else {
      palette[2][k] = static_cast<std::uint8_t>((e0[k] + e1[k]) / 2);
      palette[3][k] = 0;
    }
  }
  palette[2][3] = 255;
  palette[3][3] = (fourColours || c0 > c1) ? 255 : 0;
  const std::uint32_t bits = readLe32(b, at + 4);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int px = bx * 4 + x, py = by * 4 + y;
      if (px >= w || py >= h) continue;
      const auto& c = palette[(bits >> (2 * (4 * y + x))) & 3];
      std::copy(c.begin(), c.end(), out + 4 * (static_cast<std::size_t>(py) * w + px));
    }
}

/// The alpha of a DXT3 (explicit 4 bits) or DXT5 (interpolated) block at `at`.
void alphaBlock(std::string_view b, std::size_t at, bool interpolated, int bx, int by, int w, int h,
                std::uint8_t* out) {
  std::array<std::uint8_t, 16> alpha{};
  if (!interpolated) {
    for (int i = 0; i < 16; ++i) {
      const auto byte = static_cast<std::uint8_t>(b[at + static_cast<std::size_t>(i / 2)]);
      const unsigned nibble = (i % 2 == 0) ? (byte & 15u) : (byte >> 4);
      alpha[static_cast<std::size_t>(i)] = static_cast<std::uint8_t>(nibble * 17);
    }
  } else {
    const unsigned a0 = static_cast<std::uint8_t>(b[at]), a1 = static_cast<std::uint8_t>(b[at + 1]);
    std::array<unsigned, 8> palette{a0, a1};
    for (unsigned k = 2; k < 8; ++k)
      palette[k] = a0 > a1  ? ((8 - k) * a0 + (k - 1) * a1 + 3) / 7
                   : k < 6  ? ((6 - k) * a0 + (k - 1) * a1 + 2) / 5
                   : k == 6 ? 0u
                            : 255u;
    std::uint64_t bits = 0;
    for (int i = 0; i < 6; ++i)
      bits |= static_cast<std::uint64_t>(
                  static_cast<std::uint8_t>(b[at + 2 + static_cast<std::size_t>(i)]))
              << (8 * i);
    for (int i = 0; i < 16; ++i)
      alpha[static_cast<std::size_t>(i)] =
          static_cast<std::uint8_t>(palette[(bits >> (3 * i)) & 7]);
  }
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) {
      const int px = bx * 4 + x, py = by * 4 + y;
      if (px >= w || py >= h) continue;
      out[4 * (static_cast<std::size_t>(py) * w + px) + 3] =
          alpha[static_cast<std::size_t>(4 * y + x)];
    }
}

}  // namespace

DdsImages decodeDdsImages(std::string_view b, const std::string& url) {
  if (b.size() < kHeaderBytes || b.substr(0, 4) != "DDS " || readLe32(b, 4) != 124)
    throw std::runtime_error(url + ": not a DDS file");
  DdsImages out;
  out.height = static_cast<int>(readLe32(b, 12));
  out.width = static_cast<int>(readLe32(b, 16));
  const std::uint32_t caps2 = readLe32(b, 112);
  out.depth = (caps2 & kCaps2Volume) != 0 ? std::max(1, static_cast<int>(readLe32(b, 24))) : 1;
  const auto mips = std::max<std::uint32_t>(1, readLe32(b, 28));
  const std::uint32_t flags = readLe32(b, 80), bits = readLe32(b, 88);
  const std::uint32_t rMask = readLe32(b, 92), gMask = readLe32(b, 96), bMask = readLe32(b, 100),
                      aMask = readLe32(b, 104);
  if ((caps2 & kCaps2Cube) != 0) out.faces = (caps2 >> 10) & 63u;
  if ((caps2 & kCaps2Cube) != 0 && out.faces == 0) out.faces = 63;  // (no face named: all)

  Format format = Format::uncompressed;
  if ((flags & kPixelFourCC) != 0) {
    const std::string_view code = b.substr(84, 4);
    if (code == "DXT1")
      format = Format::dxt1;
    else if (code == "DXT3")
      format = Format::dxt3;
    else if (code == "DXT5")
      format = Format::dxt5;
    else
      throw std::runtime_error(url + ": DDS format '" + std::string(code) +
                               "' is not read (DXT1, DXT3, DXT5 and uncompressed are)");
  } else if (bits != 8 && bits != 16 && bits != 24 && bits != 32) {
    throw std::runtime_error(url + ": DDS of " + std::to_string(bits) + " bits a texel");
  }
  const auto w = static_cast<std::size_t>(out.width), h = static_cast<std::size_t>(out.height);
  const std::size_t images = out.cube() ? 6 : static_cast<std::size_t>(out.depth);
  if (out.width <= 0 || out.height <= 0 || out.width > 65536 || out.height > 65536 ||
      w * h * images > kMaxDdsTexels)
    throw std::runtime_error(url + ": DDS size out of range");

  // Bytes of one image at mip level `l` (a volume's level holds its slices together).
  const std::size_t bytesPer = bits / 8;
  const std::size_t blockBytes = format == Format::dxt1 ? 8 : 16;
  const auto levelBytes = [&](std::uint32_t l, std::size_t slices) {
    const std::size_t lw = std::max<std::size_t>(1, w >> l), lh = std::max<std::size_t>(1, h >> l);
    const std::size_t ls = std::max<std::size_t>(1, slices >> l);
    if (format == Format::uncompressed) return lw * lh * ls * bytesPer;
    return ((lw + 3) / 4) * ((lh + 3) / 4) * ls * blockBytes;
  };
  // A cube face's whole mip chain comes before the next face.
  std::size_t faceChain = 0;
  for (std::uint32_t l = 0; l < std::min<std::uint32_t>(mips, 32); ++l)
    faceChain += levelBytes(l, 1);

  out.rgba.assign(w * h * images * 4, 0);
  const bool luminance = (flags & kPixelLuminance) != 0 && (flags & kPixelRgb) == 0;
  const bool alphaOnly =
      (flags & kPixelAlphaOnly) != 0 && (flags & (kPixelRgb | kPixelLuminance)) == 0;
  if (format == Format::uncompressed)
    out.components = luminance ? (aMask != 0 ? 2 : 1) : alphaOnly ? 2 : (aMask != 0 ? 4 : 3);
  else
    out.components = 4;  // (DXT1: 3 unless a texel is transparent; below)

  std::size_t at = kHeaderBytes;
  for (std::size_t image = 0; image < images; ++image) {
    if (out.cube() && ((out.faces >> image) & 1u) == 0) continue;  // not in the file
    const std::size_t slices = out.cube() ? 1 : static_cast<std::size_t>(out.depth);
    const std::size_t need = out.cube() ? levelBytes(0, 1) : levelBytes(0, slices);
    if (b.size() < at + need)
      throw std::runtime_error(url + ": DDS data shorter than its size says");
    for (std::size_t s = 0; s < slices; ++s) {
      const std::size_t index = out.cube() ? image : s;
      std::uint8_t* dst = out.rgba.data() + index * w * h * 4;
      const std::size_t src = at + s * levelBytes(0, 1);
      if (format == Format::uncompressed) {
        for (std::size_t i = 0; i < w * h; ++i) {
          std::uint32_t p = 0;
          for (std::size_t k = 0; k < bytesPer; ++k)
            p |= static_cast<std::uint32_t>(static_cast<std::uint8_t>(b[src + i * bytesPer + k]))
                 << (8 * k);
          std::uint8_t* t = dst + 4 * i;
          if (alphaOnly) {
            t[0] = t[1] = t[2] = 255;
            t[3] = channel(p, aMask);
            continue;
          }
          const std::uint8_t r = channel(p, rMask);
          t[0] = r;
          t[1] = luminance ? r : channel(p, gMask);
          t[2] = luminance ? r : channel(p, bMask);
          t[3] = aMask != 0 ? channel(p, aMask) : 255;
        }
      } else {
        const int bw = (out.width + 3) / 4, bh = (out.height + 3) / 4;
        std::size_t block = src;
        for (int by = 0; by < bh; ++by)
          for (int bx = 0; bx < bw; ++bx, block += blockBytes) {
            if (format == Format::dxt1) {
              colourBlock(b, block, false, bx, by, out.width, out.height, dst);
            } else {
              colourBlock(b, block + 8, true, bx, by, out.width, out.height, dst);
              alphaBlock(b, block, format == Format::dxt5, bx, by, out.width, out.height, dst);
            }
          }
      }
    }
    at += out.cube() ? faceChain : need;
    if (!out.cube()) break;  // a volume's slices are all read
  }
  if (format == Format::dxt1) {
    bool transparent = false;
    for (std::size_t i = 3; i < out.rgba.size() && !transparent; i += 4)
      transparent = out.rgba[i] == 0;
    out.components = transparent ? 4 : 3;
  }
  return out;
}

}  // namespace gs::render::detail
