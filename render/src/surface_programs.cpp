// The surface programs and their variants (surface_programs.hpp).
#include "surface_programs.hpp"

#include <string_view>

namespace gs::render::detail {

void SurfaceUniforms::find(GLuint p) {
  metallic = uniform(p, "u_metallic");
  roughness = uniform(p, "u_roughness");
  normalScale = uniform(p, "u_normalScale");
  occlusionStrength = uniform(p, "u_occlusionStrength");
  alphaMode = uniform(p, "u_alphaMode");
  alphaCutoff = uniform(p, "u_alphaCutoff");
  static constexpr std::array<const char*, kPhysicalMapCount> kHas = {
      "u_hasMetallicRoughnessTexture", "u_hasNormalTexture", "u_hasEmissiveTexture",
      "u_hasOcclusionTexture"};
  static constexpr std::array<const char*, kPhysicalMapCount> kMap = {
      "u_metallicRoughnessTexture", "u_normalTexture", "u_emissiveTexture", "u_occlusionTexture"};
  for (std::size_t i = 0; i < kPhysicalMapCount; ++i) {
    hasMap[i] = uniform(p, kHas[i]);
    map[i] = uniform(p, kMap[i]);
  }
  clipPlaneCount = uniform(p, "u_clipPlaneCount");
  stageCount = uniform(p, "u_stageCount");
  texGen = uniform(p, "u_texGen");
  texGenParameter = uniform(p, "u_texGenParameter");
  eyeToWorld = uniform(p, "u_eyeToWorld");
  cubeMap = uniform(p, "u_cubeMap");
  cubeTexture = uniform(p, "u_cubeTexture");
  texture3DOn = uniform(p, "u_texture3DOn");
  texture3D = uniform(p, "u_texture3D");
  textureMatrix3D = uniform(p, "u_textureMatrix3D");
  texBoundsMin = uniform(p, "u_texBoundsMin");
  texBoundsSize = uniform(p, "u_texBoundsSize");
  stageMode = uniform(p, "u_stageMode");
  stageSource = uniform(p, "u_stageSource");
  stageFunction = uniform(p, "u_stageFunction");
  stageTexCoord = uniform(p, "u_stageTexCoord");
  stageMatrix = uniform(p, "u_stageMatrix");
  stageFactor = uniform(p, "u_stageFactor");
  static constexpr std::array<const char*, 3> kStageTextures = {
      "u_stageTexture1", "u_stageTexture2", "u_stageTexture3"};
  for (std::size_t i = 0; i < kStageTextures.size(); ++i)
    stageTexture[i] = uniform(p, kStageTextures[i]);
  textureModulates = uniform(p, "u_textureModulates");
  textureAfterLighting = uniform(p, "u_textureAfterLighting");
  flatShading = uniform(p, "u_flatShading");
  clipPlanes = uniform(p, "u_clipPlanes");
  lineType = uniform(p, "u_lineType");
  pointScale = uniform(p, "u_pointScale");
  pointSizeRange = uniform(p, "u_pointSizeRange");
  pointAttenuation = uniform(p, "u_pointAttenuation");
  hatchStyle = uniform(p, "u_hatchStyle");
  filled = uniform(p, "u_filled");
  hatchColor = uniform(p, "u_hatchColor");
  viewportSize = uniform(p, "u_viewportSize");
  separateBack = uniform(p, "u_separateBack");
  backDiffuseColor = uniform(p, "u_backDiffuseColor");
  backAmbientIntensity = uniform(p, "u_backAmbientIntensity");
  backSpecularColor = uniform(p, "u_backSpecularColor");
  backEmissiveColor = uniform(p, "u_backEmissiveColor");
  backShininess = uniform(p, "u_backShininess");
  backTransparency = uniform(p, "u_backTransparency");
  baseTexCoordSet = uniform(p, "u_baseTexCoordSet");
  mapTexCoordSet = uniform(p, "u_mapTexCoordSet");
  hasEnvironment = uniform(p, "u_hasEnvironment");
  hasEnvironmentMap = uniform(p, "u_hasEnvironmentMap");
  environmentMap = uniform(p, "u_environmentMap");
  environmentSh = uniform(p, "u_environmentSh");
  environmentColor = uniform(p, "u_environmentColor");
  environmentAmbient = uniform(p, "u_environmentAmbient");
  environmentMaxLod = uniform(p, "u_environmentMaxLod");
  eyeToEnvironment = uniform(p, "u_eyeToEnvironment");
  modelView = uniform(p, "u_modelView");
  projection = uniform(p, "u_projection");
  normalMatrix = uniform(p, "u_normalMatrix");
  textureMatrix = uniform(p, "u_textureMatrix");
  pointSize = uniform(p, "u_pointSize");
  lit = uniform(p, "u_lit");
  hasColor = uniform(p, "u_hasColor");
  textureComponents = uniform(p, "u_textureComponents");
  texture = uniform(p, "u_texture");
  diffuseColor = uniform(p, "u_diffuseColor");
  ambientIntensity = uniform(p, "u_ambientIntensity");
  specularColor = uniform(p, "u_specularColor");
  emissiveColor = uniform(p, "u_emissiveColor");
  shininess = uniform(p, "u_shininess");
  transparency = uniform(p, "u_transparency");
  unlitColor = uniform(p, "u_unlitColor");
  lightCount = uniform(p, "u_lightCount");
  lightType = uniform(p, "u_lightType");
  lightColor = uniform(p, "u_lightColor");
  lightIntensity = uniform(p, "u_lightIntensity");
  lightAmbientIntensity = uniform(p, "u_lightAmbientIntensity");
  lightPosition = uniform(p, "u_lightPosition");
  lightDirection = uniform(p, "u_lightDirection");
  lightAttenuation = uniform(p, "u_lightAttenuation");
  lightRadius = uniform(p, "u_lightRadius");
  lightBeamWidth = uniform(p, "u_lightBeamWidth");
  lightCutOffAngle = uniform(p, "u_lightCutOffAngle");
  fogType = uniform(p, "u_fogType");
  fogColor = uniform(p, "u_fogColor");
  fogVisibilityRange = uniform(p, "u_fogVisibilityRange");
  fogPlane = uniform(p, "u_fogPlane");
  projectors.find(p);
}

std::uint64_t SurfaceVariant::key() const {
  std::uint64_t k = (lit ? 1u : 0u) | (hasColor ? 2u : 0u) |
                    (static_cast<std::uint32_t>(textureComponents & 7) << 2) |
                    (static_cast<std::uint32_t>(fogType & 3) << 5) |
                    (static_cast<std::uint32_t>(lightCount & 15) << 7);
  for (int i = 0; i < lightCount && i < kMaxLights; ++i)
    k |= static_cast<std::uint64_t>(lightTypes[static_cast<std::size_t>(i)] & 3) << (11 + 2 * i);
  k |= std::uint64_t{separateBack ? 1u : 0u} << 27 |
       std::uint64_t{textureModulates ? 1u : 0u} << 28 |
       static_cast<std::uint64_t>(clipPlanes & 7) << 29 |
       static_cast<std::uint64_t>(textureStages & 7) << 32 |
       static_cast<std::uint64_t>(texGen & 15) << 35 |
       static_cast<std::uint64_t>(cubeMap & 7) << 39 | std::uint64_t{texture3D ? 1u : 0u} << 42 |
       static_cast<std::uint64_t>(lineType & 7) << 43 |
       static_cast<std::uint64_t>(hatchStyle & 7) << 46 | std::uint64_t{unfilled ? 1u : 0u} << 49;
  return k;
}

std::string SurfaceVariant::defines() const {
  std::string types;
  for (int i = 0; i < kMaxLights; ++i)
    types += (i ? ", " : "") +
             std::to_string(i < lightCount ? lightTypes[static_cast<std::size_t>(i)] : 0);
  return "#define GS_VARIANT 1\n#define GS_LIT " + std::string(lit ? "true" : "false") +
         "\n#define GS_HAS_COLOR " + (hasColor ? "true" : "false") +
         "\n#define GS_TEXTURE_COMPONENTS " + std::to_string(textureComponents) +
         "\n#define GS_FOG_TYPE " + std::to_string(fogType) + "\n#define GS_LIGHT_COUNT " +
         std::to_string(lightCount) + "\n#define GS_LIGHT_TYPES " + types +
         "\n#define GS_SEPARATE_BACK " + (separateBack ? "true" : "false") +
         "\n#define GS_TEXTURE_MODULATES " + (textureModulates ? "true" : "false") +
         "\n#define GS_CLIP_PLANES " + std::to_string(clipPlanes) + "\n#define GS_STAGE_COUNT " +
         std::to_string(textureStages) + "\n#define GS_TEX_GEN " + std::to_string(texGen) +
         "\n#define GS_CUBE_MAP " + std::to_string(cubeMap) + "\n#define GS_TEXTURE_3D " +
         (texture3D ? "true" : "false") + "\n#define GS_LINE_TYPE " + std::to_string(lineType) +
         "\n#define GS_HATCH_STYLE " + std::to_string(hatchStyle) + "\n#define GS_FILLED " +
         (unfilled ? "false" : "true") + "\n";
}

void SurfacePrograms::beginFrame() {
  ++frame_;
  builtThisFrame_ = 0;
}

SurfaceProgram& SurfacePrograms::generic() {
  if (generic_.id == 0) {
    generic_.id = buildProgram("surface", kSurfaceVertexShader, kSurfaceFragmentShader);
    generic_.u.find(generic_.id);
  }
  return generic_;
}

SurfaceProgram& SurfacePrograms::physical() {
  if (physical_.id == 0) {
    physical_.id = buildProgram("physical", kSurfaceVertexShader, kPhysicalFragmentShader);
    physical_.u.find(physical_.id);
  }
  return physical_;
}

SurfaceProgram& SurfacePrograms::phong(const SurfaceVariant& v) {
  const std::uint64_t key = v.key();
  if (const auto it = variants_.find(key); it != variants_.end()) return it->second;
  if (!variantsEnabled_ || frame_ <= 1 || builtThisFrame_ >= kVariantsPerFrame) return generic();
  ++builtThisFrame_;
  // The defines go after the #version line, which must come first.
  const auto specialize = [&](std::string_view source) {
    const std::size_t eol = source.find('\n') + 1;
    return std::string(source.substr(0, eol)) + v.defines() + std::string(source.substr(eol));
  };
  const std::string vertex = specialize(kSurfaceVertexShader);
  const std::string fragment = specialize(kSurfaceFragmentShader);
  SurfaceProgram p;
  p.id = buildProgram("surface variant", vertex.c_str(), fragment.c_str());
  p.u.find(p.id);
  return variants_.emplace(key, p).first->second;
}

void SurfacePrograms::release() {
  for (SurfaceProgram* p : {&generic_, &physical_})
    if (p->id != 0) {
      glDeleteProgram(p->id);
      *p = {};
    }
  for (auto& [key, p] : variants_) glDeleteProgram(p.id);
  variants_.clear();
}

}  // namespace gs::render::detail
