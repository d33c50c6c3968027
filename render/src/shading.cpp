// An Appearance's values for the surface programs (shading.hpp).
#include "shading.hpp"

#include "scene/node_access.hpp"
#include "scene/traversal.hpp"

#include <algorithm>
#include <string_view>

namespace gs::render::detail {

namespace {

const vrml::Node* sfnodeOf(const vrml::Node& n, std::string_view field) {
  const vrml::NodePtr p = n.sfnode(field);
  return p && !p->unresolved ? p.get() : nullptr;
}

// X3D 4's PhysicalMaterial and UnlitMaterial; their own textures win over
// Appearance.texture (X3D 4.0 clause 12.4.2).
void readX3dMaterial(const vrml::Node& m, Shading& s) {
  s.transparency = std::clamp(scene::sfFloat(m, "transparency", 0.0f), 0.0f, 1.0f);
  s.emissiveColor = glm::max(scene::sfColor(m, "emissiveColor", glm::vec3(0.0f)), 0.0f);
  if (m.typeId() == vrml::NodeTypeId::UnlitMaterial) {
    s.model = ShadingModel::unlit;
    s.emissiveColor = glm::clamp(s.emissiveColor, 0.0f, 1.0f);
    if (const vrml::Node* t = sfnodeOf(m, "emissiveTexture")) s.texture = t;
    return;
  }
  s.model = ShadingModel::physical;
  s.hasMaterial = true;
  s.diffuseColor = glm::clamp(scene::sfColor(m, "baseColor", glm::vec3(1.0f)), 0.0f, 1.0f);
  s.metallic = std::clamp(scene::sfFloat(m, "metallic", 1.0f), 0.0f, 1.0f);
  s.roughness = std::clamp(scene::sfFloat(m, "roughness", 1.0f), 0.0f, 1.0f);
  s.normalScale = scene::sfFloat(m, "normalScale", 1.0f);
  s.occlusionStrength = std::clamp(scene::sfFloat(m, "occlusionStrength", 1.0f), 0.0f, 1.0f);
  if (const vrml::Node* t = sfnodeOf(m, "baseTexture")) s.texture = t;
  s.maps[kMetallicRoughness] = sfnodeOf(m, "metallicRoughnessTexture");
  s.maps[kNormalMap] = sfnodeOf(m, "normalTexture");
  s.maps[kEmissiveMap] = sfnodeOf(m, "emissiveTexture");
  s.maps[kOcclusionMap] = sfnodeOf(m, "occlusionTexture");
  static constexpr std::array<vrml::FieldName, 1 + kPhysicalMaps> kMappings = {
      "baseTextureMapping", "metallicRoughnessTextureMapping", "normalTextureMapping",
      "emissiveTextureMapping", "occlusionTextureMapping"};
  for (std::size_t i = 0; i < kMappings.size(); ++i) {
    s.mappings[i] = scene::sfString(m, kMappings[i]);
    s.anyMapping = s.anyMapping || !s.mappings[i].empty();
  }
}

}  // namespace

/// The texture coordinate set (0 or 1, GpuMesh's two) a texture with *TextureMapping
/// `mapping` reads in `geometry`: the position of the TextureCoordinate whose `mapping`
/// equals it in the geometry's MultiTextureCoordinate (X3D 4.0 clause 18.2.3). 0 for an
/// empty mapping, none found, or a set past the second.
int texCoordSetOf(const std::string& mapping, const vrml::Node& geometry) {
  if (mapping.empty()) return 0;
  const vrml::NodePtr& tc = geometry.sfnode("texCoord");
  if (!tc || tc->typeId() != vrml::NodeTypeId::MultiTextureCoordinate) return 0;
  const std::vector<vrml::NodePtr>& sets = tc->mfnode("texCoord");
  for (std::size_t i = 0; i < sets.size() && i < 2; ++i)
    if (sets[i] && scene::sfString(*sets[i], "mapping") == mapping) return static_cast<int>(i);
  return 0;
}

namespace {

// X3D 4.0 clause 12.4.11 TwoSidedMaterial: the back* fields light back faces when
// separateBackColor is TRUE; otherwise both sides take the front values.
void readBackMaterial(const vrml::Node& m, Shading& s) {
  s.separateBack = scene::sfBool(m, "separateBackColor", false);
  if (!s.separateBack) return;
  const auto color = [&](vrml::FieldName f, glm::vec3 fallback) {
    return glm::clamp(scene::sfColor(m, f, fallback), 0.0f, 1.0f);
  };
  const auto unit = [&](vrml::FieldName f, float fallback) {
    return std::clamp(scene::sfFloat(m, f, fallback), 0.0f, 1.0f);
  };
  s.backDiffuseColor = color("backDiffuseColor", glm::vec3(0.8f));
  s.backSpecularColor = color("backSpecularColor", glm::vec3(0.0f));
  s.backEmissiveColor = color("backEmissiveColor", glm::vec3(0.0f));
  s.backAmbientIntensity = unit("backAmbientIntensity", 0.2f);
  s.backShininess = unit("backShininess", 0.2f);
  s.backTransparency = unit("backTransparency", 0.0f);
}

}  // namespace

Shading readShading(const vrml::Node* appearance, bool x3d) {
  Shading s;
  s.textureModulates = x3d;
  if (appearance == nullptr) return s;
  // Only a Material (or X3D's TwoSidedMaterial) lights the shape (6.3); any other node
  // there leaves it unlit (4.14.1).
  if (const vrml::NodePtr m = appearance->sfnode("material");
      m && !m->unresolved &&
      (m->typeId() == vrml::NodeTypeId::Material ||
       m->typeId() == vrml::NodeTypeId::TwoSidedMaterial)) {
    s.hasMaterial = true;
    s.diffuseColor = glm::clamp(scene::sfColor(*m, "diffuseColor", glm::vec3(0.8f)), 0.0f, 1.0f);
    s.ambientIntensity = std::clamp(scene::sfFloat(*m, "ambientIntensity", 0.2f), 0.0f, 1.0f);
    s.specularColor = glm::clamp(scene::sfColor(*m, "specularColor", glm::vec3(0.0f)), 0.0f, 1.0f);
    s.emissiveColor = glm::clamp(scene::sfColor(*m, "emissiveColor", glm::vec3(0.0f)), 0.0f, 1.0f);
    s.shininess = std::clamp(scene::sfFloat(*m, "shininess", 0.2f), 0.0f, 1.0f);
    s.transparency = std::clamp(scene::sfFloat(*m, "transparency", 0.0f), 0.0f, 1.0f);
    if (m->typeId() == vrml::NodeTypeId::TwoSidedMaterial) readBackMaterial(*m, s);
  }
  if (const vrml::NodePtr t = appearance->sfnode("texture"); t && !t->unresolved)
    s.texture = t.get();
  // X3D 4.0 clause 12.4.4: a Material's diffuseTexture textures the shape as
  // Appearance.texture does (which wins when both are given).
  if (const vrml::NodePtr m = appearance->sfnode("material");
      s.texture == nullptr && m && !m->unresolved &&
      (m->typeId() == vrml::NodeTypeId::Material ||
       m->typeId() == vrml::NodeTypeId::TwoSidedMaterial)) {
    s.texture = sfnodeOf(*m, "diffuseTexture");
    s.textureModulates = s.textureModulates || s.texture != nullptr;  // clause 17.2.2.4
  }
  if (const vrml::NodePtr m = appearance->sfnode("material");
      m && !m->unresolved &&
      (m->typeId() == vrml::NodeTypeId::PhysicalMaterial ||
       m->typeId() == vrml::NodeTypeId::UnlitMaterial))
    readX3dMaterial(*m, s);
  if (const vrml::FieldValue* mode = appearance->field("alphaMode");
      mode != nullptr && mode->type() == vrml::FieldType::SFString) {
    const std::string& v = mode->get<vrml::FieldType::SFString>();
    s.alphaMode = v == "OPAQUE" ? 1 : v == "MASK" ? 2 : v == "BLEND" ? 3 : 0;
    s.alphaCutoff = scene::sfFloat(*appearance, "alphaCutoff", 0.5f);
  }
  s.lineFill = readLineFillStyle(*appearance);
  s.appearance = appearance;
  s.hasShaders = !appearance->mfnode("shaders").empty();
  const vrml::NodePtr tt = appearance->sfnode("textureTransform");
  if (tt && !tt->unresolved) {
    s.textureMatrix = scene::textureTransformMatrix(*tt);
    s.textureMatrix3D = scene::textureTransformMatrix3D(*tt);
  }
  if (s.texture != nullptr && s.texture->typeId() == vrml::NodeTypeId::MultiTexture) {
    s.multiTextureNode = s.texture;
    s.multi = readMultiTexture(*s.texture, tt && !tt->unresolved ? tt.get() : nullptr);
    s.texture = nullptr;
    s.textureMatrix = glm::mat3(1.0f);  // each stage has its own (multi_texture.hpp)
    if (s.model == ShadingModel::physical) {
      if (!s.multi.stages.empty()) s.texture = s.multi.stages.front().texture;
      s.multi.stages.clear();
    }
  }
  return s;
}

}  // namespace gs::render::detail
