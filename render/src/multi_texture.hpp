// Private to render/: X3D's MultiTexture (ISO/IEC 19775-1 X3D 4.0 clause 18.4.3) read into
// the texture stages the Phong program combines (shaders.cpp, "Multi-texturing").
//
// Each stage i takes its texture (Arg1) and a source colour (Arg2: `source`, by default the
// previous stage's result, the diffuse colour with the material's alpha for the first
// stage) and combines them by `mode` (table 18.3), in RGB and alpha apart when a mode is
// written "RGBMODE / ALPHAMODE" (castle-model-viewer's extension); `function` then acts on
// that result (COMPLEMENT 1 - rgb, ALPHAREPLICATE rgb = alpha), as castle-model-viewer
// applies it.
// Arg1 is the stage's texture: REPLACE and SELECTARG1 take it, SELECTARG2 takes the source,
// SUBTRACT is texture - source, as castle-model-viewer reads the table. The result of the
// last stage is the shape's diffuse colour and alpha, which the lighting then uses.
#pragma once

#include "vrml/node.hpp"

#include <glm/glm.hpp>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace gs::render::detail {

/// Texture stages one shape combines: MultiTexture.texture entries past this are one
/// warning and not drawn (the units the Phong program samples: 0..3).
inline constexpr int kMaxTextureStages = 4;

/// MultiTexture.mode values (table 18.3), as the fragment shader numbers them.
enum class TextureMode : std::int32_t {
  modulate = 0,
  replace = 1,  // also SELECTARG1
  modulate2x = 2,
  modulate4x = 3,
  add = 4,
  addSigned = 5,
  addSigned2x = 6,
  subtract = 7,
  addSmooth = 8,
  blendDiffuseAlpha = 9,
  blendTextureAlpha = 10,
  blendFactorAlpha = 11,
  blendCurrentAlpha = 12,
  modulateAlphaAddColor = 13,
  modulateInvAlphaAddColor = 14,
  modulateInvColorAddAlpha = 15,
  off = 16,
  selectArg2 = 17,
  dotProduct3 = 18,
};

/// MultiTexture.source values: where Arg2 comes from.
enum class TextureSource : std::int32_t { previous = 0, diffuse = 1, specular = 2, factor = 3 };

/// MultiTexture.function values: what is done to a stage's result.
enum class TextureFunction : std::int32_t { none = 0, complement = 1, alphaReplicate = 2 };

struct TextureStage {
  const vrml::Node* texture = nullptr;  // an ImageTexture, PixelTexture or MovieTexture
  TextureMode rgbMode = TextureMode::modulate;
  TextureMode alphaMode = TextureMode::modulate;
  TextureSource source = TextureSource::previous;
  TextureFunction function = TextureFunction::none;
  /// The stage's texture transform: MultiTextureTransform's entry i, identity when it has
  /// fewer entries or the Appearance has a plain TextureTransform (clause 18.4.5).
  glm::mat3 matrix{1.0f};
};

struct MultiTextureStages {
  std::vector<TextureStage> stages;  // at most kMaxTextureStages
  /// MultiTexture.color and alpha: the FACTOR source and BLENDFACTORALPHA's alpha.
  glm::vec4 factor{1.0f};
  /// What could not be honoured (an unknown mode, source or function, more stages than
  /// kMaxTextureStages, a nested MultiTexture): one line each, for a warning.
  std::vector<std::string> problems;
};

/// Reads MultiTexture `multiTexture` with the Appearance's `textureTransform` (null: none).
/// Mode, source and function names are matched without regard to case; an empty or missing
/// mode is MODULATE, an empty or missing source the previous stage, an unknown one is
/// reported in `problems` and read as MODULATE / the previous stage / no function.
MultiTextureStages readMultiTexture(const vrml::Node& multiTexture,
                                    const vrml::Node* textureTransform);

/// The texture coordinate set (0 or 1, GpuMesh's two) stage `stage` reads: entry `stage` of
/// the geometry's MultiTextureCoordinate, its last entry when it has fewer (clause 18.4.4);
/// set 0 for any other geometry, or when the mesh has no second set.
int stageTexCoordSet(int stage, const vrml::Node& geometry, bool meshHasSecondSet);

}  // namespace gs::render::detail
