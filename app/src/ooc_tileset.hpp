// `ghostspace encode VOLUME|MESH.ply --tileset OUT/ --memory MB [--threads N] [--bricks I/N]`:
// the out-of-core tileset encode of a volume or a mesh (docs/out-of-core.md, "Tileset encoding").
// Private to app/src.
#pragma once

#include <string>

#include "app/options.hpp"
#include "qnv/encoder.hpp"
#include "qnv/volume_slabs.hpp"

namespace gs::app {

/// Encodes the volume `reader` reads into the tileset options.encode.tileset names, slab
/// by slab: the selection passes (qnv::planVolumeSelection), then the vector pass over
/// the slices of this share's leaf rows, leaf bricks written as their row completes,
/// leaf vectors and interior contributions spilled to the share's part folder when they
/// outgrow options.encode.memoryMB. The files are those of the in-memory encode
/// (writeTileset) byte for byte. Prints the sizes and times; returns the exit code
/// (0, 1 on a read or write error, 2 on bad options).
int writeVolumeTilesetOutOfCore(const Options& options, qnv::VolumeSlabReader& reader,
                                const qnv::VolumeEncodeOptions& encode,
                                const qnv::WriteOptions& write, const std::string& input);

/// The same for the triangles of the PLY file `input` (ooc_mesh.cpp), read with
/// formats::streamPly: its vertices and triangles are copied to the share's part folder
/// (16 bytes each), the selection passes (qnv::planSurfaceSelection) and the vector pass
/// read them back, vertices through a cache of a quarter of --memory, and each kept
/// triangle's vector goes to the leaf of its centroid. The files are those of the
/// in-memory encode byte for byte. Same exit codes.
int writeMeshTilesetOutOfCore(const Options& options, const std::string& input,
                              const qnv::SurfaceEncodeOptions& encode,
                              const qnv::WriteOptions& write);

}  // namespace gs::app
