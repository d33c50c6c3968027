// glTF 2.0 reader (JSON or GLB) on top of Debian's shared tinygltf: see mesh_readers.hpp.
// gltf/ loads the asset with its checks; this file walks the node graph (checked: no node
// reached twice, no index out of range) into one triangle mesh.
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

#include "base/byte_order.hpp"
#include "formats/mesh_readers.hpp"
#include "gltf/accessors.hpp"

namespace gs::formats {
namespace {

using base::loadFloatLe;
using gltf::fail;

constexpr std::size_t kMaxOutput = std::size_t{1} << 27;  // vertices and triangles

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

class Walker {
 public:
  Walker(const tinygltf::Model& model, const std::string& name) : m_(model), name_(name) {}

  TriangleMesh run() {
    const std::vector<int> roots = gltf::sceneRoots(m_);
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

  gltf::AccessorView view(int index, const char* what) const {
    return gltf::accessorView(m_, index, name_, what);
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
    const gltf::AccessorView pos = view(posIt->second, "POSITION");
    if (pos.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || pos.components != 3)
      fail(name_, "POSITION accessor " + std::to_string(posIt->second) + " is not float VEC3");
    const std::size_t base = out_.positions.size();
    if (pos.count > kMaxOutput - base)
      fail(name_, "more than " + std::to_string(kMaxOutput) + " vertices");
    const Rgba8 matColor = materialColor(prim.material);
    std::optional<gltf::AccessorView> color;
    if (const auto it = prim.attributes.find("COLOR_0"); it != prim.attributes.end()) {
      color = view(it->second, "COLOR_0");
      color->normalized = true;  // integer colours are always normalized (glTF 3.7.2.1)
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
          const float f = k < color->components ? color->value(i, k) : 1.0f;
          const float v = f * static_cast<float>(matColor[k]);
          c[k] = !(v > 0.0f) ? 0 : v >= 255.0f ? 255 : static_cast<std::uint8_t>(std::lround(v));
        }
      vertexColors_.push_back(c);
    }
    // The vertex list, then triangles by mode.
    std::vector<std::uint32_t> list;
    if (prim.indices >= 0) {
      list = gltf::readIndices(m_, prim.indices, pos.count, name_);
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

}  // namespace

TriangleMesh readGltf(std::string_view bytes, const std::string& name,
                      const ResourceLoader& loader) {
  try {
    const tinygltf::Model model = gltf::load(bytes, name, loader);
    return Walker(model, name).run();
  } catch (const gltf::Error& e) {
    throw InputError(e.what());
  }
}

}  // namespace gs::formats
