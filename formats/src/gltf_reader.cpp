// glTF 2.0 reader (JSON or GLB) on top of Debian's shared tinygltf: see mesh_readers.hpp.
// tinygltf parses; this file checks everything it then reads (GLB chunks, accessors,
// buffer views, indices, the node graph) so that a hostile file cannot make it read out of
// bounds, recurse without limit or allocate more than the input justifies.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>
#include <glm/mat4x4.hpp>
#include <glm/matrix.hpp>

#include <tiny_gltf.h>

#include "base/byte_order.hpp"
#include "formats/mesh_readers.hpp"

namespace gs::formats {
namespace {

using base::loadFloatLe;
using base::loadLe;

constexpr std::size_t kMaxOutput = std::size_t{1} << 27;  // vertices and triangles
constexpr int kMaxJsonDepth = 64;

[[noreturn]] void fail(const std::string& name, const std::string& what) {
  throw InputError(name + ": " + what);
}

// tinygltf recurses into "extras" and "extensions" without a depth limit: refuse deep JSON.
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

// ---- tinygltf callbacks: external files only through the ResourceLoader ----

struct FsState {
  const ResourceLoader* loader = nullptr;
  std::set<std::string> tried;
  std::map<std::string, std::string> loaded;
  std::string missing;  // the first URI that could not be loaded
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

// ---- the model walk ----

Rgba8 toRgba8(const std::vector<double>& c) {
  Rgba8 out{255, 255, 255, 255};
  for (std::size_t i = 0; i < 4 && i < c.size(); ++i) {
    const double v = c[i] * 255.0;
    out[static_cast<int>(i)] = !(v > 0.0)   ? 0
                               : v >= 255.0 ? 255
                                            : static_cast<std::uint8_t>(std::lround(v));
  }
  return out;
}

// One accessor's elements, bounds checked.
struct View {
  const unsigned char* data = nullptr;
  std::size_t count = 0, stride = 0;
  int componentType = 0, components = 0;

  const char* at(std::size_t i, int c) const {
    return reinterpret_cast<const char*>(data + i * stride) +
           c * tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(componentType));
  }
  float unorm(std::size_t i, int c) const {  // float, or unsigned normalized
    const char* p = at(i, c);
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return static_cast<float>(static_cast<std::uint8_t>(*p)) / 255.0f;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return static_cast<float>(loadLe<std::uint16_t>(p)) / 65535.0f;
      default:
        return loadFloatLe(p);
    }
  }
  std::uint32_t index(std::size_t i) const {
    const char* p = at(i, 0);
    switch (componentType) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE:
        return static_cast<std::uint8_t>(*p);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT:
        return loadLe<std::uint16_t>(p);
      default:
        return loadLe<std::uint32_t>(p);
    }
  }
};

class Walker {
 public:
  Walker(const tinygltf::Model& model, const std::string& name) : m_(model), name_(name) {}

  TriangleMesh run() {
    std::vector<int> roots;
    if (m_.defaultScene >= 0 && static_cast<std::size_t>(m_.defaultScene) < m_.scenes.size())
      roots = m_.scenes[static_cast<std::size_t>(m_.defaultScene)].nodes;
    else if (!m_.scenes.empty())
      roots = m_.scenes[0].nodes;
    else {
      std::vector<char> isChild(m_.nodes.size(), 0);
      for (const auto& n : m_.nodes)
        for (int c : n.children)
          if (c >= 0 && static_cast<std::size_t>(c) < isChild.size())
            isChild[static_cast<std::size_t>(c)] = 1;
      for (std::size_t i = 0; i < m_.nodes.size(); ++i)
        if (!isChild[i]) roots.push_back(static_cast<int>(i));
    }
    std::vector<char> visited(m_.nodes.size(), 0);
    std::vector<std::pair<int, glm::dmat4>> stack;
    for (auto it = roots.rbegin(); it != roots.rend(); ++it)
      stack.emplace_back(*it, glm::dmat4(1.0));
    while (!stack.empty()) {
      const auto [index, parent] = stack.back();
      stack.pop_back();
      if (index < 0 || static_cast<std::size_t>(index) >= m_.nodes.size())
        fail(name_, "node " + std::to_string(index) + " does not exist");
      if (visited[static_cast<std::size_t>(index)]++)
        fail(name_, "node " + std::to_string(index) + " is reached twice (not a tree)");
      const tinygltf::Node& node = m_.nodes[static_cast<std::size_t>(index)];
      const glm::dmat4 world = parent * local(node, index);
      if (node.mesh >= 0) {
        if (static_cast<std::size_t>(node.mesh) >= m_.meshes.size())
          fail(name_, "node " + std::to_string(index) + " uses mesh " + std::to_string(node.mesh) +
                          ", which does not exist");
        for (const auto& prim : m_.meshes[static_cast<std::size_t>(node.mesh)].primitives)
          primitive(prim, world);
      }
      for (auto it = node.children.rbegin(); it != node.children.rend(); ++it)
        stack.emplace_back(*it, world);
    }
    return finish();
  }

 private:
  glm::dmat4 local(const tinygltf::Node& n, int index) const {
    const std::string where = "node " + std::to_string(index) + ": ";
    if (!n.matrix.empty()) {
      if (n.matrix.size() != 16) fail(name_, where + "a matrix needs 16 numbers");
      return glm::make_mat4(n.matrix.data());  // both column-major
    }
    glm::dmat4 t(1.0), r(1.0), s(1.0);
    if (!n.translation.empty()) {
      if (n.translation.size() != 3) fail(name_, where + "a translation needs 3 numbers");
      t[3] = glm::dvec4(n.translation[0], n.translation[1], n.translation[2], 1.0);
    }
    if (!n.rotation.empty()) {
      if (n.rotation.size() != 4) fail(name_, where + "a rotation needs 4 numbers");
      const glm::dquat q(n.rotation[3], n.rotation[0], n.rotation[1], n.rotation[2]);
      const double len = glm::length(q);
      if (!(len > 0.0)) fail(name_, where + "the rotation quaternion is zero");
      r = glm::mat4_cast(q / len);
    }
    if (!n.scale.empty()) {
      if (n.scale.size() != 3) fail(name_, where + "a scale needs 3 numbers");
      s = glm::scale(glm::dmat4(1.0), glm::dvec3(n.scale[0], n.scale[1], n.scale[2]));
    }
    return t * r * s;
  }

  View view(int index, const char* what) const {
    const std::string where = std::string(what) + " accessor " + std::to_string(index);
    if (index < 0 || static_cast<std::size_t>(index) >= m_.accessors.size())
      fail(name_, where + " does not exist");
    const tinygltf::Accessor& a = m_.accessors[static_cast<std::size_t>(index)];
    if (a.sparse.isSparse) fail(name_, where + " is sparse, which is not supported");
    if (a.bufferView < 0 || static_cast<std::size_t>(a.bufferView) >= m_.bufferViews.size())
      fail(name_, where + " has no valid bufferView");
    const tinygltf::BufferView& bv = m_.bufferViews[static_cast<std::size_t>(a.bufferView)];
    if (bv.buffer < 0 || static_cast<std::size_t>(bv.buffer) >= m_.buffers.size())
      fail(name_, where + ": its buffer view has no valid buffer");
    const std::vector<unsigned char>& buf = m_.buffers[static_cast<std::size_t>(bv.buffer)].data;
    const int size = tinygltf::GetComponentSizeInBytes(static_cast<std::uint32_t>(a.componentType));
    const int comps = tinygltf::GetNumComponentsInType(static_cast<std::uint32_t>(a.type));
    if (size <= 0 || comps <= 0) fail(name_, where + " has an invalid type");
    const std::size_t elem = static_cast<std::size_t>(size) * static_cast<std::size_t>(comps);
    const std::size_t stride = bv.byteStride ? bv.byteStride : elem;
    if (stride < elem) fail(name_, where + ": byteStride is smaller than an element");
    if (bv.byteOffset > buf.size() || bv.byteLength > buf.size() - bv.byteOffset)
      fail(name_, where + ": its buffer view runs past the end of its buffer");
    View v{nullptr, a.count, stride, a.componentType, comps};
    if (a.count == 0) return v;
    if (a.byteOffset > bv.byteLength || elem > bv.byteLength - a.byteOffset ||
        a.count - 1 > (bv.byteLength - a.byteOffset - elem) / stride)
      fail(name_, where + " runs past the end of its buffer view");
    v.data = buf.data() + bv.byteOffset + a.byteOffset;
    return v;
  }

  // baseColorFactor; white without a material (the glTF default material).
  Rgba8 materialColor(int material) const {
    if (material < 0 || static_cast<std::size_t>(material) >= m_.materials.size())
      return Rgba8{255, 255, 255, 255};
    return toRgba8(
        m_.materials[static_cast<std::size_t>(material)].pbrMetallicRoughness.baseColorFactor);
  }

  void primitive(const tinygltf::Primitive& prim, const glm::dmat4& world) {
    if (prim.mode != TINYGLTF_MODE_TRIANGLES && prim.mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        prim.mode != TINYGLTF_MODE_TRIANGLE_FAN)
      return;
    const auto posIt = prim.attributes.find("POSITION");
    if (posIt == prim.attributes.end()) return;
    const View pos = view(posIt->second, "POSITION");
    if (pos.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pos.components != 3)
      fail(name_, "POSITION accessor " + std::to_string(posIt->second) + " is not float VEC3");
    const std::size_t base = out_.positions.size();
    if (pos.count > kMaxOutput - base)
      fail(name_, "more than " + std::to_string(kMaxOutput) + " vertices");
    const Rgba8 matColor = materialColor(prim.material);
    std::optional<View> color;
    if (const auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
      color = view(it->second, "COLOR_0");
      const int t = color->componentType;
      if ((t != TINYGLTF_COMPONENT_TYPE_FLOAT && t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
           t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT) ||
          (color->components != 3 && color->components != 4) || color->count != pos.count)
        fail(name_, "COLOR_0 accessor " + std::to_string(it->second) +
                        " is not float/unorm VEC3/VEC4 with one colour per vertex");
      anyVertexColor_ = true;
    }
    out_.positions.reserve(base + pos.count);
    vertexColors_.reserve(base + pos.count);
    for (std::size_t i = 0; i < pos.count; ++i) {
      const glm::dvec4 p = world * glm::dvec4(loadFloatLe(pos.at(i, 0)), loadFloatLe(pos.at(i, 1)),
                                              loadFloatLe(pos.at(i, 2)), 1.0);
      const glm::vec3 q(p);
      if (!std::isfinite(q.x) || !std::isfinite(q.y) || !std::isfinite(q.z))
        fail(name_, "a vertex position is NaN, infinite or out of float range");
      out_.positions.push_back(q);
      Rgba8 c = matColor;
      if (color)
        for (int k = 0; k < 4; ++k) {
          const float f = k < color->components ? color->unorm(i, k) : 1.0f;
          const float v = f * static_cast<float>(matColor[k]);
          c[k] = !(v > 0.0f) ? 0 : v >= 255.0f ? 255 : static_cast<std::uint8_t>(std::lround(v));
        }
      vertexColors_.push_back(c);
    }
    // The vertex list, then triangles by mode.
    std::vector<std::uint32_t> list;
    if (prim.indices >= 0) {
      const View idx = view(prim.indices, "indices");
      const int t = idx.componentType;
      if (idx.components != 1 || (t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
                                  t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
                                  t != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT))
        fail(name_,
             "indices accessor " + std::to_string(prim.indices) + " is not u8/u16/u32 SCALAR");
      list.reserve(idx.count);
      for (std::size_t i = 0; i < idx.count; ++i) {
        const std::uint32_t v = idx.index(i);
        if (v >= pos.count)
          fail(name_, "index " + std::to_string(v) + " in accessor " +
                          std::to_string(prim.indices) + " is out of range (" +
                          std::to_string(pos.count) + " vertices)");
        list.push_back(v);
      }
    } else {
      list.resize(pos.count);
      for (std::size_t i = 0; i < pos.count; ++i) list[i] = static_cast<std::uint32_t>(i);
    }
    const std::size_t n = list.size();
    const std::size_t tris = prim.mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : (n >= 3 ? n - 2 : 0);
    if (tris > kMaxOutput - out_.triangleCount())
      fail(name_, "more than " + std::to_string(kMaxOutput) + " triangles");
    const bool flip = glm::determinant(world) < 0.0;
    const auto b = static_cast<std::uint32_t>(base);
    out_.indices.reserve(out_.indices.size() + 3 * tris);
    for (std::size_t i = 0; i < tris; ++i) {
      std::uint32_t v0, v1, v2;
      if (prim.mode == TINYGLTF_MODE_TRIANGLES) {
        v0 = list[3 * i], v1 = list[3 * i + 1], v2 = list[3 * i + 2];
      } else if (prim.mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        v0 = list[i], v1 = list[i + 1 + i % 2], v2 = list[i + 2 - i % 2];
      } else {
        v0 = list[i + 1], v1 = list[i + 2], v2 = list[0];
      }
      if (flip) std::swap(v1, v2);
      out_.indices.insert(out_.indices.end(), {b + v0, b + v1, b + v2});
      triangleColors_.push_back(matColor);
    }
  }

  TriangleMesh finish() {
    if (anyVertexColor_) {
      out_.vertexColors = std::move(vertexColors_);
    } else if (!triangleColors_.empty()) {
      const Rgba8 first = triangleColors_[0];
      if (std::all_of(triangleColors_.begin(), triangleColors_.end(),
                      [&](const Rgba8& c) { return c == first; }))
        out_.baseColor = first;
      else
        out_.faceColors = std::move(triangleColors_);
    }
    return std::move(out_);
  }

  const tinygltf::Model& m_;
  const std::string& name_;
  TriangleMesh out_;
  std::vector<Rgba8> vertexColors_;    // COLOR_0 times material colour, else material colour
  std::vector<Rgba8> triangleColors_;  // material colour
  bool anyVertexColor_ = false;
};

std::string firstLine(const std::string& s) {
  std::string line = s.substr(0, s.find('\n'));
  return line.empty() ? "tinygltf could not read the file" : line;
}

}  // namespace

TriangleMesh readGltf(std::string_view bytes, const std::string& name,
                      const ResourceLoader& loader) {
  if (bytes.size() > std::numeric_limits<std::uint32_t>::max())
    fail(name, "glTF input larger than 4 GiB");
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  std::size_t length = bytes.size();
  checkJsonDepth(glb ? checkGlb(bytes, name, length) : bytes, name);

  FsState state;
  state.loader = &loader;
  tinygltf::TinyGLTF ctx;
  ctx.SetImageLoader(&skipImage, nullptr);
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
  return Walker(model, name).run();
}

}  // namespace gs::formats
