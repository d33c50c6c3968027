// The surface and volume encoders (Nagasawa, "Beyond VRML", sections 2, 2.1 and 3.2):
// triangles or voxels in, quantized normal vectors out, sorted largest first so every
// prefix of the stream is the best picture of its size.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include "qnv/mesh.hpp"
#include "qnv/stream.hpp"
#include "qnv/volume.hpp"

namespace gs::qnv {

/// Called with the fraction done (0..1) at a few points of a long encode.
using ProgressCallback = std::function<void(double)>;

/// Which vectors to keep, largest magnitude first. `count` (> 0) wins over `fraction`;
/// the fraction is of all input elements (triangles, or voxels of the whole grid, as in
/// the paper's figure 2), in (0, 1]. Elements of zero magnitude are never kept.
struct Selection {
  double fraction = 1.0;
  std::uint64_t count = 0;
  /// The number of elements to keep out of `elements` (before dropping zeros).
  std::uint64_t keepOf(std::uint64_t elements) const;
};

/// What an encode saw, for reports: elements read, elements with a magnitude > 0 (and,
/// for volumes, inside the value window), vectors kept.
struct EncodeSummary {
  std::uint64_t elements = 0;
  std::uint64_t candidates = 0;
  std::uint64_t kept = 0;
};

struct SurfaceEncodeOptions {
  Selection selection;
  MagnitudeMapping mapping = MagnitudeMapping::logarithmic;
  OpacityProfile profile;
  ProgressCallback progress;
};

/// One vector per triangle of `mesh` (section 2.1): position = centroid, direction = unit
/// normal of (b - a) x (c - a) (counter-clockwise front), A = triangle area (square
/// units), C = the triangle's colour (face, mean vertex, or base colour) in a palette
/// of at most 256 colours (exact when the mesh has no more, else median cut).
/// Degenerate triangles (zero or non-finite area) are dropped. The bounding box is that
/// of the kept centroids; the magnitude range that of the kept areas.
EncodedVectors encodeSurface(const TriangleMesh& mesh, const SurfaceEncodeOptions& options,
                             EncodeSummary* summary = nullptr);

struct VolumeEncodeOptions {
  Selection selection;
  /// Only voxels whose value lies in [first, second] are kept (e.g. bone in CT). The
  /// transfer function domain is the window, else the volume's value range.
  std::optional<std::pair<float, float>> valueWindow;
  MagnitudeMapping mapping = MagnitudeMapping::logarithmic;
  OpacityProfile profile;
  /// The transfer function: palette entry c colours values in the c-th of 256 equal
  /// slices of the domain. Empty: defaultTransferFunction().
  std::optional<std::array<Rgba8, kPaletteSize>> palette;
  ProgressCallback progress;
};

/// One vector per voxel (section 3.2): position = voxel centre (origin + index *
/// spacing), direction = the gradient by central differences divided by twice the
/// spacing (one-sided at the border), pointing towards higher values; A = gradient
/// magnitude (value units per length unit); C = the voxel value's palette slice.
/// Voxels with a zero gradient are dropped. Bounds: the voxel centres of the grid.
EncodedVectors encodeVolume(const Volume& volume, const VolumeEncodeOptions& options,
                            EncodeSummary* summary = nullptr);

/// One vector before quantization, as the encoders select it: what a record quantizes,
/// plus the exact magnitude and the element it came from (for tilesets, which quantize
/// each brick against its own box: qnv/tileset_writer.hpp).
struct SourceVector {
  glm::vec3 position{0};     // triangle centroid or voxel centre (world units)
  glm::vec3 normal{0};       // (b - a) x (c - a) or the gradient; any non-zero length
  float magnitude = 0;       // A: triangle area or gradient magnitude (> 0, finite)
  std::uint8_t color = 0;    // palette index
  std::uint64_t source = 0;  // triangle index, or voxel linear index x + dx (y + dy z)
};

/// The kept vectors of an encode and the stream header that gives them meaning
/// (vectorCount = vectors.size(); packetBytes and encoding left at their defaults).
struct SelectedVectors {
  StreamHeader header;
  std::vector<SourceVector> vectors;
};

/// encodeSurface up to quantization: the kept triangles' vectors in triangle order.
SelectedVectors selectSurfaceVectors(const TriangleMesh& mesh, const SurfaceEncodeOptions& options,
                                     EncodeSummary* summary = nullptr);

/// encodeVolume up to quantization: the kept voxels' vectors (in no particular order;
/// deterministic for a given input).
SelectedVectors selectVolumeVectors(const Volume& volume, const VolumeEncodeOptions& options,
                                    EncodeSummary* summary = nullptr);

/// The record of `v` in a stream with header `header` (its box, and the magnitude range
/// `quantizeA` was made for). With `gridIndex` (volumes: the voxel's index within the
/// header's volumeDims, whose voxel 0 sits at boundsMin) the position codes are computed
/// exactly in integers, floor(i * 1024 / (dims - 1)) clamped to 1023 (0 when dims is 1),
/// the value quantizeCoordinate gives without rounding, so the entropy coding's grid mode
/// always applies.
std::uint64_t quantizeVector(const SourceVector& v, const StreamHeader& header,
                             const MagnitudeQuantizer& quantizeA,
                             const glm::uvec3* gridIndex = nullptr);

/// `ghostspace encode --magnitude-bits N` (docs/qnv-format.md, "Shared low bits"): rounds
/// every record's A code to `bits` bits (1..15, roundMagnitudeCode; lossy) and orders each
/// run of records with equal codes by the Morton code of (X, Y, Z), so that a packet cut
/// from a long run covers one region of space, whose positions code in fewer bits.
/// `records` must be sorted largest first (as encodeSurface and encodeVolume give them);
/// they stay so. With bits = 15 nothing changes.
void coarsenMagnitudes(std::span<std::uint64_t> records, int bits);

/// A ramp for CT: entry c (t = c / 255) goes from dark red (soft tissue) to white
/// (bone), with opacity 255 * t.
std::array<Rgba8, kPaletteSize> defaultTransferFunction();

/// Builds a palette of at most 256 colours for `colors` and writes each colour's palette
/// index to `indices` (same length). Exact when there are at most 256 distinct colours,
/// else a count-weighted median cut in RGBA. Unused entries are opaque black.
std::array<Rgba8, kPaletteSize> buildPalette(std::span<const Rgba8> colors,
                                             std::vector<std::uint8_t>& indices);

/// The key of `color` in buildPaletteFromCounts: r | g << 8 | b << 16 | a << 24.
std::uint32_t paletteKey(const Rgba8& color);
/// A palette made from colour counts, and the palette index of every counted colour.
struct CountedPalette {
  std::array<Rgba8, kPaletteSize> palette{};
  std::vector<std::uint32_t> keys;    // the counted colours' paletteKey, ascending
  std::vector<std::uint8_t> indices;  // the palette index of keys[i]
  /// The palette index of `color` (binary search; 0 for a colour that was not counted).
  std::uint8_t indexOf(const Rgba8& color) const;
};
/// buildPalette from the distinct colours (by paletteKey, each once, in any order) and how
/// often each occurs: the same palette as buildPalette on any list with those counts.
/// Memory: about 40 bytes per distinct colour at the peak, 5 in the result.
CountedPalette buildPaletteFromCounts(std::vector<std::pair<std::uint32_t, std::uint64_t>> counts);

/// The vector of triangle (a, b, c) as encodeSurface defines it (section 2.1): area
/// 0.5 |(b - a) x (c - a)|, centroid (a + b + c) / 3, normal (b - a) x (c - a). False
/// (and `out` untouched) for a degenerate triangle: zero or non-finite area, or a
/// non-finite coordinate. `out.color` is left as it is; out.source = `index`.
bool triangleVector(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c, std::uint64_t index,
                    SourceVector& out);

}  // namespace gs::qnv
