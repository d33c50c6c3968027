// glTF meshes as X3D geometry (glTF 2.0 clause 3.7 "Geometry"): a Shape per primitive;
// TRIANGLES, TRIANGLE_STRIP and TRIANGLE_FAN as IndexedTriangleSet, LINES, LINE_LOOP and
// LINE_STRIP as IndexedLineSet, POINTS as PointSet. Morph targets are applied with the
// default weights: the node's, else the mesh's (clause 3.7.2.2).
#include "importer.hpp"

#include "gltf/accessors.hpp"

#include <glm/mat3x3.hpp>

namespace gs::gltf::x3d {
namespace {

std::vector<glm::vec3> vec3s(const std::vector<float>& f) {
  std::vector<glm::vec3> out(f.size() / 3);
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = {f[3 * i], f[3 * i + 1], f[3 * i + 2]};
  return out;
}

}  // namespace

const std::vector<NodePtr>& GltfImporter::meshShapes(int index) {
  if (const auto it = meshes_.find(index); it != meshes_.end()) return it->second;
  if (index < 0 || static_cast<std::size_t>(index) >= m_.meshes.size())
    gltf::fail(url_, "mesh " + std::to_string(index) + " does not exist");
  const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(index)];
  std::vector<NodePtr> shapes;
  for (const tinygltf::Primitive& p : mesh.primitives)
    if (NodePtr s = primitiveShape(p, mesh.weights)) shapes.push_back(std::move(s));
  return meshes_[index] = std::move(shapes);
}

std::vector<NodePtr> GltfImporter::ownShapes(int node, int index) {
  if (index < 0 || static_cast<std::size_t>(index) >= m_.meshes.size())
    gltf::fail(url_, "mesh " + std::to_string(index) + " does not exist");
  const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(index)];
  std::vector<NodePtr> shapes;
  auto& own = nodePrimitives_[node];
  // A node's own weights replace its mesh's (glTF 2.0 clause 3.7.2.2).
  const std::vector<double>& nodeWeights = m_.nodes[static_cast<std::size_t>(node)].weights;
  const std::vector<double>& weights = nodeWeights.empty() ? mesh.weights : nodeWeights;
  for (std::size_t i = 0; i < mesh.primitives.size(); ++i)
    if (NodePtr s = primitiveShape(mesh.primitives[i], weights)) {
      own.emplace_back(static_cast<int>(i), s);
      shapes.push_back(std::move(s));
    }
  return shapes;
}

NodePtr GltfImporter::primitiveShape(const tinygltf::Primitive& p,
                                     const std::vector<double>& weights) {
  if (p.extensions.count("KHR_gaussian_splatting")) {
    gaussianSplats_ = true;  // drawn as Gaussians by the node run() adds, not as points
    return nullptr;
  }
  const int posIndex = gltfAttribute(p, "POSITION");
  if (posIndex < 0) return nullptr;  // nothing to draw (clause 3.7.2.1 allows it)
  std::vector<float> pos = gltf::readFloats(m_, posIndex, 3, url_, "POSITION");
  const std::size_t vertexCount = pos.size() / 3;
  std::vector<float> normals;
  if (const int n = gltfAttribute(p, "NORMAL"); n >= 0) {
    normals = gltf::readFloats(m_, n, 3, url_, "NORMAL");
    if (normals.size() != pos.size()) gltf::fail(url_, "NORMAL and POSITION counts differ");
  }
  // Morph targets at the default weights.
  for (std::size_t t = 0; t < p.targets.size() && t < weights.size(); ++t) {
    const auto w = static_cast<float>(weights[t]);
    if (w == 0.0f) continue;
    for (const auto& [name, accessor] : p.targets[t]) {
      std::vector<float>* dest = name == "POSITION" ? &pos : name == "NORMAL" ? &normals : nullptr;
      if (dest == nullptr || dest->empty()) continue;
      const std::vector<float> d = gltf::readFloats(m_, accessor, 3, url_, "morph target");
      if (d.size() != dest->size())
        gltf::fail(url_, "a morph target's count differs from POSITION");
      for (std::size_t i = 0; i < d.size(); ++i) (*dest)[i] += w * d[i];
    }
  }
  for (float f : pos)
    if (!std::isfinite(f)) gltf::fail(url_, "a vertex position is NaN or infinite");

  std::vector<std::uint32_t> list;
  if (p.indices >= 0)
    list = gltf::readIndices(m_, p.indices, vertexCount, url_);
  else
    for (std::size_t i = 0; i < vertexCount; ++i) list.push_back(static_cast<std::uint32_t>(i));

  NodePtr coord = make("Coordinate");
  set(*coord, "point", FieldValue::make<FieldType::MFVec3f>(vec3s(pos)));
  NodePtr color;
  if (const int c = gltfAttribute(p, "COLOR_0"); c >= 0) {
    const gltf::AccessorView v = gltf::accessorView(m_, c, url_, "COLOR_0", true);
    const std::vector<float> f = gltf::readFloats(m_, c, v.components, url_, "COLOR_0");
    if (f.size() / static_cast<std::size_t>(v.components) != vertexCount)
      gltf::fail(url_, "COLOR_0 and POSITION counts differ");
    if (v.components == 4) {
      std::vector<glm::vec4> rgba(vertexCount);
      for (std::size_t i = 0; i < vertexCount; ++i)
        rgba[i] = {f[4 * i], f[4 * i + 1], f[4 * i + 2], f[4 * i + 3]};
      color = make("ColorRGBA");
      set(*color, "color", FieldValue::make<FieldType::MFColorRGBA>(std::move(rgba)));
    } else {
      color = make("Color");
      set(*color, "color", FieldValue::make<FieldType::MFColor>(vec3s(f)));
    }
  }

  NodePtr geometry;
  std::vector<std::int32_t> index;
  const int mode = p.mode < 0 ? TINYGLTF_MODE_TRIANGLES : p.mode;
  const std::size_t n = list.size();
  auto push = [&](std::uint32_t v) { index.push_back(static_cast<std::int32_t>(v)); };
  if (mode == TINYGLTF_MODE_TRIANGLES || mode == TINYGLTF_MODE_TRIANGLE_STRIP ||
      mode == TINYGLTF_MODE_TRIANGLE_FAN) {
    const std::size_t tris = mode == TINYGLTF_MODE_TRIANGLES ? n / 3 : (n >= 3 ? n - 2 : 0);
    index.reserve(3 * tris);
    for (std::size_t i = 0; i < tris; ++i) {
      if (mode == TINYGLTF_MODE_TRIANGLES) {
        push(list[3 * i]), push(list[3 * i + 1]), push(list[3 * i + 2]);
      } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
        push(list[i]), push(list[i + 1 + i % 2]), push(list[i + 2 - i % 2]);
      } else {
        push(list[0]), push(list[i + 1]), push(list[i + 2]);
      }
    }
    geometry = make("IndexedTriangleSet");
    set(*geometry, "index", FieldValue::make<FieldType::MFInt32>(std::move(index)));
    if (!normals.empty()) {
      NodePtr normal = make("Normal");
      std::vector<glm::vec3> v = vec3s(normals);
      for (glm::vec3& x : v)
        if (glm::length(x) > 0.0f) x = glm::normalize(x);
      set(*normal, "vector", FieldValue::make<FieldType::MFVec3f>(std::move(v)));
      set(*geometry, "normal", FieldValue::make<FieldType::SFNode>(std::move(normal)));
    }
  } else if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_STRIP ||
             mode == TINYGLTF_MODE_LINE_LOOP) {
    if (mode == TINYGLTF_MODE_LINE) {
      for (std::size_t i = 0; i + 1 < n; i += 2)
        push(list[i]), push(list[i + 1]), index.push_back(-1);
    } else if (n >= 2) {
      for (std::uint32_t v : list) push(v);
      if (mode == TINYGLTF_MODE_LINE_LOOP) push(list[0]);
      index.push_back(-1);
    }
    geometry = make("IndexedLineSet");
    set(*geometry, "coordIndex", FieldValue::make<FieldType::MFInt32>(std::move(index)));
  } else if (mode == TINYGLTF_MODE_POINTS) {
    // PointSet has no index: the listed vertices in order.
    std::vector<glm::vec3> pts;
    const std::vector<glm::vec3> all = vec3s(pos);
    for (std::uint32_t v : list) pts.push_back(all[v]);
    set(*coord, "point", FieldValue::make<FieldType::MFVec3f>(std::move(pts)));
    if (color && p.indices >= 0) color = nullptr;  // (colours would need the same reorder)
    geometry = make("PointSet");
  } else {
    warn("a primitive of mode " + std::to_string(mode) + " is skipped (unknown mode)");
    return nullptr;
  }
  set(*geometry, "coord", FieldValue::make<FieldType::SFNode>(coord));
  if (color) set(*geometry, "color", FieldValue::make<FieldType::SFNode>(color));

  bool doubleSided = false;
  if (p.material >= 0 && static_cast<std::size_t>(p.material) < m_.materials.size())
    doubleSided = m_.materials[static_cast<std::size_t>(p.material)].doubleSided;
  const bool triangles = geometry->typeId() == NodeTypeId::IndexedTriangleSet;
  if (triangles) {
    set(*geometry, "solid", FieldValue::make<FieldType::SFBool>(!doubleSided));
    // The texture coordinates the material's textures read, V flipped (glTF's origin is
    // the image's top left, X3D's its bottom left), the base colour texture's
    // KHR_texture_transform applied to its set. Two sets become a MultiTextureCoordinate
    // whose TextureCoordinates' `mapping` the PhysicalMaterial's *TextureMapping fields
    // name (appearance()).
    const std::vector<int> sets = texCoordSets(p.material);
    std::vector<NodePtr> coordinates;
    for (std::size_t k = 0; k < sets.size(); ++k) {
      const int uv = gltfAttribute(p, "TEXCOORD_" + std::to_string(sets[k]));
      if (uv < 0) continue;
      const std::vector<float> f = gltf::readFloats(m_, uv, 2, url_, "TEXCOORD");
      if (f.size() / 2 != vertexCount) gltf::fail(url_, "TEXCOORD and POSITION counts differ");
      const glm::mat3 m = k == 0 ? uvTransform(p.material) : glm::mat3(1.0f);
      std::vector<glm::vec2> st(vertexCount);
      for (std::size_t i = 0; i < vertexCount; ++i) {
        const glm::vec3 t = m * glm::vec3(f[2 * i], f[2 * i + 1], 1.0f);
        st[i] = {t.x, 1.0f - t.y};
      }
      NodePtr tc = make("TextureCoordinate");
      GltfImporter::set(*tc, "point", FieldValue::make<FieldType::MFVec2f>(std::move(st)));
      if (sets.size() > 1)
        GltfImporter::set(
            *tc, "mapping",
            FieldValue::make<FieldType::SFString>("TEXCOORD_" + std::to_string(sets[k])));
      coordinates.push_back(std::move(tc));
    }
    if (coordinates.size() == 1 && sets.size() == 1) {
      GltfImporter::set(*geometry, "texCoord", FieldValue::make<FieldType::SFNode>(coordinates[0]));
    } else if (!coordinates.empty()) {
      NodePtr multi = make("MultiTextureCoordinate");
      GltfImporter::set(*multi, "texCoord",
                        FieldValue::make<FieldType::MFNode>(std::move(coordinates)));
      GltfImporter::set(*geometry, "texCoord",
                        FieldValue::make<FieldType::SFNode>(std::move(multi)));
    }
  }
  NodePtr shape = make("Shape");
  set(*shape, "geometry", FieldValue::make<FieldType::SFNode>(geometry));
  set(*shape, "appearance", FieldValue::make<FieldType::SFNode>(appearance(p.material)));
  return shape;
}

}  // namespace gs::gltf::x3d
