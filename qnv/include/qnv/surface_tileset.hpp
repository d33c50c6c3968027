// Out-of-core tileset encoding of meshes (issue 13, part 2): the global selection of
// selectSurfaceVectors (keep the N largest triangle areas, ties by lower triangle index),
// its bounding box, magnitude range and palette, computed from passes over a triangle
// soup that is never held whole, so that a last pass can feed qnv::TilesetShareWriter
// triangle by triangle. The kept set, the stream header and therefore every brick are the
// in-memory encode's, bit for bit (docs/out-of-core.md, "Meshes").
#pragma once

#include <cstdint>
#include <functional>
#include <span>

#include "qnv/encoder.hpp"
#include "qnv/mesh.hpp"

namespace gs::qnv {

/// One triangle of a soup: its corners (world units) and its colour as encodeSurface
/// takes it (the face colour, else triangleMeanColor of the vertex colours, else the
/// mesh's base colour).
struct SurfaceTriangle {
  glm::vec3 a{0}, b{0}, c{0};
  Rgba8 color{204, 204, 204, 255};
};

/// The mean of three vertex colours as encodeSurface takes it: (sum + 1) / 3 per channel.
inline Rgba8 triangleMeanColor(const Rgba8& x, const Rgba8& y, const Rgba8& z) {
  Rgba8 out;
  for (int ch = 0; ch < 4; ++ch)
    out[ch] = static_cast<std::uint8_t>((unsigned{x[ch]} + y[ch] + z[ch] + 1) / 3);
  return out;
}

/// Called with batches of consecutive triangles: `first` is the index of batch[0].
using TriangleBatchCallback =
    std::function<void(std::uint64_t first, std::span<const SurfaceTriangle> batch)>;

/// A triangle soup that can be read any number of times, front to back.
class TriangleSoupReader {
 public:
  virtual ~TriangleSoupReader() = default;
  /// Triangles in the soup (TriangleMesh::triangleCount() of the same mesh).
  virtual std::uint64_t triangleCount() const = 0;
  /// Hands out every triangle once, in index order, in batches. Throws InputError on a
  /// read error.
  virtual void forEachTriangle(const TriangleBatchCallback& callback) = 0;
};

/// What the passes over the soup found: the header selectSurfaceVectors would give
/// (vectorCount = kept), the exact keep rule and the palette index of each kept colour.
struct SurfaceSelectionPlan {
  StreamHeader header;
  EncodeSummary summary;  // elements = triangles, candidates, kept
  /// Kept: a candidate (triangleVector is true) with area > threshold, and the first
  /// tiesKept candidates (in triangle order) whose area equals threshold. keepAll: every
  /// candidate.
  bool keepAll = true;
  float threshold = 0.0f;
  std::uint64_t tiesKept = 0;
  /// Passes over the soup it took: 1 (keep all or none), else 3 (the second looks into
  /// the boundary bin of the first's histogram, the third measures the kept triangles'
  /// box, area range and colours).
  unsigned passes = 1;
  /// The palette (header.palette) and the index of every colour of a kept triangle.
  CountedPalette palette;
};

/// The passes over `soup`. Pass 1 counts the candidates, measures their box, area range
/// and colours and takes a histogram of the upper 16 bits of their areas' float bits
/// (positive floats order as their bits). When the selection keeps some but not all,
/// pass 2 takes a histogram of the lower 16 bits inside the bin where the kept count is
/// crossed (the threshold is then exact) and pass 3 measures the kept triangles.
/// Memory: two 64 Ki-entry histograms (1 MiB) and the distinct colours (at most 40 bytes
/// each: counted in a table of 8-24 bytes, then buildPaletteFromCounts). Throws InputError when the
/// soup has more than 2^32 - 1 triangles (as selectSurfaceVectors does), when the counted triangles
/// have more than `maxColors` distinct colours, and as the reader does.
SurfaceSelectionPlan planSurfaceSelection(TriangleSoupReader& soup,
                                          const SurfaceEncodeOptions& options,
                                          std::uint64_t maxColors);

/// Decides, for candidates handed out in increasing triangle index from triangle 0,
/// which are kept (not thread-safe; one per pass).
class SurfaceKeepFilter {
 public:
  explicit SurfaceKeepFilter(const SurfaceSelectionPlan& plan) : plan_(plan) {}
  /// `magnitude`: the candidate's area (triangleVector's).
  bool keep(float magnitude) {
    if (plan_.keepAll) return true;
    if (magnitude > plan_.threshold) return true;
    if (magnitude < plan_.threshold) return false;
    return ties_++ < plan_.tiesKept;
  }

 private:
  const SurfaceSelectionPlan& plan_;
  std::uint64_t ties_ = 0;
};

}  // namespace gs::qnv
