#include "session/splat_inputs.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "base/byte_order.hpp"
#include "base/fetch.hpp"
#include "base/file.hpp"

#include "base/url.hpp"
#include "formats/input_kind.hpp"
#include "qnv/encoder.hpp"
#include "qnv/error.hpp"
#include "session/mesh_input.hpp"
#include "session/volume_input.hpp"
#include "splats/lod_tree.hpp"
#include "splats/readers.hpp"

namespace gs::session {

namespace {

/// The bytes of the glTF asset at `path` that say what it holds: a GLB's header and JSON
/// chunk, or a JSON text, at most 64 MiB; empty when it cannot be read.
std::string gltfHead(const std::string& path) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  const std::size_t kMax =
      ec ? 0 : static_cast<std::size_t>(std::min<std::uintmax_t>(size, std::uintmax_t{64} << 20));
  std::ifstream in(path, std::ios::binary);
  std::string head(20, '\0');
  in.read(head.data(), 20);
  head.resize(static_cast<std::size_t>(in.gcount()));
  std::size_t want = kMax;
  if (head.size() == 20 && head.starts_with("glTF"))
    want = std::min<std::size_t>(kMax,
                                 20 + std::size_t{base::loadLe<std::uint32_t>(head.data() + 12)});
  if (head.size() < want && in) {
    const std::size_t have = head.size();
    head.resize(want);
    in.read(head.data() + have, static_cast<std::streamsize>(want - have));
    head.resize(have + static_cast<std::size_t>(in.gcount()));
  }
  return head;
}

/// Whether the glTF at `path` draws Gaussian splats alone (parsed only when its JSON names
/// the extension).
bool isGaussianOnlyGltf(const std::string& path) {
  const std::string head = gltfHead(path);
  return head.find("KHR_gaussian_splatting") != std::string::npos &&
         splats::gltfDrawsOnlyGaussians(head);
}

}  // namespace

bool isSplatInput(const std::string& path) {
  const formats::InputKind kind = formats::classifyFile(path);
  return formats::isSplatKind(kind) || !tilesetIndexOf(path).empty() ||
         (kind == formats::InputKind::gltf && isGaussianOnlyGltf(path));
}

std::string tilesetIndexOf(const std::string& input) {
  if (base::isHttpUrl(input)) {
    const std::string_view bare = base::withoutQueryOrFragment(input);
    if (!bare.empty() && bare.back() == '/') return std::string(bare) + "index.qnvt";
    return formats::kindFromName(input) == formats::InputKind::qnvTileset ? input : "";
  }
  const std::string path = base::localPathOfUrl(input);
  if (path.empty()) return "";
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    // A folder is a tileset when it holds an index (classifyFile alone would take the
    // missing file's name for one: a DICOM series folder is not a tileset).
    const std::string index = (std::filesystem::path(path) / "index.qnvt").string();
    return std::filesystem::is_regular_file(index, ec) &&
                   formats::classifyFile(index) == formats::InputKind::qnvTileset
               ? index
               : "";
  }
  return formats::classifyFile(path) == formats::InputKind::qnvTileset ? input : "";
}

std::string splatWorldText(const std::string& path) {
  std::string escaped;
  for (char c : path) {
    if (c == '"' || c == '\\') escaped.push_back('\\');
    escaped.push_back(c);
  }
  return "#VRML V2.0 utf8\n# " + std::string("A QNV world made by ghostspace for one file.\n") +
         "NavigationInfo { type [\"EXAMINE\", \"ANY\"] }\n" + "QuantizedNormalVectors { url \"" +
         escaped + "\" }\n";
}

namespace {

void appendFloat(std::string& out, float v) {
  char buffer[32];
  const int n = std::snprintf(buffer, sizeof buffer, "%.9g ", static_cast<double>(v));
  out.append(buffer, static_cast<std::size_t>(n));
}

std::string meshWorldText(const qnv::TriangleMesh& mesh) {
  std::string out = "#VRML V2.0 utf8\n# A mesh file opened by ghostspace.\n";
  out += "NavigationInfo { type [\"EXAMINE\", \"ANY\"] }\nShape {\n";
  const glm::vec3 base = glm::vec3(mesh.baseColor) / 255.0f;
  out += "  appearance Appearance { material Material { diffuseColor ";
  for (int i = 0; i < 3; ++i) appendFloat(out, base[i]);
  out +=
      "} }\n  geometry IndexedFaceSet {\n    solid FALSE creaseAngle 0.5\n    coord Coordinate { "
      "point [\n";
  for (const glm::vec3& p : mesh.positions) {
    for (int i = 0; i < 3; ++i) appendFloat(out, p[i]);
    out += ",\n";
  }
  out += "    ] }\n";
  if (!mesh.vertexColors.empty()) {
    out += "    color Color { color [\n";
    for (const qnv::Rgba8& c : mesh.vertexColors) {
      for (int i = 0; i < 3; ++i) appendFloat(out, static_cast<float>(c[i]) / 255.0f);
      out += ",\n";
    }
    out += "    ] }\n";
  }
  out += "    coordIndex [\n";
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    out += std::to_string(mesh.indices[t]) + " " + std::to_string(mesh.indices[t + 1]) + " " +
           std::to_string(mesh.indices[t + 2]) + " -1\n";
  out += "    ]\n  }\n}\n";
  return out;
}

}  // namespace

bool isGaussianQnvFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[11] = {};
  return in.read(head, sizeof head) &&
         splats::detectSplatFormat(std::string_view(head, sizeof head), path) ==
             splats::SplatFormat::qnv;
}

bool isGaussianTilesetIndex(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char head[27] = {};  // the template header's kind: byte 10 of the header at byte 16
  return in.read(head, sizeof head) && head[0] == '\x89' && head[1] == 'Q' && head[2] == 'N' &&
         head[3] == 'T' && head[26] == static_cast<char>(qnv::StreamKind::gaussian);
}

std::string gaussianWorldText(const std::string& path, bool turned) {
  std::string escaped;
  for (char c : path) {
    if (c == '"' || c == '\\') escaped.push_back('\\');
    escaped.push_back(c);
  }
  // The captures' axes are y-down (docs/splats.md, "Axes"): turned 180 degrees about Z,
  // as SuperSplat and Spark show them.
  return "#VRML V2.0 utf8\n# A 3D Gaussian splatting scene opened by ghostspace.\n"
         "NavigationInfo { type [\"EXAMINE\", \"ANY\"] }\n"
         "Transform { rotation 0 0 1 " +
         std::string(turned ? "3.14159265" : "0") + "\n  children QuantizedNormalVectors { url \"" +
         escaped + "\" }\n}\n";
}

bool isGaussianSplatFile(const std::string& path) {
  const formats::InputKind kind = formats::classifyFile(path);
  if (kind == formats::InputKind::gaussianSplats) return true;
  if (kind == formats::InputKind::qnv) return isGaussianQnvFile(path);
  if (kind != formats::InputKind::gltf) return false;
  return splats::detectSplatFormat(gltfHead(path), path) == splats::SplatFormat::gltf;
}

std::pair<std::shared_ptr<const splats::LodTree>, std::string> buildTreeOf(
    std::shared_ptr<const splats::GaussianCloud> cloud, std::shared_ptr<std::atomic<bool>> cancel,
    const std::string& url) {
  try {
    splats::LodTreeOptions options;
    options.cancel = cancel.get();
    return {std::make_shared<const splats::LodTree>(splats::buildLodTree(*cloud, options)), {}};
  } catch (const splats::LodTreeCancelled&) {
    return {};
  } catch (const std::exception& e) {
    return {nullptr, url + ": no level-of-detail tree for its " + std::to_string(cloud->size()) +
                         " splats (" + e.what() + ")"};
  }
}

std::shared_ptr<const render::SplatSet> gaussianSet(const std::string& bytes,
                                                    const std::string& name,
                                                    const splats::SideFileReader& sideFiles,
                                                    std::string& error) {
  try {
    auto set = std::make_shared<render::SplatSet>();
    set->gaussians = std::make_shared<const splats::GaussianCloud>(
        splats::sortByImportance(splats::readGaussians(bytes, name, sideFiles)));
    set->lodTree = std::make_shared<const splats::LodTree>(splats::buildLodTree(*set->gaussians));
    set->computeBounds();
    return set;
  } catch (const splats::FormatError& e) {
    error = e.what();
  } catch (const std::bad_alloc&) {
    error = name + ": out of memory";
  }
  return nullptr;
}

std::shared_ptr<const render::SplatSet> loadGaussianFile(const std::string& path,
                                                         std::string& error) {
  std::string bytes;
  if (!base::readFile(path, bytes, error, std::size_t{16} << 30)) return nullptr;
  base::LocalFetcher fetcher;
  return gaussianSet(bytes, path, sideFileReader(fetcher, path), error);
}

std::string sideFileUrl(const std::string& sceneUrl, const std::string& relative,
                        std::string& why) {
  if (!splats::isFileBesideScene(relative)) {
    why = relative + ": not a file beside the scene";
    return {};
  }
  // A URL names the file by its path percent-encoded (a space as %20); a local path as is.
  return base::resolveUrl(sceneUrl,
                          base::hasScheme(sceneUrl) ? base::percentEncodePath(relative) : relative);
}

splats::SideFileReader sideFileReader(base::Fetcher& fetcher, const std::string& sceneUrl) {
  return [&fetcher, sceneUrl](const std::string& relative, std::string& out, std::string& why) {
    const std::string url = sideFileUrl(sceneUrl, relative, why);
    if (url.empty()) return false;
    base::Fetched f = fetcher.fetch(url, sceneUrl, base::FetchMode::whole);
    if (!f.ready()) {
      why = f.error;
      return false;
    }
    out = std::move(f.bytes);
    return true;
  };
}

std::string worldTextFor(const std::string& path) {
  if (isGaussianSplatFile(path)) {
    // A LAS point cloud is z up already: not turned as a capture is.
    std::ifstream in(path, std::ios::binary);
    char magic[4] = {};
    const bool las = in.read(magic, 4) && std::string_view(magic, 4) == "LASF";
    return gaussianWorldText(std::filesystem::path(path).filename().string(), !las);
  }
  if (formats::isMesh(formats::classifyFile(path))) return meshWorldText(loadMeshFile(path));
  return splatWorldText(std::filesystem::path(path).filename().string());  // resolves to itself
}

render::SplatLoader splatLoader() {
  return [](const std::string& url, const std::string&,
            std::string& error) -> std::shared_ptr<const render::SplatSet> {
    const std::string path = base::localPathOfUrl(url);
    if (path.empty()) {
      error = "cannot read " + url + ": only local files are supported here";
      return nullptr;
    }
    if (isGaussianSplatFile(path)) return loadGaussianFile(path, error);
    try {
      const formats::InputKind kind = formats::classifyFile(path);
      if (formats::isVolume(kind))
        return render::splatSetFromEncoded(qnv::encodeVolume(loadVolumeFile(path), {}));
      if (formats::isMesh(kind))
        return render::splatSetFromEncoded(qnv::encodeSurface(loadMeshFile(path), {}));
    } catch (const qnv::InputError& e) {
      error = e.what();
      return nullptr;
    }
    return render::loadQnvFile(path, error);
  };
}

}  // namespace gs::session
