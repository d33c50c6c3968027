// Loading glTF 2.0 assets through tinygltf with the checks tinygltf lacks: see document.hpp.
#include "gltf/document.hpp"

#include "compression.hpp"

#include "base/byte_order.hpp"

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <set>

#include <nlohmann/json.hpp>

namespace gs::gltf {
namespace {

using base::appendLe;
using base::loadLe;

// Checks the GLB container (tinygltf 2.7 bounds the BIN chunk 8 bytes too late) and
// returns the JSON chunk; `length` is set to the GLB's own length.
std::string_view checkGlb(std::string_view b, const std::string& name, std::size_t& length) {
  if (b.size() < 20) fail(name, "GLB header needs 20 bytes, got " + std::to_string(b.size()));
  const auto version = loadLe<std::uint32_t>(b.data() + 4);
  if (version != 2) fail(name, "expected GLB version 2, got " + std::to_string(version));
  length = loadLe<std::uint32_t>(b.data() + 8);
  if (length > b.size() || length < 20)
    fail(name, "GLB length " + std::to_string(length) + " does not match the " +
                   std::to_string(b.size()) + " bytes present");
  const std::size_t jsonBytes = loadLe<std::uint32_t>(b.data() + 12);
  if (loadLe<std::uint32_t>(b.data() + 16) != 0x4E4F534Au) fail(name, "GLB lacks a JSON chunk");
  if (jsonBytes > length - 20) fail(name, "GLB JSON chunk runs past the end of the file");
  const std::size_t rest = 20 + jsonBytes;
  if (rest < length) {
    if (length - rest < 8) fail(name, "GLB chunk header truncated");
    if (loadLe<std::uint32_t>(b.data() + rest) > length - rest - 8)
      fail(name, "GLB BIN chunk runs past the end of the file");
  }
  return b.substr(20, jsonBytes);
}

/// tinygltf 2.7 decodes a uri as an HTML form's value (dlib::urldecode: '+' a space, a '%'
/// without two hex digits after it a NUL), not as RFC 3986 does (glTF 2.0 section 3.6.2.1:
/// URIs per RFC 3986; base::percentDecode). The glTF JSON `json` with each buffer's and
/// image's uri (not data:) given '+' as "%2B" and such a '%' as "%25", so that tinygltf
/// decodes them as RFC 3986 does, or "" when none needed it.
std::string escapeUrisForTinygltf(std::string_view json) {
  if (json.find('+') == std::string_view::npos && json.find('%') == std::string_view::npos)
    return {};
  nlohmann::json doc = nlohmann::json::parse(json, nullptr, /*allow_exceptions=*/false);
  if (!doc.is_object()) return {};
  const auto hex = [](char c) {
    return (c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || (c >= 'A' && c <= 'F');
  };
  bool changed = false;
  for (const char* list : {"buffers", "images"}) {
    const auto items = doc.find(list);
    if (items == doc.end() || !items->is_array()) continue;
    for (nlohmann::json& item : *items) {
      if (!item.is_object() || !item.contains("uri") || !item["uri"].is_string()) continue;
      const std::string uri = item["uri"].get<std::string>();
      if (uri.starts_with("data:")) continue;
      std::string escaped;
      for (std::size_t i = 0; i < uri.size(); ++i) {
        if (uri[i] == '+')
          escaped += "%2B";
        else if (uri[i] == '%' && !(i + 2 < uri.size() && hex(uri[i + 1]) && hex(uri[i + 2])))
          escaped += "%25";
        else
          escaped += uri[i];
      }
      if (escaped != uri) {
        item["uri"] = escaped;
        changed = true;
      }
    }
  }
  return changed ? doc.dump() : std::string();
}

// ---- tinygltf callbacks: external files only through the BufferLoader ----

struct FsState {
  const BufferLoader* loader = nullptr;
  std::set<std::string> tried;
  std::map<std::string, std::string> loaded;
  std::string missing;            // the first URI that could not be loaded
  std::size_t fallbackBytes = 0;  // zero bytes served for EXT_meshopt_compression so far
  std::exception_ptr error;
};

bool isImageUri(const std::string& uri) {
  const auto dot = uri.find_last_of("./");
  if (dot == std::string::npos || uri[dot] != '.') return false;
  std::string ext = uri.substr(dot + 1);
  for (char& c : ext) c = static_cast<char>(c >= 'A' && c <= 'Z' ? c - 'A' + 'a' : c);
  return ext == "png" || ext == "jpg" || ext == "jpeg" || ext == "webp" || ext == "ktx2" ||
         ext == "ktx" || ext == "basis" || ext == "dds" || ext == "bmp" || ext == "gif" ||
         ext == "tga";
}

bool fileExists(const std::string& path, void* user) {
  auto& s = *static_cast<FsState*>(user);
  if (path.empty() || isImageUri(path) || s.error) return false;  // images are not needed
  if (s.loaded.count(path)) return true;
  if (const auto zeros = detail::meshoptFallbackBytes(path)) {  // decoded into after loading
    if (*zeros > detail::maxMeshoptFallbackBytes() - s.fallbackBytes) return false;
    s.fallbackBytes += *zeros;
    s.loaded.emplace(path, std::string(*zeros, '\0'));
    return true;
  }
  // tinygltf tries the URI, then "./" + URI: ask the loader once.
  if (path.starts_with("./") && s.tried.count(path.substr(2))) return false;
  if (!s.tried.insert(path).second) return false;
  std::optional<std::string> bytes;
  if (*s.loader) {
    try {
      bytes = (*s.loader)(path);
    } catch (...) {
      s.error = std::current_exception();
      return false;
    }
  }
  if (!bytes) {
    if (s.missing.empty()) s.missing = path;
    return false;
  }
  s.loaded.emplace(path, std::move(*bytes));
  return true;
}

std::string expandFilePath(const std::string& path, void*) {
  return path;
}

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path,
                   void* user) {
  auto& s = *static_cast<FsState*>(user);
  const auto it = s.loaded.find(path);
  if (it == s.loaded.end()) {
    if (err) *err = "not available";
    return false;
  }
  out->assign(it->second.begin(), it->second.end());
  s.loaded.erase(it);
  return true;
}

bool writeWholeFile(std::string* err, const std::string&, const std::vector<unsigned char>&,
                    void*) {
  if (err) *err = "writing is not allowed";
  return false;
}

bool skipImage(tinygltf::Image*, const int, std::string*, std::string*, int, int,
               const unsigned char*, int, void*) {
  return true;  // images are not decoded
}

// Images::keepEncoded: the bytes of a data: URI or GLB bufferView image, undecoded.
bool keepImage(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
               const unsigned char* bytes, int size, void*) {
  image->image.assign(bytes, bytes + std::max(size, 0));
  image->width = -1;
  image->height = -1;
  return true;
}

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "tinygltf could not read the file" : line;
}

}  // namespace

constexpr int kMaxJsonDepth = 64;

void checkJsonDepth(std::string_view json, const std::string& name) {
  int depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (inString) {
      if (c == '\\')
        ++i;
      else if (c == '"')
        inString = false;
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonDepth)
        fail(name, "JSON nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void fail(const std::string& name, const std::string& what) {
  throw Error(name + ": " + what);
}

std::vector<int> sceneRoots(const tinygltf::Model& m) {
  if (m.defaultScene >= 0 && static_cast<std::size_t>(m.defaultScene) < m.scenes.size())
    return m.scenes[static_cast<std::size_t>(m.defaultScene)].nodes;
  if (!m.scenes.empty()) return m.scenes[0].nodes;
  std::vector<char> isChild(m.nodes.size(), 0);
  for (const auto& n : m.nodes)
    for (int c : n.children)
      if (c >= 0 && static_cast<std::size_t>(c) < isChild.size())
        isChild[static_cast<std::size_t>(c)] = 1;
  std::vector<int> roots;
  for (std::size_t i = 0; i < m.nodes.size(); ++i)
    if (!isChild[i]) roots.push_back(static_cast<int>(i));
  return roots;
}

bool isGlb(std::string_view bytes) {
  return bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
}

bool looksLikeGltfJson(std::string_view bytes) {
  std::size_t i = bytes.starts_with("\xEF\xBB\xBF") ? 3 : 0;
  auto skipSpace = [&] {
    while (i < bytes.size() &&
           (bytes[i] == ' ' || bytes[i] == '\t' || bytes[i] == '\n' || bytes[i] == '\r'))
      ++i;
  };
  skipSpace();
  if (i >= bytes.size() || bytes[i] != '{') return false;
  ++i;
  skipSpace();
  if (bytes.substr(i).starts_with("\"X3D\"")) return false;
  return bytes.find("\"asset\"") != std::string_view::npos;
}

tinygltf::Model load(std::string_view bytes, const std::string& name, const BufferLoader& loader,
                     Images images, std::vector<std::string>* warnings) {
  if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
    fail(name, "glTF input larger than 4 GiB");
  const bool glb = isGlb(bytes);
  std::size_t length = bytes.size();
  const std::string_view json = glb ? checkGlb(bytes, name, length) : bytes;
  checkJsonDepth(json, name);
  // Draco primitives' accessors get placeholder buffer views (compression.hpp); a GLB is
  // rebuilt around the patched JSON chunk.
  std::string patched = detail::placeDracoAccessors(json);
  // EXT_meshopt_compression's fallback buffers get a uri load() serves as zeros.
  if (std::string more = detail::placeMeshoptFallbacks(patched.empty() ? json : patched);
      !more.empty())
    patched = std::move(more);
  // Buffer and image uris decoded as RFC 3986 says, not as tinygltf would.
  if (std::string more = escapeUrisForTinygltf(patched.empty() ? json : patched); !more.empty())
    patched = std::move(more);
  if (!patched.empty()) {
    while (patched.size() % 4 != 0) patched += ' ';
    if (glb) {
      const std::string_view rest = bytes.substr(20 + json.size(), length - 20 - json.size());
      std::string rebuilt(bytes.substr(0, 8));  // magic and version
      appendLe<std::uint32_t>(rebuilt,
                              static_cast<std::uint32_t>(20 + patched.size() + rest.size()));
      appendLe<std::uint32_t>(rebuilt, static_cast<std::uint32_t>(patched.size()));
      appendLe<std::uint32_t>(rebuilt, 0x4E4F534Au);  // "JSON"
      patched = rebuilt + patched + std::string(rest);
    }
    bytes = patched;
    length = bytes.size();
  }

  FsState state;
  state.loader = &loader;
  tinygltf::TinyGLTF ctx;
  ctx.SetImageLoader(images == Images::keepEncoded ? &keepImage : &skipImage, nullptr);
  ctx.SetFsCallbacks({&fileExists, &expandFilePath, &readWholeFile, &writeWholeFile, &state});
  tinygltf::Model model;
  std::string err, warn;
  bool ok = false;
  try {
    const auto n = static_cast<unsigned int>(length);
    if (glb)
      ok = ctx.LoadBinaryFromMemory(&model, &err, &warn,
                                    reinterpret_cast<const unsigned char*>(bytes.data()), n, "");
    else
      ok = ctx.LoadASCIIFromString(&model, &err, &warn, bytes.data(), n, "");
  } catch (const std::exception& e) {
    if (state.error) std::rethrow_exception(state.error);
    fail(name, std::string("tinygltf: ") + e.what());
  }
  if (state.error) std::rethrow_exception(state.error);
  if (!ok) {
    if (!state.missing.empty())
      fail(name, "cannot load external buffer '" + state.missing + "'" +
                     (loader ? "" : " (no resource loader: external files are not allowed)"));
    fail(name, firstLine(err));
  }
  if (warnings != nullptr) {
    std::size_t at = 0;
    while (at < warn.size()) {
      const std::size_t eol = warn.find('\n', at);
      const std::string line = warn.substr(at, eol == std::string::npos ? eol : eol - at);
      // Images are never read here (the renderer fetches them by URL): not a problem.
      const bool imageNotRead = line.starts_with("File not found") ||
                                line.starts_with("Failed to load external 'uri' for image");
      if (!line.empty() && !imageNotRead) warnings->push_back(line);
      if (eol == std::string::npos) break;
      at = eol + 1;
    }
  }
  detail::decodeMeshopt(model, name);
  detail::decodeDraco(model, name);
  return model;
}

namespace detail {

void replaceAccessorData(tinygltf::Model& m, tinygltf::Accessor& a, int componentType,
                         std::size_t count, const void* data, std::size_t bytes) {
  tinygltf::Buffer buffer;
  buffer.data.assign(static_cast<const unsigned char*>(data),
                     static_cast<const unsigned char*>(data) + bytes);
  m.buffers.push_back(std::move(buffer));
  tinygltf::BufferView view;
  view.buffer = static_cast<int>(m.buffers.size() - 1);
  view.byteOffset = 0;
  view.byteLength = bytes;
  view.byteStride = 0;
  m.bufferViews.push_back(std::move(view));
  a.bufferView = static_cast<int>(m.bufferViews.size() - 1);
  a.byteOffset = 0;
  a.componentType = componentType;
  a.normalized = false;
  a.count = count;
  a.sparse.isSparse = false;
}

}  // namespace detail

}  // namespace gs::gltf
