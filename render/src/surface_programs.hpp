// Private to render/: the surface programs SceneRenderer draws with, and their uniform
// locations: the generic VRML97 (Phong) program, its specialized variants, and the
// physically based program (shaders.cpp, shaders_physical.cpp).
//
// A variant is the Phong program compiled with what a shape uses as constants (lit or not,
// colour per vertex, the texture's component count, the fog type, the number and kinds of
// its lights): llvmpipe, which runs the fragment shader for every pixel on the CPU, then
// runs straight-line code instead of a loop over eight lights with branches on uniforms.
// The pixels are those of the generic program (the same expressions, only constants
// folded). Variants are compiled lazily, a few per frame and none in a renderer's first
// frame, so the first picture costs no compiles beyond the generic program's; until its
// variant exists a shape is drawn by the generic program. Which program draws a frame
// depends only on the frame count, never on time: the same command gives the same pixels.
#pragma once

#include "gl_program.hpp"
#include "texture_projectors.hpp"

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <unordered_map>

namespace gs::render::detail {

/// Maps a PhysicalMaterial has beyond its base texture (texture units 1-4).
inline constexpr std::size_t kPhysicalMapCount = 4;

/// Uniform locations of one surface program (-1 for those it lacks: a variant has no
/// u_lit ... u_fogType; the Phong programs have none of the physical program's own).
struct SurfaceUniforms {
  GLint modelView, projection, normalMatrix, textureMatrix, pointSize;
  GLint lit, hasColor, textureComponents, texture;
  GLint diffuseColor, ambientIntensity, specularColor, emissiveColor, shininess, transparency,
      unlitColor;
  GLint lightCount, lightType, lightColor, lightIntensity, lightAmbientIntensity, lightPosition,
      lightDirection, lightAttenuation, lightRadius, lightBeamWidth, lightCutOffAngle;
  GLint fogType, fogColor, fogVisibilityRange, fogPlane;
  GLint metallic, roughness, normalScale, occlusionStrength, alphaMode, alphaCutoff;
  std::array<GLint, kPhysicalMapCount> hasMap, map;
  GLint hasEnvironment, hasEnvironmentMap, environmentMap, environmentSh, environmentColor,
      environmentAmbient, environmentMaxLod, eyeToEnvironment;
  GLint baseTexCoordSet, mapTexCoordSet;
  GLint clipPlaneCount, clipPlanes, textureModulates, textureAfterLighting, flatShading;
  // A MultiTexture's stages (multi_texture.hpp): units 1..3 for stages 1..3.
  GLint stageCount, stageMode, stageSource, stageFunction, stageTexCoord, stageMatrix, stageFactor;
  std::array<GLint, 3> stageTexture;
  GLint texGen, texGenParameter, eyeToWorld;  // TextureCoordinateGenerator
  GLint cubeMap, cubeTexture;                 // a ComposedCubeMapTexture on unit 6
  GLint texture3DOn, texture3D, textureMatrix3D, texBoundsMin, texBoundsSize;  // unit 7
  GLint lineType, hatchStyle, filled, hatchColor, viewportSize;  // line_fill_properties
  GLint pointScale, pointSizeRange, pointAttenuation;            // PointProperties
  GLint separateBack, backDiffuseColor, backAmbientIntensity, backSpecularColor, backEmissiveColor,
      backShininess, backTransparency;
  ProjectorUniformLocations projectors;  // X3D TextureProjectors (texture_projectors.hpp)

  /// Looks every location up in linked program `p`.
  void find(GLuint p);
};

/// What a specialized Phong variant fixes at compile time.
struct SurfaceVariant {
  bool lit = false;
  bool hasColor = false;
  int textureComponents = 0;                          // 0 (none) .. 4
  int fogType = 0;                                    // 0 none, 1 LINEAR, 2 EXPONENTIAL
  int lightCount = 0;                                 // 0 .. kMaxLights; 0 when not lit
  std::array<std::uint8_t, kMaxLights> lightTypes{};  // 0 directional, 1 point, 2 spot
  bool separateBack = false;                          // TwoSidedMaterial with separateBackColor
  bool textureModulates = false;                      // Material.diffuseTexture
  int clipPlanes = 0;                                 // 0 .. 6 ClipPlanes
  int textureStages = 0;                              // 0 .. 4 MultiTexture stages
  int texGen = 0;                                     // TexGenMode (texture_generation.hpp)
  int cubeMap = 0;         // 0 none, else the lookup direction (shaders.cpp, cubeDirection)
  bool texture3D = false;  // an X3D Texturing3D texture
  int lineType = 1;        // LineProperties.linetype, 1 .. 5 (line_fill_properties.hpp)
  int hatchStyle = 0;      // FillProperties hatch style, 0 (none) .. 6
  bool unfilled = false;   // FillProperties.filled FALSE

  /// A number naming the variant (equal keys, equal variants).
  std::uint64_t key() const;
  /// The `#define` lines that turn kSurfaceFragmentShader into this variant.
  std::string defines() const;
};

/// A linked program, its uniforms, and the frame whose per-frame uniforms it holds.
struct SurfaceProgram {
  GLuint id = 0;
  SurfaceUniforms u{};
  std::uint64_t frameSet = 0;
};

/// The surface programs of one GL context. Needs that context current in every call.
class SurfacePrograms {
 public:
  /// Variants compiled at most in one frame (each costs llvmpipe some 20-60 ms).
  static constexpr int kVariantsPerFrame = 4;

  /// Starts a frame (frame() counts from 1).
  void beginFrame();
  std::uint64_t frame() const { return frame_; }
  /// The generic Phong program, built on first use.
  SurfaceProgram& generic();
  /// The PhysicalMaterial program, built on first use.
  SurfaceProgram& physical();
  /// The program for a Phong shape using `v`: its variant when built or buildable within
  /// this frame's budget (never in frame 1), else generic().
  SurfaceProgram& phong(const SurfaceVariant& v);
  /// false: phong() always answers generic() (SceneRendererOptions::shaderVariants).
  void enableVariants(bool on) { variantsEnabled_ = on; }
  /// Variants built so far (for statistics and tests).
  std::size_t variantCount() const { return variants_.size(); }
  /// Deletes every program.
  void release();

 private:
  SurfaceProgram generic_, physical_;
  std::unordered_map<std::uint64_t, SurfaceProgram> variants_;
  std::uint64_t frame_ = 0;
  int builtThisFrame_ = 0;
  bool variantsEnabled_ = true;
};

}  // namespace gs::render::detail
