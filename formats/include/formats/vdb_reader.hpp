// OpenVDB sparse grids as volumes, through libopenvdb (issue 42): fog volumes as they are,
// level sets as the fog volume of their interior (OpenVDB's tools::sdfToFogVolume: 0
// outside, a ramp through the narrow band, 1 inside), so that the QNV gradient vectors of
// the volume encoder lie on the surface.
//
// Sources: the OpenVDB file format (io::Stream, format version 222+; the magic number
// 0x56444220 "VDB " as a little-endian int64 at byte 0), the grid classes of
// openvdb/Types.h (GRID_FOG_VOLUME, GRID_LEVEL_SET), a linear transform's voxel size.
//
// Safety: OpenVDB 10 allocates sizes read from a file before it reads the bytes (its
// blosc and zip readers), so every file is read by a child process
// (base/isolated_process.hpp) with its memory bounded by base::isolationMemoryFor and an
// idle time-out; what comes back is checked frame by frame. A file that makes OpenVDB
// fail, allocate too much or crash gives an InputError naming it, never a crash here.
//
// Layout: the active voxels' index bounding box, densified slice by slice (x fastest, then
// y, then z; one slab of slices per frame, read forward); voxels outside the active set
// take the grid's background. Spacing = the transform's voxel size, origin = the world
// position of the box's first voxel; rotations and non-linear (frustum) transforms are
// not applied (the grid is drawn axis-aligned at its voxel size).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "base/isolated_process.hpp"
#include "qnv/volume_slabs.hpp"

namespace gs::formats {

/// Whether `head` starts with OpenVDB's magic: bytes 20 42 44 56 00 00 00 00.
bool hasVdbMagic(std::string_view head);

/// What a VDB file's chosen grid is, beside the slab reader's grid info.
struct VdbGridSummary {
  std::string name;                // the grid's name ("density", "ls_bunny"; may be empty)
  std::string valueType;           // "float" or "double"
  bool levelSet = false;           // GRID_LEVEL_SET: read as the fog volume of its interior
  std::uint64_t activeVoxels = 0;  // active voxels, tiles counted by their voxels
  std::uint32_t grids = 0;         // grids in the file
};

/// A VolumeSlabReader over one scalar grid of a VDB file, read by a child process.
class VdbSlabReader : public qnv::VolumeSlabReader {
 public:
  /// The grid the reader chose.
  virtual const VdbGridSummary& summary() const = 0;
};

/// Opens the VDB file at `path`: its first grid of float or double values whose name is
/// `gridName` (any name when empty). The child reads the whole file (io::Stream, no
/// delayed loading) and then sends slabs forward; reading slices before the last ones
/// read starts it again. `memoryBytes` bounds the child (0: base::isolationMemoryFor the
/// file's size).
/// Throws qnv::InputError: "f.vdb: cannot open as OpenVDB (...)" with OpenVDB's message,
/// "f.vdb: no float or double grid (the file has vec3s 'v', int32 'mask')", "f.vdb:
/// grid 'density' has no active voxels", "f.vdb: the active box of grid 'density' is
/// 4096 x 4096 x 4096 voxels, more than 2^40", "f.vdb: OpenVDB ran out of its 2048 MiB of
/// memory", "f.vdb: OpenVDB ended by signal 11 (Segmentation fault)".
std::unique_ptr<VdbSlabReader> openVdb(const std::string& path, const std::string& gridName = {},
                                       std::uint64_t memoryBytes = 0);

/// openVdb over the bytes of a file in memory (`name` names it in errors), the child
/// bounded by `limits` (memoryBytes 0: base::isolationMemoryFor the bytes; idleSeconds:
/// how long the child may take to send its next frame).
std::unique_ptr<VdbSlabReader> openVdbBytes(std::string bytes, const std::string& name,
                                            const std::string& gridName = {},
                                            base::IsolationLimits limits = {0, 120});

}  // namespace gs::formats
