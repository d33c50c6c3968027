// Readers for triangle mesh files: PLY, Wavefront OBJ and glTF 2.0 (JSON or GLB).
// They read bytes already in memory (streamPly reads a PLY file piece by piece), are safe for
// untrusted input and report malformed input with InputError. Positions are the file's own units,
// unscaled.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <string_view>

#include "qnv/error.hpp"
#include "qnv/mesh.hpp"

namespace gs::formats {

// The readers produce the surface encoder's input type and throw the codec's error type,
// so that a mesh read here goes to qnv::encodeSurface as it is.
using qnv::InputError;
using qnv::Rgba8;
using qnv::TriangleMesh;

/// Reads a PLY 1.0 file (format ascii, binary_little_endian or binary_big_endian).
///
/// Accepted: an element "vertex" with properties x, y, z of any scalar type (char, uchar,
/// short, ushort, int, uint, float, double or their int8..float64 aliases) and optionally
/// red, green, blue[, alpha] (also diffuse_red...; integer types are 0..255 and clamped to
/// it, float types are 0..1; used only when all of red, green and blue are there) which
/// become vertexColors; an element "face" with a list property "vertex_indices" or
/// "vertex_index" (any integer count and index types) and optionally red, green,
/// blue[, alpha] which become faceColors. Polygons with more than 3 vertices
/// are fan-triangulated (v0 v1 v2, v0 v2 v3, ...); degenerate triangles are kept. Other
/// elements and properties, lists included, are skipped; comment and obj_info lines are
/// ignored; bytes after the last element are ignored. `name` names the input in messages.
///
/// Throws InputError on malformed input: "name:LINE: expected X, got Y" for the header and
/// ascii bodies (1-based lines), "name: ..." for binary bodies. Among the errors: faces
/// with fewer than 3 vertices, vertex indices that are negative or not below the vertex
/// count, NaN or infinite coordinates, a missing vertex x/y/z or face index list, more
/// than 2^32 - 1 vertices, data ending early, and counts that the remaining bytes cannot
/// hold (checked before anything is allocated for them).
TriangleMesh readPly(std::string_view bytes, const std::string& name);

/// What streamPly found in a PLY header, before the body.
struct PlyLayout {
  std::uint64_t vertexCount = 0;  // declared count of element "vertex"
  std::uint64_t faceCount = 0;    // declared count of element "face" (polygons, not triangles)
  bool vertexColors = false;      // the vertex element has red, green and blue
  bool faceColors = false;        // the face element has red, green and blue
};

/// Receives a PLY file's vertices and triangles in file order from streamPly.
class PlySink {
 public:
  virtual ~PlySink() = default;
  /// Called once, after the header and before the first vertex or triangle.
  virtual void begin(const PlyLayout& layout) = 0;
  /// One vertex (finite coordinates); `color` is its colour when layout.vertexColors,
  /// else opaque black.
  virtual void vertex(const glm::vec3& position, Rgba8 color) = 0;
  /// One triangle of a face (faces fan-triangulated as readPly does): vertex indices below
  /// layout.vertexCount; `color` is the face's colour when layout.faceColors, else opaque
  /// black. Triangles arrive in readPly's order, so the n-th call is readPly's triangle n.
  virtual void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, Rgba8 color) = 0;
};

/// readPly on the file at `path` without holding it: the file is read forward in 1 MiB
/// pieces (the header, up to 16 MiB, whole) and everything readPly would store goes to
/// `sink` instead, so memory does not grow with the file. The same rules and the same
/// errors as readPly (named by `path`), plus InputError for a file that cannot be opened
/// or read, and for a gzip-compressed file ("gunzip it first"). Exceptions `sink` throws
/// pass through.
/// `chunkBytes` (>= 1) is the piece size, small only in tests.
void streamPly(const std::string& path, PlySink& sink,
               std::size_t chunkBytes = std::size_t{1} << 20);

/// Reads a Wavefront OBJ file.
///
/// Accepted: "v x y z" (also "v x y z w", w ignored), "v x y z r g b" and
/// "v x y z r g b a" (the common vertex-colour extension, 0..1, which become vertexColors;
/// vertices without a colour then take baseColor); "f" with vertex references "i",
/// "i/t", "i//n" or "i/t/n" where i is 1-based or negative (relative to the vertices read
/// so far); polygons fan-triangulated. Every other statement (vt, vn, g, o, s, usemtl,
/// mtllib, l, p, ...) and "#" comments are ignored. `name` names the input in messages.
///
/// Throws InputError "name:LINE: expected X, got Y" (1-based lines) on malformed
/// numbers, NaN or infinite coordinates, faces with fewer than 3 vertices, index 0 and
/// indices out of range (positive indices may refer to vertices defined later).
TriangleMesh readObj(std::string_view bytes, const std::string& name);

/// Supplies the bytes behind a glTF external buffer URI (as written in the file, with
/// %-escapes decoded), or std::nullopt when it cannot. An exception it throws propagates
/// out of readGltf unchanged.
using ResourceLoader = std::function<std::optional<std::string>(const std::string& uri)>;

/// Reads a glTF 2.0 asset: JSON text, or GLB (detected by the "glTF" magic), through
/// tinygltf.
///
/// Buffers may be GLB's BIN chunk, data: URIs, or external URIs, which are resolved only
/// through `loader` (never the file system directly); with an empty loader, or when it
/// returns std::nullopt or bytes of the wrong length, an external buffer is an InputError
/// naming the URI. No image is decoded, and image URIs with an image file extension
/// (.png, .jpg, .jpeg, .webp, .ktx2, ...) are not even requested from the loader.
///
/// The default scene is walked (else scene 0, else every root node) with node matrices
/// or translation/rotation/scale applied, so positions are world positions; a node
/// mirrored by a negative determinant has its triangles' winding flipped. Primitives of
/// mode TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN are read (other modes are skipped):
/// POSITION must be float VEC3, indices u8/u16/u32 or absent, COLOR_0 (float or
/// normalized u8/u16, VEC3 or VEC4) becomes vertexColors multiplied by the material's
/// pbrMetallicRoughness.baseColorFactor (primitives without COLOR_0 then give their
/// vertices the material colour). Without COLOR_0 anywhere, a common material colour
/// becomes baseColor and differing ones per-triangle faceColors. A primitive without a
/// material has glTF's default material, white.
///
/// Throws InputError "name: ..." on malformed input: JSON errors, GLB chunk errors,
/// accessors, buffer views or indices out of bounds, unsupported accessor types, sparse
/// accessors, node cycles, JSON nested deeper than 64 levels, and results over 2^27
/// vertices or triangles (instancing can multiply a small file).
TriangleMesh readGltf(std::string_view bytes, const std::string& name,
                      const ResourceLoader& loader = {});

}  // namespace gs::formats
