// glTF skins (glTF 2.0 clause 3.8 "Skins") as GhostSpace Skin nodes
// (docs/vrml-extensions.md): one per skinned primitive, naming the joint Transforms, the
// inverse bind matrices, the Transform of the skinned node, and the primitive's Coordinate
// and Normal with their rest pose and JOINTS_n / WEIGHTS_n. The execution model
// (runtime/src/skin.cpp) writes the skinned vertices whenever the skeleton moves.
#include "importer.hpp"

#include "gltf/accessors.hpp"

namespace gs::gltf::x3d {
void GltfImporter::skins() {
  std::vector<NodePtr> made;
  for (const auto& [nodeIndex, primitives] : nodePrimitives_) {
    const tinygltf::Node& n = m_.nodes[static_cast<std::size_t>(nodeIndex)];
    if (n.skin < 0) continue;
    const std::string where = "node " + std::to_string(nodeIndex) + ": ";
    if (static_cast<std::size_t>(n.skin) >= m_.skins.size()) {
      warn(where + "skin " + std::to_string(n.skin) + " does not exist; drawn unskinned");
      continue;
    }
    const tinygltf::Skin& skin = m_.skins[static_cast<std::size_t>(n.skin)];
    // The joints, and the roots of the trees holding them and the skinned node: the
    // skeleton the runtime walks for their matrices.
    std::vector<NodePtr> joints;
    std::vector<NodePtr> roots;
    auto addRoot = [&](int i) {
      for (std::size_t steps = 0;
           steps < parents_.size() && parents_[static_cast<std::size_t>(i)] >= 0; ++steps)
        i = parents_[static_cast<std::size_t>(i)];
      const NodePtr& r = transforms_[static_cast<std::size_t>(i)];
      if (r && std::find(roots.begin(), roots.end(), r) == roots.end()) roots.push_back(r);
    };
    addRoot(nodeIndex);
    for (int j : skin.joints) {
      const bool valid = j >= 0 && static_cast<std::size_t>(j) < transforms_.size();
      if (!valid || !transforms_[static_cast<std::size_t>(j)])
        warn(where + "joint " + std::to_string(j) + " is not a node of the scene drawn");
      joints.push_back(valid ? transforms_[static_cast<std::size_t>(j)] : nullptr);
      if (valid) addRoot(j);
    }
    std::vector<float> inverseBind;
    if (skin.inverseBindMatrices >= 0) {
      inverseBind = gltf::readFloats(m_, skin.inverseBindMatrices, 16, url_, "inverseBindMatrices");
      if (inverseBind.size() < 16 * joints.size())
        gltf::fail(url_,
                   "skin " + std::to_string(n.skin) + ": fewer inverseBindMatrices than joints");
    }
    const tinygltf::Mesh& mesh = m_.meshes[static_cast<std::size_t>(n.mesh)];
    for (const auto& [primIndex, shape] : primitives) {
      const tinygltf::Primitive& p = mesh.primitives[static_cast<std::size_t>(primIndex)];
      const NodePtr geometry = shape->sfnode("geometry");
      if (!geometry) continue;
      if (geometry->typeId() == NodeTypeId::PointSet && p.indices >= 0) {
        warn(where + "indexed POINTS are drawn unskinned");
        continue;
      }
      const NodePtr coord = geometry->sfnode("coord");
      const NodePtr normal = geometry->sfnode("normal");
      if (!coord) continue;
      const std::vector<glm::vec3>& rest = mfvec3Field(*coord, "point");
      const std::size_t count = rest.size();
      // Every JOINTS_n / WEIGHTS_n pair, four influences each, interleaved per vertex.
      std::vector<std::vector<float>> jointSets, weightSets;
      for (int set = 0;; ++set) {
        const int ja = gltfAttribute(p, "JOINTS_" + std::to_string(set));
        const int wa = gltfAttribute(p, "WEIGHTS_" + std::to_string(set));
        if (ja < 0 || wa < 0) break;
        jointSets.push_back(gltf::readFloats(m_, ja, 4, url_, "JOINTS"));
        weightSets.push_back(gltf::readFloats(m_, wa, 4, url_, "WEIGHTS"));
        if (jointSets.back().size() != 4 * count || weightSets.back().size() != 4 * count)
          gltf::fail(url_, where + "JOINTS/WEIGHTS and POSITION counts differ");
      }
      if (jointSets.empty()) continue;  // a primitive with no influences stays put
      const std::size_t per = 4 * jointSets.size();
      std::vector<std::int32_t> vertexJoints(per * count);
      std::vector<float> vertexWeights(per * count);
      for (std::size_t v = 0; v < count; ++v)
        for (std::size_t s = 0; s < jointSets.size(); ++s)
          for (std::size_t k = 0; k < 4; ++k) {
            const float j = jointSets[s][4 * v + k];
            vertexJoints[v * per + 4 * s + k] =
                j >= 0.0f && j < 2147483647.0f ? static_cast<std::int32_t>(j) : -1;
            vertexWeights[v * per + 4 * s + k] = weightSets[s][4 * v + k];
          }
      NodePtr s = make("Skin");
      set(*s, "skeleton", FieldValue::make<FieldType::MFNode>(roots));
      set(*s, "joints", FieldValue::make<FieldType::MFNode>(joints));
      set(*s, "inverseBindMatrices", FieldValue::make<FieldType::MFFloat>(inverseBind));
      set(*s, "skinnedTransform",
          FieldValue::make<FieldType::SFNode>(transforms_[static_cast<std::size_t>(nodeIndex)]));
      set(*s, "coord", FieldValue::make<FieldType::SFNode>(coord));
      set(*s, "restPoint", FieldValue::make<FieldType::MFVec3f>(rest));
      if (normal) {
        set(*s, "normal", FieldValue::make<FieldType::SFNode>(normal));
        set(*s, "restNormal", FieldValue::make<FieldType::MFVec3f>(mfvec3Field(*normal, "vector")));
      }
      set(*s, "vertexJoints", FieldValue::make<FieldType::MFInt32>(std::move(vertexJoints)));
      set(*s, "vertexWeights", FieldValue::make<FieldType::MFFloat>(std::move(vertexWeights)));
      skinOfShape_[shape.get()] = s;
      made.push_back(std::move(s));
    }
  }
  for (NodePtr& n : made) {
    scene_.rootNodes.push_back(n);
    if (options_.onRootNode) options_.onRootNode(n);
  }
}

}  // namespace gs::gltf::x3d
