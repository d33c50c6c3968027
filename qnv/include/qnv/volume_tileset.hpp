// Out-of-core tileset encoding of volumes (issue 13, part 2): the global selection of
// selectVolumeVectors (keep the N largest gradient magnitudes, ties by lower voxel index)
// computed from passes over the slabs of a VolumeSlabReader, without holding the volume
// or its vectors, so that a second pass can feed qnv::TilesetShareWriter slab by slab.
// The kept set, the stream header and therefore every brick are the same as the
// in-memory encode's, bit for bit (docs/out-of-core.md, "Tileset encoding").
#pragma once

#include <array>
#include <cstdint>

#include "qnv/encoder.hpp"
#include "qnv/volume_slabs.hpp"

namespace gs::qnv {

/// What the passes over the slabs found: the header selectVolumeVectors would give
/// (vectorCount = kept), and the exact rule that decides, voxel by voxel in increasing
/// index, whether a candidate vector is kept.
struct VolumeSelectionPlan {
  StreamHeader header;
  EncodeSummary summary;  // elements = voxels, candidates, kept
  /// Kept: magnitude > threshold, and the first tiesKept candidates (in voxel order) whose
  /// magnitude equals threshold. keepAll: every candidate (threshold unused).
  bool keepAll = true;
  float threshold = 0.0f;
  std::uint64_t tiesKept = 0;
  /// Candidates equal to threshold in slices [0, startSlice) (the `startSlice` given to
  /// planVolumeSelection): where a pass starting at that slice begins counting ties.
  std::uint64_t tiesBefore = 0;
  std::uint32_t startSlice = 0;
  /// Gradient passes over the whole volume it took: 1 (keep all, or keep none), else 2
  /// (the second looks into the boundary bin of the first pass's histogram).
  unsigned passes = 1;
  /// The colour domain (the window, else the finite value range) for the vector pass.
  std::pair<float, float> colorDomain{0.0f, 0.0f};
};

/// The passes over every slab of `reader` (`step` sets slab thickness, memory and
/// threads; its valueWindow and valueRange are ignored: `options.valueWindow` decides).
/// Pass 1 counts the candidates (magnitude > 0 and finite, value in the window; without
/// a window every finite value), their magnitude extremes, the finite value range and a
/// histogram of the upper 16 bits of the magnitudes' float bits (positive floats order
/// as their bits). When the selection keeps some but not all candidates, pass 2 takes a
/// histogram of the lower 16 bits inside the bin where the kept count is crossed: the
/// threshold is then exact, and the ties at it are counted before `startSlice` so that
/// a pass starting there (one share of a split encode) keeps exactly the right ones.
/// Memory: two 64 Ki-entry histograms (1 MiB) besides the gradient step's own.
/// Throws InputError as forEachVolumeVector does (an empty window, a bad read).
VolumeSelectionPlan planVolumeSelection(VolumeSlabReader& reader,
                                        const VolumeEncodeOptions& options,
                                        const VolumeVectorOptions& step,
                                        std::uint32_t startSlice = 0);

/// Decides, for vectors handed out in increasing voxel index from plan.startSlice on,
/// which are kept (not thread-safe; one per pass).
class VolumeKeepFilter {
 public:
  explicit VolumeKeepFilter(const VolumeSelectionPlan& plan)
      : plan_(plan), ties_(plan.tiesBefore) {}
  bool keep(const VolumeVector& v) {
    if (plan_.keepAll) return true;
    if (v.magnitude > plan_.threshold) return true;
    if (v.magnitude < plan_.threshold) return false;
    return ties_++ < plan_.tiesKept;
  }

 private:
  const VolumeSelectionPlan& plan_;
  std::uint64_t ties_;
};

/// The SourceVector of a gradient vector (what selectVolumeVectors gives for the voxel).
inline SourceVector toSourceVector(const VolumeVector& v) {
  SourceVector s;
  s.position = v.position;
  s.normal = v.gradient;
  s.magnitude = v.magnitude;
  s.color = v.color;
  s.source = v.index;
  return s;
}

}  // namespace gs::qnv
