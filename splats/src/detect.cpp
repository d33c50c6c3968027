// Telling the splat scene formats apart (readers.hpp: detectSplatFormat) and reading any
// of them (readGaussians).
#include <algorithm>
#include <cctype>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "base/byte_order.hpp"
#include "base/gzip.hpp"
#include "gltf/detect.hpp"
#include "gltf/document.hpp"
#include "reader_support.hpp"
#include "splats/qnv_gaussians.hpp"
#include "zip_reader.hpp"

namespace gs::splats {

namespace {

bool endsWith(std::string_view name, std::string_view suffix) {
  if (name.size() < suffix.size()) return false;
  const std::string_view tail = name.substr(name.size() - suffix.size());
  return std::equal(tail.begin(), tail.end(), suffix.begin(), [](char a, char b) {
    return std::tolower(static_cast<unsigned char>(a)) == b;
  });
}

bool isNgsp(std::string_view b) {
  return b.size() >= 4 && base::loadLe<std::uint32_t>(b.data()) == 0x5053474eu;
}

/// The first non-blank character of `text` is '{' and, within its first 64 KiB, the key
/// `"means"` and (to tell SOG from other JSON) `"quats"` occur.
bool looksLikeSogMeta(std::string_view text) {
  std::size_t i = text.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  while (i < text.size() && std::isspace(static_cast<unsigned char>(text[i]))) ++i;
  if (i >= text.size() || text[i] != '{') return false;
  const std::string_view head = text.substr(0, 65536);
  return head.find("\"means\"") != std::string_view::npos &&
         head.find("\"quats\"") != std::string_view::npos;
}

/// A glTF asset (GLB or JSON) naming KHR_gaussian_splatting in its JSON.
bool gltfWithSplats(std::string_view head) {
  std::string_view json;
  if (gltf::isGlb(head)) {
    if (head.size() < 20) return false;
    const std::size_t length = base::loadLe<std::uint32_t>(head.data() + 12);
    json = head.substr(20, length);
  } else if (gltf::looksLikeGltfJson(head)) {
    json = head;
  } else {
    return false;
  }
  return json.find("\"KHR_gaussian_splatting\"") != std::string_view::npos;
}

}  // namespace

bool gltfDrawsOnlyGaussians(std::string_view head) {
  std::string_view text = head;
  if (gltf::isGlb(head)) {
    if (head.size() < 20) return false;
    const std::size_t length = base::loadLe<std::uint32_t>(head.data() + 12);
    if (length > head.size() - 20) return false;  // the JSON chunk is cut
    text = head.substr(20, length);
  }
  try {
    gltf::checkJsonDepth(text, "");
  } catch (const gltf::Error&) {
    return false;
  }
  const nlohmann::json doc = nlohmann::json::parse(text, nullptr, false);
  if (doc.is_discarded() || !doc.is_object()) return false;
  const auto meshes = doc.find("meshes");
  if (meshes == doc.end() || !meshes->is_array()) return false;
  bool any = false;
  for (const nlohmann::json& mesh : *meshes) {
    const auto primitives = mesh.is_object() ? mesh.find("primitives") : mesh.end();
    if (!mesh.is_object() || primitives == mesh.end() || !primitives->is_array()) return false;
    for (const nlohmann::json& p : *primitives) {
      const auto ext = p.is_object() ? p.find("extensions") : p.end();
      if (!p.is_object() || ext == p.end() || !ext->is_object() ||
          !ext->contains("KHR_gaussian_splatting"))
        return false;
      any = true;
    }
  }
  return any;
}

SplatFormat detectSplatFormat(std::string_view head, std::string_view name) {
  if (head.starts_with("LASF")) return SplatFormat::las;
  if (head.size() > 10 && head.starts_with("\x89QNV\r\n\x1a\n"))
    return head[10] == static_cast<char>(qnv::StreamKind::gaussian) ? SplatFormat::qnv
                                                                    : SplatFormat::unknown;
  if (head.starts_with("ply")) {
    detail::PlyHeader header;
    std::string error;
    if (!detail::parsePlyHeader(head, header, error)) return SplatFormat::unknown;
    const detail::PlyElement* vertex = header.find("vertex");
    if (!vertex) return SplatFormat::unknown;
    if (header.find("chunk") && vertex->find("packed_position") >= 0)
      return SplatFormat::compressedPly;
    for (const char* p : {"f_dc_0", "scale_0", "rot_0", "opacity"})
      if (vertex->find(p) >= 0) return SplatFormat::ply;
    return SplatFormat::unknown;
  }
  if (base::isGzip(head))
    return isNgsp(base::gunzipPrefix(head, 4)) ? SplatFormat::spz : SplatFormat::unknown;
  if (isNgsp(head)) return SplatFormat::spz;
  if (detail::ZipArchive::isZip(head)) {
    try {
      if (detail::ZipArchive(head, name).has("meta.json")) return SplatFormat::sog;
    } catch (const FormatError&) {
      // Only the start of the archive: judge by the name.
    }
    return endsWith(name, ".sog") ? SplatFormat::sog : SplatFormat::unknown;
  }
  if (gltfWithSplats(head)) return SplatFormat::gltf;
  if (looksLikeSogMeta(head)) return SplatFormat::sogMeta;
  if (endsWith(name, ".splat")) return SplatFormat::splat;
  return SplatFormat::unknown;
}

GaussianCloud readGaussians(std::string_view bytes, std::string_view name,
                            const SideFileReader& sideFiles) {
  switch (detectSplatFormat(bytes, name)) {
    case SplatFormat::ply:
      return readPlyGaussians(bytes, name);
    case SplatFormat::compressedPly:
      return readCompressedPlyGaussians(bytes, name);
    case SplatFormat::splat:
      return readSplatGaussians(bytes, name);
    case SplatFormat::spz:
      return readSpzGaussians(bytes, name);
    case SplatFormat::sog:
    case SplatFormat::sogMeta:
      return readSogGaussians(bytes, name, sideFiles);
    case SplatFormat::gltf:
      return readGltfGaussians(bytes, name, sideFiles);
    case SplatFormat::qnv:
      return readQnvGaussians(bytes, name);
    case SplatFormat::las:
      return readLasPoints(bytes, name);
    case SplatFormat::unknown:
      break;
  }
  detail::fail(name, "not a Gaussian splatting scene");
}

GaussianColumns openGaussianColumns(std::string_view head, const std::string& name,
                                    std::uint64_t fileBytes) {
  GaussianColumns found;
  if (fileBytes == 0) return found;
  if (head.starts_with("glTF") || (gltf::looksLikeGltfJson(head) && gltfWithSplats(head)))
    return openGltfColumns(head, name, fileBytes);
  if (looksLikeSogMeta(head)) return openSogColumns(head, name, fileBytes);
  // A JSON object not yet whole may still show a .gltf's "asset" or an SOG's "means" and
  // "quats" (one of at most 1 MiB).
  if (const auto at = head.find_first_not_of(" \t\r\n\xEF\xBB\xBF");
      at != std::string_view::npos && head[at] == '{') {
    found.needMore = head.size() < fileBytes && fileBytes <= kMaxColumnsJsonBytes;
    return found;
  }
  if (head.size() < 4) {
    found.needMore =
        std::string_view("NGSP").starts_with(head) || std::string_view("glTF").starts_with(head);
    return found;
  }
  return openSpzColumns(head, name, fileBytes);
}

std::unique_ptr<GaussianBatchReader> openGaussianBatches(const std::string& path,
                                                         const SideFileReader& sideFiles) {
  const std::string head = detail::PieceFile(path).head();
  switch (detectSplatFormat(head, path)) {
    case SplatFormat::ply:
      return openPlyGaussianBatches(path);
    case SplatFormat::compressedPly:
      return openCompressedPlyGaussianBatches(path);
    case SplatFormat::splat:
      return openSplatGaussianBatches(path);
    case SplatFormat::spz:
      return openSpzGaussianBatches(path);
    case SplatFormat::sog:
    case SplatFormat::sogMeta:
      return openSogGaussianBatches(path, sideFiles);
    case SplatFormat::gltf:
      return openGltfGaussianBatches(path);
    case SplatFormat::qnv:
      throw NotPiecewiseError(path + ": " + detail::kPiecewiseFormats +
                              ", not a QNV Gaussian stream");
    case SplatFormat::las:
      throw NotPiecewiseError(path + ": " + detail::kPiecewiseFormats + ", not a LAS point cloud");
    case SplatFormat::unknown:
      break;
  }
  throw NotPiecewiseError(path + ": " + detail::kPiecewiseFormats + ", not an unknown format");
}

}  // namespace gs::splats
