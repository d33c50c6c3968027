// DirectDraw Surface files (Microsoft's DDS format: a 128-byte header, then the images)
// decoded to 8-bit RGBA, for ImageTexture3D (X3D 4.0 clause 33.4.2) and
// ImageCubeMapTexture (clause 34.4.2), which name DDS as the format of volumes and cube
// maps. Internal to gs_render.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace gs::render::detail {

/// The first mip level of every image of a DDS file.
struct DdsImages {
  int width = 0, height = 0;  // texels
  int depth = 1;              // slices of a volume texture; 1 otherwise
  /// Cube maps: which of the six faces the file holds (bit f for DDS face f: +X, -X, +Y,
  /// -Y, +Z, -Z); 0 for a 2D or volume texture.
  unsigned faces = 0;
  int components = 0;  // 1 (luminance), 2 (luminance, alpha), 3 (RGB) or 4 (RGBA)
  /// RGBA texels, rows top to bottom as in the file: for a cube map six faces in DDS order
  /// (a face the file lacks is transparent black), else `depth` slices; each
  /// width * height * 4 bytes.
  std::vector<std::uint8_t> rgba;
  bool cube() const { return faces != 0; }
};

/// Largest number of texels decoded from one file (2^26: 256 MiB of RGBA).
inline constexpr std::size_t kMaxDdsTexels = std::size_t{1} << 26;

/// Decodes `bytes` (a whole .dds file; `url` names it in errors): uncompressed RGB, RGBA,
/// luminance and luminance-alpha of 8 to 32 bits a texel with any channel masks, and the
/// S3TC block formats DXT1, DXT3 and DXT5 (FourCC "DXT1", "DXT3", "DXT5"; decoded on the
/// CPU, 4x4 texel blocks of 8 or 16 bytes). Throws std::runtime_error ("url: why") for
/// what is not a DDS file, other formats (DX10 headers, floating point), sizes of zero or
/// above kMaxDdsTexels, and data shorter than the header says.
DdsImages decodeDdsImages(std::string_view bytes, const std::string& url);

}  // namespace gs::render::detail
