// Mesh files from disk: PLY, OBJ and glTF (optionally gzip-compressed) read into
// qnv::TriangleMesh. The parsing is formats/mesh_readers.hpp's; this layer reads the
// file, decompresses gzip and resolves glTF external buffers.
#pragma once

#include <string>

#include "formats/mesh_readers.hpp"
#include "qnv/mesh.hpp"

namespace gs::session {

/// Reads the mesh file at `path`, choosing the reader by formats::classifyInput (content
/// first, then the extension .ply, .obj, .gltf or .glb, each optionally followed by .gz,
/// any case); gzip data are decompressed (at most 2 GiB). glTF external buffers are read
/// from the file's folder or below it only: a URI with a scheme, an absolute path, a ".."
/// component or a link leading out of the folder is refused, so that a file from
/// elsewhere cannot read arbitrary local files. Throws qnv::InputError naming the file
/// for every problem: unreadable file, not a mesh ("PATH: not a mesh file name or
/// content ..."), corrupt gzip, malformed content, missing external buffer.
qnv::TriangleMesh loadMeshFile(const std::string& path);

}  // namespace gs::session
