// Mesh files from disk: PLY, OBJ and glTF (optionally gzip-compressed) read into
// qnv::TriangleMesh. The parsing is qnv's (qnv/mesh_readers.hpp); this layer reads the
// file, decompresses gzip and resolves glTF external buffers.
#pragma once

#include <string>

#include "qnv/mesh.hpp"
#include "qnv/mesh_readers.hpp"

namespace gs::app {

/// True when `path` ends with .ply, .obj, .gltf or .glb, each optionally followed by .gz
/// (any case).
bool isMeshFile(const std::string& path);

/// Reads the mesh file at `path`, choosing the reader by extension (see isMeshFile);
/// gzip data are decompressed (at most 2 GiB). glTF external buffers are read from the
/// file's folder or below it only: a URI with a scheme, an absolute path, a ".."
/// component or a link leading out of the folder is refused, so that a file from
/// elsewhere cannot read arbitrary local files. Throws qnv::InputError naming the file
/// for every problem: unknown extension, unreadable file, corrupt gzip, malformed
/// content, missing external buffer.
qnv::TriangleMesh loadMeshFile(const std::string& path);

}  // namespace gs::app
