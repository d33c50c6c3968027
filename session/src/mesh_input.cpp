// Mesh files from disk around the parsers of formats/mesh_readers.hpp.
#include "session/mesh_input.hpp"

#include <algorithm>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>

#include "base/file.hpp"
#include "base/gzip.hpp"
#include "formats/input_kind.hpp"
#include "qnv/error.hpp"

namespace gs::session {

namespace {

constexpr std::size_t kMaxBytes = std::size_t{1} << 31;

std::string readOrThrow(const std::string& path) {
  std::string bytes, error;
  if (!base::readFile(path, bytes, error, kMaxBytes)) throw qnv::InputError(error);
  return bytes;
}

// base::gunzipIfCompressed with its GzipError turned into an InputError naming `path`.
std::string gunzip(std::string_view bytes, const std::string& path) {
  try {
    return base::gunzipIfCompressed(bytes, kMaxBytes);
  } catch (const base::GzipError& e) {
    throw qnv::InputError(path + ": " + e.what());
  }
}

// Reads the glTF external buffer `uri` of the file at `path` from the file's folder.
std::string readBuffer(const std::string& path, const std::string& uri) {
  const auto refuse = [&](const std::string& why) -> qnv::InputError {
    return qnv::InputError(path + ": external buffer '" + uri + "' " + why +
                           "; only files in the glTF file's folder are read");
  };
  const std::size_t colon = uri.find(':');
  if (colon != std::string::npos && uri.find('/') > colon) throw refuse("is not a relative file");
  const std::filesystem::path rel(uri);
  if (rel.is_absolute() || rel.has_root_path()) throw refuse("is an absolute path");
  for (const auto& part : rel)
    if (part == "..") throw refuse("leaves the folder ('..')");
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  const std::filesystem::path file = dir / rel;
  std::error_code ec;
  const auto realDir = std::filesystem::weakly_canonical(dir, ec);
  const auto realFile = ec ? realDir : std::filesystem::weakly_canonical(file, ec);
  if (!ec) {
    const auto [d, f] =
        std::mismatch(realDir.begin(), realDir.end(), realFile.begin(), realFile.end());
    if (d != realDir.end()) throw refuse("leads out of the folder through a link");
    (void)f;
  }
  std::string bytes, error;
  if (!base::readFile(file.string(), bytes, error, kMaxBytes))
    throw qnv::InputError(path + ": external buffer '" + uri + "': " + error);
  return bytes;
}

}  // namespace

qnv::TriangleMesh loadMeshFile(const std::string& path) {
  const std::string file = readOrThrow(path);
  const formats::InputKind kind = formats::classifyInput(path, file);
  if (!formats::isMesh(kind))
    throw qnv::InputError(path +
                          ": not a mesh file name or content (expected .ply, .obj, .gltf or "
                          ".glb, optionally with .gz)");
  const std::string bytes = gunzip(file, path);
  switch (kind) {
    case formats::InputKind::ply:
      return formats::readPly(bytes, path);
    case formats::InputKind::obj:
      return formats::readObj(bytes, path);
    default:
      return formats::readGltf(bytes, path,
                               [&path](const std::string& uri) -> std::optional<std::string> {
                                 return readBuffer(path, uri);
                               });
  }
}

}  // namespace gs::session
