// The merged levels of a QNV tileset (issue 40 item 3; docs/tilesets.md, "Merged levels"):
// every interior node of the octree gets, beside its brick of original vectors, a small
// Gaussian stream of its whole region merged cell by cell, so that a far view draws a few
// wide, faint splats that keep the region's coverage instead of every weak vector.
//
// A QNV vector is one case of the Gaussian model (splats/gaussian.hpp): a flat disc whose
// normal is the vector's direction, isotropic in its plane with the paper's opacity
// profile (Nagasawa, section 3.1; vectorProfile below). A node of level L is cut into R^3
// cells (R = cells per axis, a power of two); the vectors of a cell merge by moment
// matching (splats/lod_tree.hpp: weights = opacity x mean projected area, merged mean and
// covariance, opacity keeping the summed coverage). Colours: the palette colour's weighted
// mean times the headlight's flat shading (render/splat_model.hpp shadeSplat) as spherical
// harmonics of degree 2: the member normals' |n . d| as its Legendre series 1/2 + 5/8
// P2(n . d) on SH bands 0 and 2, so the merged splat brightens where its members face the
// viewer, as the vectors would under the headlight.
//
// Sums are kept in 128-bit fixed point (2^-40 of each cell's own units), so they are exact
// and do not depend on the order vectors arrive: shares of a split encode sum to the bytes
// of the unsplit one. A Gaussian scene's higher SH coefficients are summed in doubles
// beside them, which do depend on the order: its encodes feed the splats in one order
// (GaussianMergedLevels).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>
#include <vector>

#include <glm/glm.hpp>

#include "qnv/encoder.hpp"
#include "qnv/tileset_writer.hpp"
#include "splats/gaussian.hpp"
#include "splats/vector_splat.hpp"

namespace gs::splats {

/// One cell's sums (fixed point, see the file comment).
struct MergedCell {
  static constexpr int kFields = 18;  // weight, mean 3, second moment 6, rgb 3, SH band 2: 5
  __extension__ using Wide = __int128;
  __extension__ using UnsignedWide = unsigned __int128;
  Wide sums[kFields] = {};
  std::uint64_t count = 0;
};

/// Builds the merged bricks of a tileset from its vectors, in any order, in any share (a
/// Gaussian scene's splats: the same bytes for the same order, see the file comment).
class MergedLevelBuilder {
 public:
  /// `layout` (which must outlive the builder) gives the octree; cellsLog2 in
  /// 1..qnv::kTilesetMaxMergedLog2. Merged cells exist for the interior levels 0 ..
  /// min(depth - 1, qnv::deepestMergedLevel(cellsLog2)).
  MergedLevelBuilder(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2);
  /// The same for the levels firstLevel .. lastLevel only (lastLevel < depth; any interior
  /// level, the bound of deepestMergedLevel not applied: GaussianMergedLevels holds one
  /// node per level). Throws qnv::InputError as above, or when the range is empty or
  /// reaches the leaves of a layout of depth >= 1 (of depth 0 nothing is summed).
  MergedLevelBuilder(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2,
                     std::uint8_t firstLevel, std::uint8_t lastLevel);

  /// Adds `v` (a selected vector of the tileset) to its cell at every interior level.
  void add(const qnv::SourceVector& v);
  /// Adds splat `i` of `cloud` (a splat the tileset of a Gaussian scene keeps,
  /// splats/gaussian_tileset.hpp; the layout's template is then of kind gaussian) to its
  /// cell at every interior level: weight = opacity x meanProjectedArea(scale), its own
  /// covariance added to the second moment, its band-0 colour (0.5 + kShC0 dc) to the
  /// colour, and its higher SH coefficients (up to the template's shDegree) to sums of
  /// their own: the merged splat's SH is its members' weighted mean (colour is linear in
  /// them). Not part of serialize(): Gaussian tilesets are built whole.
  void addGaussian(const GaussianCloud& cloud, std::size_t i);
  /// Cells holding vectors.
  std::size_t cellCount() const { return cells_.size(); }
  /// Forgets every sum (the levels and the layout stay).
  void clear() {
    cells_.clear();
    shSums_.clear();
  }

  /// The bytes of the sums (parts/I-of-N/merged.qnvm): signature 0x89 "QNM" CR LF 0x1A LF,
  /// u8 cellsLog2, u8[3] 0, u64 cell count, then per cell (by key) u64 key (level << 60 |
  /// x << 40 | y << 20 | z, global cell coordinates), u64 count, 18 x i128 sums; CRC-32
  /// last. Little-endian.
  std::string serialize() const;
  /// Parses those bytes (signature, sizes, CRC, levels below the depth, coordinates
  /// inside the level's grid) into this builder's sums (added to what it holds); false
  /// and a sentence naming `name` in `error` otherwise.
  bool addSerialized(std::string_view bytes, const std::string& name, std::string& error);

  /// The merged Gaussians of every interior node holding vectors, by node (splats in
  /// (z, y, x) cell order, SH degree 2 for vectors, the scene's for Gaussians, positions in world
  /// units).
  std::map<qnv::TilesetCell, GaussianCloud> build() const;

 private:
  struct CellFrame {
    glm::dvec3 origin{0.0};
    double size = 1.0;  // the cell's largest side, world units
  };
  /// The global cell of `v` at `level` and its frame.
  glm::uvec3 cellOf(const qnv::SourceVector& v, std::uint8_t level) const;
  CellFrame frameOf(std::uint8_t level, glm::uvec3 cell) const;
  std::uint32_t cellsPerAxis(std::uint8_t level) const;

  const qnv::TilesetLayout& layout_;
  std::uint8_t cellsLog2_;
  std::uint8_t firstLevel_ = 0, levelEnd_ = 0;  // the levels summed: [firstLevel_, levelEnd_)
  std::uint32_t brickVoxels_ = 0;
  double weightUnit_ = 1.0;  // world units^2: the largest weight a vector can have
  std::unordered_map<std::uint64_t, MergedCell> cells_;
  /// Gaussian scenes: the SH degree, and per cell the weighted sums of the members' SH
  /// coefficients above band 0 (kept in double beside the fixed-point sums: a Gaussian
  /// tileset is built in one run, never summed from shares).
  int shDegree_ = 0;
  std::unordered_map<std::uint64_t, std::vector<glm::dvec3>> shSums_;
};

/// The merged bricks of a Gaussian tileset at every interior level (the index's
/// qnv::kTilesetMergedEveryLevel; docs/tilesets.md, "Merged levels of Gaussian tilesets"),
/// built node by node so that what is held does not grow with the scene or the depth:
/// fed the kept splats leaf by leaf, leaves in increasing mortonOfCell order (so the
/// leaves under any node come together), it holds the cells of one node per level (at
/// most depth x R^3) and hands a node's merged Gaussians (MergedLevelBuilder::build of its
/// cells: positions in world units, the scene's SH degree) to `sink` once the leaves
/// under it are done, deepest first. A node whose splats merge to nothing is not handed.
/// The SH sums are doubles, added in the order given: the in-memory and the out-of-core
/// encodes both give leaves in Morton order and each leaf's splats in scene order, so
/// their merged bricks are the same bytes.
class GaussianMergedLevels {
 public:
  using Sink = std::function<void(const qnv::TilesetCell& node, GaussianCloud&& merged)>;
  /// `layout` (of kind gaussian, outliving this) with depth >= 1; cellsLog2 in
  /// 1..qnv::kTilesetMaxMergedLog2 (qnv::InputError otherwise).
  GaussianMergedLevels(const qnv::TilesetLayout& layout, std::uint8_t cellsLog2, Sink sink);
  /// Adds splats `members` of `cloud` (each kept by the stream), all of leaf `leaf`'s.
  /// Throws std::logic_error when `leaf` does not come after the last leaf in Morton order.
  void addLeaf(glm::uvec3 leaf, const GaussianCloud& cloud, std::span<const std::uint32_t> members);
  /// Hands the nodes still open to the sink (call once, after the last leaf).
  void finish();
  /// The most cells held at once, and the cells handed to the sink's nodes in all.
  std::size_t peakCells() const { return peakCells_; }
  std::uint64_t cellsMerged() const { return cellsMerged_; }

 private:
  void flush(std::size_t level);

  const qnv::TilesetLayout& layout_;
  Sink sink_;
  std::vector<MergedLevelBuilder> levels_;  // level L's open node's cells
  std::vector<std::optional<glm::uvec3>> open_;
  std::optional<std::uint64_t> lastLeaf_;  // its Morton code
  std::size_t peakCells_ = 0;
  std::uint64_t cellsMerged_ = 0;
};

/// The Morton code of an octree cell (bit 3 i of x, 3 i + 1 of y, 3 i + 2 of z; 21 bits
/// an axis): the order of a depth-first walk of the octree, in which the cells under any
/// node come together.
std::uint64_t mortonOfCell(glm::uvec3 cell);
/// The cell of Morton code `code` (mortonOfCell's inverse for cells below 2^21 an axis).
glm::uvec3 cellOfMorton(std::uint64_t code);

}  // namespace gs::splats
