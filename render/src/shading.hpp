// Private to render/: an Appearance's values as the surface programs take them, read once
// per revision of the Appearance (scene_renderer.cpp): VRML97's Material and texture
// (clauses 6.3, 6.27), X3D 4.0's PhysicalMaterial, UnlitMaterial, TwoSidedMaterial,
// alphaMode, MultiTexture, LineProperties and FillProperties.
#pragma once

#include "line_fill_properties.hpp"
#include "multi_texture.hpp"
#include "surface_programs.hpp"

#include "vrml/node.hpp"

#include <glm/mat3x3.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstdint>
#include <string>

namespace gs::render::detail {

/// The lighting model of a shape: VRML97 / X3D Material (Phong), X3D 4 PhysicalMaterial
/// (shaders_physical.cpp) or UnlitMaterial (the Phong program's unlit path).
enum class ShadingModel : std::uint8_t { phong, physical, unlit };

/// The maps of a PhysicalMaterial beyond its base texture, in texture units 1..4.
enum PhysicalMap { kMetallicRoughness, kNormalMap, kEmissiveMap, kOcclusionMap, kPhysicalMaps };
static_assert(kPhysicalMaps == kPhysicalMapCount);

/// An Appearance node's values, read once (clause 6.3 Appearance, 6.27 Material; X3D 4.0
/// clause 12.4.2 Appearance alphaMode, 12.4.10 PhysicalMaterial, 12.4.12 UnlitMaterial).
struct Shading {
  ShadingModel model = ShadingModel::phong;
  bool hasMaterial = false;
  glm::vec3 diffuseColor{0.8f};
  float ambientIntensity = 0.2f;
  glm::vec3 specularColor{0.0f};
  glm::vec3 emissiveColor{0.0f};
  float shininess = 0.2f;
  float transparency = 0.0f;
  /// X3D 4.0 TwoSidedMaterial with separateBackColor TRUE: the back faces' values.
  bool separateBack = false;
  glm::vec3 backDiffuseColor{0.8f}, backSpecularColor{0.0f}, backEmissiveColor{0.0f};
  float backAmbientIntensity = 0.2f, backShininess = 0.2f, backTransparency = 0.0f;
  const vrml::Node* texture = nullptr;
  /// An RGB(A) texture multiplies the diffuse (or Color) colour and its alpha the
  /// material's (X3D 4.0 clause 17.2.2.4: Material.diffuseTexture and every texture of an
  /// X3D world, as X_ITE and castle draw X3D 3 files too) instead of replacing them
  /// (VRML97 table 4.5).
  bool textureModulates = false;
  glm::mat3 textureMatrix{1.0f};
  glm::mat4 textureMatrix3D{1.0f};  // the same transform for 3D texture coordinates
  // PhysicalMaterial (diffuseColor holds baseColor, texture baseTexture).
  float metallic = 1.0f, roughness = 1.0f, normalScale = 1.0f, occlusionStrength = 1.0f;
  std::array<const vrml::Node*, kPhysicalMaps> maps{};
  /// baseTextureMapping, then the maps' *TextureMapping fields (X3D 4.0 clause 12.4.10).
  std::array<std::string, 1 + kPhysicalMaps> mappings{};
  bool anyMapping = false;
  int alphaMode = 0;  // 0 AUTO, 1 OPAQUE, 2 MASK, 3 BLEND
  float alphaCutoff = 0.5f;
  /// Appearance.texture's MultiTexture (X3D 4.0 clause 18.4.3) for the Phong program;
  /// `texture` is then null. A PhysicalMaterial takes its first stage as baseTexture.
  MultiTextureStages multi;
  const vrml::Node* multiTextureNode = nullptr;
  LineFillStyle lineFill;  // X3D LineProperties and FillProperties
  /// The Appearance read, and whether its `shaders` field lists any shader (X3D 4.0
  /// clause 31: composed_shaders.hpp).
  const vrml::Node* appearance = nullptr;
  bool hasShaders = false;
  std::uint64_t revision = 0;  // vrml::revisionWithFields of the Appearance read
};

/// Reads `appearance` (null: no Appearance, an unlit white shape). `x3d`: the world is an
/// X3D one (any version), whose RGB(A) textures modulate (`textureModulates`).
Shading readShading(const vrml::Node* appearance, bool x3d = false);

/// The texture coordinate set (0 or 1, GpuMesh's two) a texture with *TextureMapping
/// `mapping` reads in `geometry`: the position of the TextureCoordinate whose `mapping`
/// equals it in the geometry's MultiTextureCoordinate (X3D 4.0 clause 18.2.3). 0 for an
/// empty mapping, none found, or a set past the second.
int texCoordSetOf(const std::string& mapping, const vrml::Node& geometry);

}  // namespace gs::render::detail
