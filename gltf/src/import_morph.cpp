// glTF morph target animation (glTF 2.0 clauses 3.7.2.2 "Morph Targets" and 3.11
// "Animations", path `weights`): per primitive of the animated node, the morphed
// positions  base + sum_t weight_t * target_t  (and normals) at every key, as a
// CoordinateInterpolator (NormalInterpolator) ROUTEd from the animation's TimeSensor to
// the primitive's Coordinate (Normal), or to its Skin's rest pose when the node is
// skinned too.
#include "importer.hpp"

#include "gltf/accessors.hpp"

namespace gs::gltf::x3d {
namespace {

/// Most vertices times keys one interpolator may hold (48 MB of MFVec3f): beyond it the
/// channel is reported and not played, so small files cannot ask for huge tables.
constexpr std::size_t kMaxMorphValues = std::size_t{1} << 22;

}  // namespace

void GltfImporter::morphChannel(const NodePtr& sensor, int node,
                                const std::vector<float>& fractions,
                                const std::vector<std::size_t>& sourceKeys,
                                const std::vector<float>& output, std::size_t keyCount, bool cubic,
                                std::vector<NodePtr>& made) {
  const auto own = nodePrimitives_.find(node);
  if (own == nodePrimitives_.end() || keyCount == 0) return;
  const std::string where = "node " + std::to_string(node) + ": morph animation: ";
  const tinygltf::Mesh& mesh =
      m_.meshes[static_cast<std::size_t>(m_.nodes[static_cast<std::size_t>(node)].mesh)];
  // Output holds, per key, one weight per target (times 3 with CUBICSPLINE tangents).
  const std::size_t per = cubic ? 3 : 1;
  if (output.size() % (keyCount * per) != 0) {
    warn(where + "the weights output count is not a multiple of the key count; not played");
    return;
  }
  const std::size_t weightsPerKey = output.size() / (keyCount * per);
  for (const auto& [primIndex, shape] : own->second) {
    const tinygltf::Primitive& p = mesh.primitives[static_cast<std::size_t>(primIndex)];
    if (p.targets.empty()) continue;
    const NodePtr geometry = shape->sfnode("geometry");
    if (!geometry || (geometry->typeId() == NodeTypeId::PointSet && p.indices >= 0)) continue;
    const NodePtr coord = geometry->sfnode("coord");
    const NodePtr normal = geometry->sfnode("normal");
    if (!coord) continue;
    const std::vector<float> base =
        gltf::readFloats(m_, gltfAttribute(p, "POSITION"), 3, url_, "POSITION");
    std::vector<float> baseNormal;
    if (normal) baseNormal = gltf::readFloats(m_, gltfAttribute(p, "NORMAL"), 3, url_, "NORMAL");
    const std::size_t count = base.size() / 3;
    if (fractions.size() * count > kMaxMorphValues) {
      warn(where + std::to_string(fractions.size()) + " keys of " + std::to_string(count) +
           " vertices are too many; not played");
      return;
    }
    // Each target's displacements (empty when it moves no position / normal).
    const std::size_t targets = std::min(p.targets.size(), weightsPerKey);
    std::vector<std::vector<float>> dPos(targets), dNormal(targets);
    for (std::size_t t = 0; t < targets; ++t)
      for (const auto& [name, accessor] : p.targets[t]) {
        if (name == "POSITION")
          dPos[t] = gltf::readFloats(m_, accessor, 3, url_, "morph target");
        else if (name == "NORMAL" && normal)
          dNormal[t] = gltf::readFloats(m_, accessor, 3, url_, "morph target");
        if ((name == "POSITION" && dPos[t].size() != base.size()) ||
            (name == "NORMAL" && normal && dNormal[t].size() != base.size()))
          gltf::fail(url_, "a morph target's count differs from POSITION");
      }
    std::vector<glm::vec3> points, normals;
    points.reserve(fractions.size() * count);
    for (std::size_t k : sourceKeys) {
      const float* w = output.data() + (k * per + (cubic ? 1 : 0)) * weightsPerKey;
      for (std::size_t v = 0; v < count; ++v) {
        glm::vec3 pt(base[3 * v], base[3 * v + 1], base[3 * v + 2]);
        glm::vec3 nv = baseNormal.empty() ? glm::vec3(0.0f)
                                          : glm::vec3(baseNormal[3 * v], baseNormal[3 * v + 1],
                                                      baseNormal[3 * v + 2]);
        for (std::size_t t = 0; t < targets; ++t) {
          if (!dPos[t].empty())
            pt += w[t] * glm::vec3(dPos[t][3 * v], dPos[t][3 * v + 1], dPos[t][3 * v + 2]);
          if (!dNormal[t].empty())
            nv += w[t] * glm::vec3(dNormal[t][3 * v], dNormal[t][3 * v + 1], dNormal[t][3 * v + 2]);
        }
        points.push_back(pt);
        if (!baseNormal.empty())
          normals.push_back(glm::length(nv) > 0.0f ? glm::normalize(nv) : nv);
      }
    }
    for (const glm::vec3& pt : points)
      if (!std::isfinite(pt.x) || !std::isfinite(pt.y) || !std::isfinite(pt.z)) {
        warn(where + "a morphed position is NaN or infinite; not played");
        return;
      }
    // A skinned primitive morphs its rest pose; the Skin re-skins it.
    const auto skin = skinOfShape_.find(shape.get());
    const bool skinned = skin != skinOfShape_.end();
    // One interpolator of `values` per key, ROUTEd from the sensor to `to`.`toField`.
    auto interpolate = [&](const char* type, std::vector<glm::vec3> values, const NodePtr& to,
                           const char* toField) {
      NodePtr i = make(type);
      set(*i, "key", FieldValue::make<FieldType::MFFloat>(fractions));
      set(*i, "keyValue", FieldValue::make<FieldType::MFVec3f>(std::move(values)));
      addRoute(scene_, sensor, "fraction_changed", i, "set_fraction", url_);
      addRoute(scene_, i, "value_changed", to, toField, url_);
      made.push_back(std::move(i));
    };
    interpolate("CoordinateInterpolator", std::move(points), skinned ? skin->second : coord,
                skinned ? "set_restPoint" : "set_point");
    if (!normals.empty())
      interpolate("NormalInterpolator", std::move(normals), skinned ? skin->second : normal,
                  skinned ? "set_restNormal" : "set_vector");
  }
}

}  // namespace gs::gltf::x3d
