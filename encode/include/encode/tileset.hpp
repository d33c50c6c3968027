// Writing QNV tilesets to a folder (docs/qnv-format.md, "Tilesets"; docs/out-of-core.md,
// "Tileset encoding"): the in-memory encode of selected vectors, the out-of-core encodes
// of a volume read slab by slab and of a PLY mesh, and the merge of split runs' shares.
// Files, not printing: every function reports what it did in a result struct and its
// failure as an error value (it does not throw for bad input or unwritable folders);
// `ghostspace encode --tileset` and `ghostspace tileset index` print them.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>

#include "qnv/encoder.hpp"
#include "qnv/tileset.hpp"
#include "qnv/tileset_writer.hpp"
#include "qnv/volume_slabs.hpp"
#include "splats/gaussian.hpp"
#include "splats/qnv_gaussians.hpp"

namespace gs::encode {

/// Parses a share "I/N" (decimal, 0 <= I < N <= qnv::kMaxTilesetShares); false, with
/// `share` and `shares` unspecified, when malformed.
bool parseShare(std::string_view text, std::uint32_t& share, std::uint32_t& shares);
/// "I-of-N": the folder of share I of N under OUT/parts/.
std::string shareName(std::uint32_t share, std::uint32_t shares);
/// Writes `bytes` to `path`, making its folders as needed; "" or a sentence naming the path.
std::string writeFile(const std::filesystem::path& path, std::string_view bytes);

/// Where and how a tileset is written.
struct TilesetTarget {
  std::filesystem::path dir;  // OUT/: bricks/, index.qnvt, parts/I-of-N/ while split
  /// The cut (brickVoxels, brickVectors) and the packet coding (write).
  qnv::TilesetOptions cut;
  /// True: the whole tileset (share 0 of 1, then the merge; stale bricks/, parts/ and
  /// index.qnvt removed first). False: only share `share` of `shares` (its leaf bricks
  /// and OUT/parts/I-of-N/), merged later by mergeShares.
  bool whole = true;
  std::uint32_t share = 0, shares = 1;  // 0 <= share < shares <= qnv::kMaxTilesetShares
};

/// What mergeShares wrote.
struct Merged {
  qnv::TilesetIndex index;
  std::uint64_t indexBytes = 0;  // OUT/index.qnvt
  std::uint64_t totalBytes = 0;  // the index and every brick
};

/// Merges OUT/parts/*: writes the interior bricks and OUT/index.qnvt, then removes
/// OUT/parts. "" or the error (no or missing shares, shares of different encodes,
/// unreadable or unwritable files).
std::string mergeShares(const std::filesystem::path& dir, Merged& merged);

/// Why a tileset encode failed.
enum class Failure {
  none,
  input,  // bad input or options (qnv::InputError: a malformed file, a layout that fails)
  write,  // a file could not be written or read back, or the merge failed
};

/// What a tileset encode wrote.
struct TilesetResult {
  Failure failure = Failure::none;
  std::string error;                                     // the sentence, when failure != none
  Merged merged;                                         // target.whole: the merged tileset
  std::pair<std::uint64_t, std::uint64_t> leaves{0, 0};  // the share's leaves [first, end)
  std::uint64_t leafCount = 0;                           // of the whole layout
  unsigned depth = 0;                                    // of the octree
  std::uint64_t shareBytes = 0;  // bytes the share wrote (leaf bricks and parts)
  double seconds = 0;            // wall time of the call
  bool ok() const { return failure == Failure::none; }
};

/// Writes `selected` (qnv::selectVolumeVectors / selectSurfaceVectors) as `target` asks.
TilesetResult writeTileset(const TilesetTarget& target, const qnv::SelectedVectors& selected);

/// Writes the tileset of the Gaussian splatting scene `cloud`
/// (splats::buildGaussianTileset: bricks of Gaussian streams, merged bricks from the
/// Gaussians when target.cut.mergedCellsLog2 > 0, the index). Whole (target.whole): stale
/// bricks/, merged/, parts/ and index.qnvt are removed first. A share: its bricks (share 0
/// the interior and merged ones too) and OUT/parts/I-of-N/ (leaves.qnvt, its bricks'
/// index; interior.qnvp without entries, the brick options; gaussian.txt, the SH options),
/// which mergeShares indexes. Failure::input for a scene with no splat to keep or a K of 0,
/// Failure::write for a file not written.
/// result.merged.index.header.vectorCount counts records (recordsPerElement() a splat).
/// The bricks are encoded on `threads` threads (0: every core, as OutOfCoreOptions), the
/// same bytes whatever the count.
TilesetResult writeGaussianTileset(const TilesetTarget& target, const splats::GaussianCloud& cloud,
                                   const splats::GaussianStreamOptions& options,
                                   unsigned threads = 1);

/// The memory and threads of an out-of-core encode.
struct OutOfCoreOptions {
  /// The bound on what the encode holds, in bytes (> 0; the `--memory MB` of the CLI
  /// times 1048576); vectors past it are spilled to OUT/parts/I-of-N/*.spill.
  std::uint64_t memoryBytes = 64u << 20;
  unsigned threads = 0;  // workers finishing leaves; 0: std::thread::hardware_concurrency()
};

/// What an out-of-core volume encode did, beyond the tileset.
struct VolumeOutOfCoreResult {
  TilesetResult tileset;
  qnv::EncodeSummary summary;  // voxels, candidates, kept
  unsigned passes = 0;         // selection passes over the volume
  double planSeconds = 0, vectorSeconds = 0;
  std::uint32_t z0 = 0, z1 = 0;  // the slices [z0, z1) the vector pass read
  std::uint32_t slabSlices = 0;  // slices per slab of the vector pass
  std::uint64_t leafSpillBytes = 0, interiorSpillBytes = 0;
};

/// Encodes the volume `reader` reads into `target`, slab by slab (docs/out-of-core.md):
/// the selection passes (qnv::planVolumeSelection), then the vector pass over the slices
/// of the share's leaf rows, leaf bricks written as their row completes, leaf vectors
/// and interior contributions spilled when they outgrow `ooc.memoryBytes`. The files
/// are writeTileset's for qnv::selectVolumeVectors of the whole volume, byte for byte.
VolumeOutOfCoreResult writeVolumeTilesetOutOfCore(const TilesetTarget& target,
                                                  qnv::VolumeSlabReader& reader,
                                                  const qnv::VolumeEncodeOptions& encode,
                                                  const OutOfCoreOptions& ooc);

/// What an out-of-core mesh encode did, beyond the tileset.
struct MeshOutOfCoreResult {
  TilesetResult tileset;
  qnv::EncodeSummary summary;              // triangles, with a non-zero area, kept
  std::uint64_t vertices = 0, colors = 0;  // the PLY's vertices; the palette's colours
  std::uint64_t copiedBytes = 0;           // the part folder's copy of the mesh
  std::uint64_t cacheMisses = 0;           // vertex block reads
  unsigned passes = 0;                     // selection passes
  double copySeconds = 0, planSeconds = 0, vectorSeconds = 0;
  std::uint64_t leafSpillBytes = 0, interiorSpillBytes = 0;
};

/// The same for the triangles of the PLY file `ply` (read with formats::streamPly and
/// copied to the share's part folder, 16 bytes a vertex and a triangle; vertices read
/// back through a cache of a quarter of the bound). The files are writeTileset's for
/// qnv::selectSurfaceVectors of the whole mesh, byte for byte. A malformed PLY is
/// Failure::input, its copy removed.
MeshOutOfCoreResult writeMeshTilesetOutOfCore(const TilesetTarget& target,
                                              const std::filesystem::path& ply,
                                              const qnv::SurfaceEncodeOptions& encode,
                                              const OutOfCoreOptions& ooc);

/// Which parts of a Gaussian tileset's cut the encode was not told (the CLI's
/// `--brick-vectors` and `--merged-cells` not given): the scene's defaults replace them.
struct GaussianCutDefaults {
  bool brickVectors = false;  // splats::defaultGaussianBrickVectors
  bool mergedCells = false;   // splats::defaultGaussianMergedCellsLog2
};

/// What an out-of-core Gaussian tileset encode did, beyond the tileset.
struct GaussianOutOfCoreResult {
  TilesetResult tileset;
  std::uint64_t splats = 0, kept = 0;  // the scene's, and those the stream keeps
  int shDegree = 0;
  std::uint64_t brickVectors = 0;     // K as used (the scene's default when asked)
  std::uint8_t mergedCellsLog2 = 0;   // as used (the scene's default when asked)
  std::uint64_t mergedCells = 0;      // cells of the merged levels' sums (share 0), in all
  std::uint64_t mergedPeakCells = 0;  // the most held at once (one node a level)
  unsigned passes = 0;                // reads of the scene
  double frameSeconds = 0, bucketSeconds = 0, brickSeconds = 0, mergedSeconds = 0;
  std::uint64_t leafSpillBytes = 0, interiorSpillBytes = 0;
  /// Failure::input because the scene could not be read (a short or changed file, its
  /// FormatError's sentence), not because of what it holds or the cut.
  bool unreadable = false;
};

/// Encodes the Gaussian splatting scene `reader` reads into `target`, piecewise
/// (docs/out-of-core.md, "Gaussian splatting scenes"): pass 1 the stream frame
/// (splats::GaussianFrameBuilder), pass 2 each kept splat's importance and leaf, its
/// floats (16 + 3 x 15 words at SH degree 3: 244 bytes) held by leaf in half the bound and
/// spilled to OUT/parts/I-of-N/leaves.spill past it, then each leaf ranked and split
/// (splats::splitGaussianLeaf; a leaf is held whole while it is ranked; each brick
/// encoded and written by a job, ooc.threads of them at once, each holding its node's
/// splats), the interior
/// nodes' splats held in a quarter of the bound (interior.spill past it); share 0 with
/// merged levels adds each leaf, before it is ranked (leaves in Morton order), to the
/// merged levels' open nodes (splats::GaussianMergedLevels: at most depth x R^3 cells
/// held, each node's merged brick written when its leaves are done). A batch read is at
/// most an eighth of the bound. `defaults`: the cut's K is the scene's
/// (splats::defaultGaussianBrickVectors of the splats kept in pass 1), its merged cells the
/// scene's (splats::gaussianMergedCellsLog2For, from pass 2's occupancy). Shares as
/// writeGaussianTileset's: share 0 also reads every other leaf, for the interior nodes.
/// The files are writeGaussianTileset's for the whole scene read at once, byte for byte.
/// Failure::input for a scene that cannot be read (its sentence; `unreadable` set), no
/// splat kept or a bad cut; Failure::write for a file (or spill file) not written. A whole
/// run removes the old tileset only once the scene was read and something kept, and its
/// OUT/parts/ whatever happens; no index.qnvt is written unless every brick was.
GaussianOutOfCoreResult writeGaussianTilesetOutOfCore(const TilesetTarget& target,
                                                      splats::GaussianBatchReader& reader,
                                                      const splats::GaussianStreamOptions& options,
                                                      const GaussianCutDefaults& defaults,
                                                      const OutOfCoreOptions& ooc);

}  // namespace gs::encode
