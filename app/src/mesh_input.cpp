// Mesh files from disk around the parsers of qnv/mesh_readers.hpp.
#include "app/mesh_input.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <optional>
#include <string_view>
#include <system_error>

#include "net/file_source.hpp"
#include "qnv/error.hpp"
#include "vrml/diagnostic.hpp"
#include "vrml/parser.hpp"

namespace gs::app {

namespace {

constexpr std::size_t kMaxBytes = std::size_t{1} << 31;

enum class Kind { kNone, kPly, kObj, kGltf };

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

Kind kindOf(const std::string& path) {
  std::string low = lower(path);
  std::string_view l = low;
  if (l.ends_with(".gz")) l.remove_suffix(3);
  if (l.ends_with(".ply")) return Kind::kPly;
  if (l.ends_with(".obj")) return Kind::kObj;
  if (l.ends_with(".gltf") || l.ends_with(".glb")) return Kind::kGltf;
  return Kind::kNone;
}

std::string readOrThrow(const std::string& path) {
  std::string bytes, error;
  if (!net::readFile(path, bytes, error, kMaxBytes)) throw qnv::InputError(error);
  return bytes;
}

// gunzipIfCompressed with its ParseError turned into an InputError naming `path`.
std::string gunzip(std::string_view bytes, const std::string& path) {
  try {
    return vrml::gunzipIfCompressed(bytes, path, kMaxBytes);
  } catch (const vrml::ParseError& e) {
    throw qnv::InputError(path + ": " + e.diagnostic.message);
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
  if (!net::readFile(file.string(), bytes, error, kMaxBytes))
    throw qnv::InputError(path + ": external buffer '" + uri + "': " + error);
  return bytes;
}

}  // namespace

bool isMeshFile(const std::string& path) {
  return kindOf(path) != Kind::kNone;
}

qnv::TriangleMesh loadMeshFile(const std::string& path) {
  const Kind kind = kindOf(path);
  if (kind == Kind::kNone)
    throw qnv::InputError(path +
                          ": not a mesh file name (expected .ply, .obj, .gltf or .glb, "
                          "optionally with .gz)");
  const std::string bytes = gunzip(readOrThrow(path), path);
  switch (kind) {
    case Kind::kPly:
      return qnv::readPly(bytes, path);
    case Kind::kObj:
      return qnv::readObj(bytes, path);
    default:
      return qnv::readGltf(bytes, path,
                           [&path](const std::string& uri) -> std::optional<std::string> {
                             return readBuffer(path, uri);
                           });
  }
}

}  // namespace gs::app
