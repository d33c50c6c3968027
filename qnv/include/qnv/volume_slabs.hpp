// Out-of-core volumes (issue 13, part 2): a volume read slab by slab (a run of whole z
// slices) instead of whole, and the gradient step of the volume encoder (paper section
// 3.2) over such slabs with memory bounded by the slab, not by the volume.
// The readers of files live in formats/volume_slabs.hpp; this header holds the interface
// they implement, so that the codec can consume them without depending on formats/.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <utility>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/volume.hpp"

namespace gs::qnv {

/// Readers of slabs refuse grids above this many voxels (2^40; a 2048^3 volume is 2^33).
inline constexpr std::uint64_t kMaxSlabVolumeVoxels = std::uint64_t{1} << 40;
/// ... and slices above this many voxels (2^28, e.g. 16384 x 16384), so that one slice
/// (the least a slab holds) is a bounded allocation.
inline constexpr std::uint64_t kMaxSliceVoxels = std::uint64_t{1} << 28;

/// What a slab reader knows about its grid before reading any sample.
struct VolumeGridInfo {
  glm::uvec3 dims{0, 0, 0};    // samples along x, y, z; each >= 1
  glm::vec3 spacing{1, 1, 1};  // distance between neighbouring samples (file units, > 0)
  glm::vec3 origin{0, 0, 0};   // position of sample (0,0,0)
  ScalarType sourceType = ScalarType::float32;  // the stored sample type
  /// The range of the (finite) sample values when the source states it; empty when
  /// unknown (then volumeValueRange() measures it).
  std::optional<std::pair<float, float>> valueRange;

  std::uint64_t sliceVoxels() const { return std::uint64_t{dims.x} * dims.y; }
  std::uint64_t voxelCount() const { return sliceVoxels() * dims.z; }
};

/// A volume read as slabs of z slices. Implementations keep memory bounded by what one
/// call asks for (plus a fixed buffer), whatever the volume's size; they are not
/// thread-safe (one caller at a time).
class VolumeSlabReader {
 public:
  virtual ~VolumeSlabReader() = default;
  virtual const VolumeGridInfo& info() const = 0;
  /// Slices [z0, z1) as float samples, x fastest, then y, then z; `out` is resized to
  /// dims.x * dims.y * (z1 - z0). Requires z0 < z1 <= dims.z (else InputError). Throws
  /// InputError naming the file and byte offset on a short or bad read.
  virtual void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) = 0;
};

/// A VolumeSlabReader over a Volume in memory (tests, and small volumes given whole).
/// `volume` must outlive the reader. valueRange is left unknown.
class MemoryVolumeSlabs final : public VolumeSlabReader {
 public:
  explicit MemoryVolumeSlabs(const Volume& volume);
  const VolumeGridInfo& info() const override { return info_; }
  void readSlices(std::uint32_t z0, std::uint32_t z1, std::vector<float>& out) override;

 private:
  const Volume& volume_;
  VolumeGridInfo info_;
};

/// Reads every slice of `reader` into one Volume (the whole-volume readers' result).
/// Throws InputError when the grid has more than kMaxVoxels voxels.
Volume readWholeVolume(VolumeSlabReader& reader);

/// The range [min, max] of the finite samples of `reader`, read `slabSlices` slices at a
/// time (one pass). (0, 0) when no sample is finite.
std::pair<float, float> volumeValueRange(VolumeSlabReader& reader, std::uint32_t slabSlices);

/// One voxel's gradient vector, unquantized, exactly as encodeVolume computes it before
/// quantizing (paper section 3.2).
struct VolumeVector {
  glm::vec3 position;   // voxel centre: origin + (x, y, z) * spacing
  glm::vec3 gradient;   // central differences / (2 spacing), one-sided at the border;
                        // points towards higher values; normal = gradient / magnitude
  float magnitude;      // |gradient| (value units per length unit), > 0 and finite
  float value;          // the voxel's sample
  std::uint64_t index;  // x + dims.x * (y + dims.y * z)
  std::uint8_t color;   // palette slice of `value` in the colour domain (0..255)
};

struct VolumeVectorOptions {
  /// Only voxels whose value lies in [first, second] give vectors (encodeVolume's
  /// valueWindow); the window is also the colour domain.
  std::optional<std::pair<float, float>> valueWindow;
  /// Without a window, the colour domain (and the window) is this range; when empty too,
  /// the reader's info().valueRange, else volumeValueRange() of the whole volume (an
  /// extra pass over the data). encodeVolume's domain is the whole volume's finite range.
  std::optional<std::pair<float, float>> valueRange;
  /// Slices computed per slab; 0 derives it from memoryBytes (slabSlicesForMemory).
  std::uint32_t slabSlices = 0;
  /// The memory bound of the gradient step when slabSlices is 0 (bytes).
  std::uint64_t memoryBytes = std::uint64_t{512} << 20;
  /// Worker threads per slab; 0: std::thread::hardware_concurrency().
  unsigned threads = 0;
};

/// What forEachVolumeVector did.
struct VolumeVectorSummary {
  std::uint64_t voxels = 0;   // voxels of [z0, z1)
  std::uint64_t vectors = 0;  // vectors handed out (magnitude > 0, in the window)
  std::uint32_t slabSlices = 0;
  std::pair<float, float> colorDomain{0.0f, 0.0f};
};

/// Receives the vectors of a run of consecutive slices, in increasing voxel index.
/// Calls come on the caller's thread, in increasing z, one after another.
using VolumeVectorCallback = std::function<void(std::span<const VolumeVector>)>;

/// The slab thickness (>= 1) such that the gradient step over `info`'s grid holds at
/// most `memoryBytes`: the window of (slab + 2) slices of float samples, the slab's
/// freshly read slices, the next slab's slices (read ahead while this one is computed),
/// and a VolumeVector (48 bytes) per voxel of the slab (the worst case: every voxel
/// gives a vector), i.e. slice voxels * (12 + 48) bytes per slab slice plus slice
/// voxels * 8 bytes. 1 when even one slice exceeds the bound; never more
/// than dims.z. The reader's own buffer (a few MiB) and the callback's memory are not
/// counted.
std::uint32_t slabSlicesForMemory(const VolumeGridInfo& info, std::uint64_t memoryBytes);

/// The gradient vectors of slices [z0, z1) of `reader` (z0 < z1 <= dims.z), with the
/// definition of encodeVolume: gradient = central differences divided by twice the
/// spacing (one-sided, divided by the spacing, at the border; 0 along an axis of one
/// sample), voxels with a zero or non-finite magnitude or a value outside the window
/// dropped, colour = min(255, (value - lo) * 256 / (hi - lo)) for the domain [lo, hi].
/// Reads each slice of [z0 - 1, z1 + 1) once, slab by slab, keeping a window of the
/// slab plus its two neighbour slices (memory O(slab)); the vectors of each slab are
/// computed by `options.threads` threads and handed to `callback` in order, while one
/// more thread reads the next slab from `reader` (which is used by one thread at a time).
/// Throws InputError for a bad range or an empty window, and whatever the reader or the
/// callback throws (the workers are joined first).
VolumeVectorSummary forEachVolumeVector(VolumeSlabReader& reader, std::uint32_t z0,
                                        std::uint32_t z1, const VolumeVectorOptions& options,
                                        const VolumeVectorCallback& callback);

}  // namespace gs::qnv
