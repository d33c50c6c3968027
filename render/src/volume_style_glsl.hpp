// Private to render/: X3D volume render styles (ISO/IEC 19775-1 X3D 4.0 clause 41) as
// X_ITE 15 writes them in GLSL, for the volume ray caster (docs/x3d-volume-styles.md).
//
// X_ITE builds the fragment shader of a volume data node from three pieces: the #defines
// its styles ask for (X3D_HSV, X3D_PLANE, X3D_SHADING), the declarations and functions
// of its styles (__VOLUME_STYLES_UNIFORMS__), and the statements that transform `vec4
// textureColor` sampled at `vec3 texCoord` inside getTextureColor()
// (__VOLUME_STYLES_FUNCTIONS__). volumeStyleGlsl() writes the same three pieces with
// X_ITE's formulas, with these differences:
//
// - A field value X_ITE passes as a uniform is a `const` of the GLSL instead (`const float
//   retainedOpacity_3 = 0.2;`): the C++ side sets no style uniform, only the samplers
//   listed in VolumeStyleGlsl::samplers.
// - Names carry a counter of style occurrences (1, 2, ... per call) instead of X_ITE's
//   node ids, so a style USEd twice gets two copies instead of two clashing definitions.
// - The helper functions VolumeStyle.fs keeps under #if defined(X3D_HSV) / X3D_PLANE /
//   X3D_SHADING (rgb2hsv, hsv2rgb, mix_hsv; Plane3; getSpotFactor) come first in
//   `uniforms` when a style needs them.
// - X_ITE's default transfer function (a 256 x 1 luminance-alpha texture, texel i = (i, i))
//   is a formula: what its linear filter reads at level 0.
// - Where X_ITE discards a sample (IsoSurfaceVolumeData away from its surfaces, a disabled
//   segment), the code returns transparent black instead: X_ITE discards one slice's
//   fragment, while in the ray caster's march a discard would end the whole ray.
// - Where X_ITE's GLSL would not compile (BlendedVolumeStyle's ALPHA1 weight; the
//   defines of a style inside a BlendedVolumeStyle), the code is what X_ITE evidently
//   meant; the .cpp says where.
//
// The code is written against this prelude of the ray caster (GLSL 3.30 core):
// `uniform sampler3D x3d_Texture3D[1]` (the voxels, (v, v, v, 1)), `uniform mat3
// x3d_TextureNormalMatrix`, X3D_NUM_LIGHTS (0..8), x3d_DirectionalLight / x3d_PointLight /
// x3d_SpotLight, `struct x3d_LightSourceParameters` and `uniform x3d_LightSourceParameters
// x3d_LightSource[8]` in eye space, M_PI, M_SQRT2, M_SQRT1_2, and the global `vec3 vertex`
// (the sample's eye-space position). A lit ShadedVolumeStyle also declares `uniform mat3
// x3d_LightMatrix[8]`: X_ITE's x3d_LightSource[i].matrix, the inverse of the upper-left
// 3x3 of light i's model-view matrix (eye-space vectors to the light's own coordinates,
// where its radius is measured).
#pragma once

#include "vrml/node.hpp"

#include <string>
#include <string_view>
#include <vector>

namespace gs::render::detail {

/// A texture a style's GLSL samples, bound by the ray caster.
struct VolumeStyleSampler {
  std::string uniform;                  // the sampler's uniform name in the generated GLSL
  const vrml::Node* texture = nullptr;  // the texture node (an X3DTexture2DNode for 2D, an
                                        // X3DTexture3DNode for 3D)
  int dimensions = 2;                   // 2: sampler2D, 3: sampler3D
};

/// The style code of one volume data node, in X_ITE's three pieces.
struct VolumeStyleGlsl {
  std::string defines;    // #define lines (X3D_HSV, X3D_PLANE, X3D_SHADING), one per line
  std::string uniforms;   // helper functions, sampler uniforms, constants, style functions
  std::string functions;  // statements that transform `vec4 textureColor` at `vec3 texCoord`
  std::vector<VolumeStyleSampler> samplers;  // every sampler `uniforms` declares
};

/// X_ITE 15's style code for volume data node `volumeData` (VolumeData, SegmentedVolumeData
/// or IsoSurfaceVolumeData, with their renderStyle and other fields): X_ITE's default
/// OpacityMapVolumeStyle, then the node's styles as its createShader() arranges them
/// (SegmentedVolumeData: one per segment; IsoSurfaceVolumeData: its surfaces, each with its
/// style). A disabled style (`enabled FALSE`) contributes nothing. Any other node gives
/// the default OpacityMapVolumeStyle alone.
VolumeStyleGlsl volumeStyleGlsl(const vrml::Node& volumeData);

/// Whether `volumeData` needs the ray caster rather than the splats of volume_data.hpp:
/// an enabled style in its renderStyle other than OpacityMapVolumeStyle (a
/// ComposedVolumeStyle or BlendedVolumeStyle counts as one), a SegmentedVolumeData with
/// segmentIdentifiers, or an IsoSurfaceVolumeData with any renderStyle.
bool needsVolumeRaycast(const vrml::Node& volumeData);

// ---- Shared by volume_style_glsl.cpp (helpers, data nodes) and
// ---- volume_style_glsl_styles.cpp (the style nodes); not for other callers.

/// A GLSL float literal of `v` (as a float when `single`): the shortest decimal that
/// reads back as it, always with a '.' or an exponent (NaN reads as 0, infinities as the
/// largest float).
std::string volumeStyleFloat(double v, bool single = true);
/// X_ITE's getNormal_@ from the voxels: central differences one texel apart, pointing to
/// lower values, turned to eye space by x3d_TextureNormalMatrix; w the difference's length.
inline constexpr std::string_view kVolumeStyleGradientNormal = R"(
vec4
getNormal_@ (in vec3 texCoord)
{
   vec4  offset = vec4 (1.0 / vec3 (textureSize (x3d_Texture3D [0], 0)), 0.0);
   float i0     = texture (x3d_Texture3D [0], texCoord + offset .xww) .r;
   float i1     = texture (x3d_Texture3D [0], texCoord - offset .xww) .r;
   float i2     = texture (x3d_Texture3D [0], texCoord + offset .wyw) .r;
   float i3     = texture (x3d_Texture3D [0], texCoord - offset .wyw) .r;
   float i4     = texture (x3d_Texture3D [0], texCoord + offset .wwz) .r;
   float i5     = texture (x3d_Texture3D [0], texCoord - offset .wwz) .r;
   vec3  n      = vec3 (i1 - i0, i3 - i2, i5 - i4);

   return vec4 (normalize (x3d_TextureNormalMatrix * n), length (n));
}
)";
/// `text` with every '@' replaced by `id` (the style's number where X_ITE puts getId()).
std::string volumeStyleText(std::string_view text, const std::string& id);
/// The node of `p` when X_ITE's X3DCast to abstract type `t` keeps it (not NULL, resolved,
/// of that type), else null.
const vrml::Node* volumeStyleCast(const vrml::NodePtr& p, vrml::AbstractType t);
/// A style's `enabled` field (TRUE when it has none).
bool volumeStyleEnabled(const vrml::Node& style);
/// The composable styles of `n`'s MFNode field renderStyle, in order: those X_ITE's X3DCast
/// to X3DComposableVolumeRenderStyleNode keeps (numbered so by SegmentedVolumeData and
/// IsoSurfaceVolumeData).
std::vector<const vrml::Node*> volumeStyleComposables(const vrml::Node& n);

/// The GLSL of one style occurrence: X_ITE's getUniformsText and getFunctionsText.
struct VolumeStyleCode {
  std::string uniforms;
  std::string functions;
};

/// Writes the styles of one volume data node, numbering its names 1, 2, ... and collecting
/// the defines and samplers they need.
class VolumeStyleWriter {
 public:
  /// X_ITE's getDefines of a style: `line` ("#define X3D_HSV") once, in first-use order.
  void define(const std::string& line);
  /// Whether define() was given `line`.
  bool hasDefine(const std::string& line) const;
  /// The next number, as a string.
  std::string nextId() { return std::to_string(++counter_); }
  /// Lists sampler `uniform` of `texture` (`dimensions` 2 or 3) and returns its
  /// declaration line.
  std::string sampler(const std::string& uniform, const vrml::Node& texture, int dimensions);

  /// A style node as VolumeData's renderStyle (`projection`: ProjectionVolumeStyle too) or
  /// as a composable style of the others, `depth` styles deep; nothing for a disabled or
  /// unresolved style or another node.
  VolumeStyleCode style(const vrml::Node& node, bool projection, int depth);
  /// An OpacityMapVolumeStyle, or X_ITE's default one (getDefaultVolumeStyle,
  /// getDefaultBlendedVolumeStyle) when `node` is null.
  VolumeStyleCode opacityMap(const vrml::Node* node);

  /// The result: the defines; VolumeStyle.fs's helpers they switch on, then `uniforms`;
  /// `functions`; the samplers.
  VolumeStyleGlsl finish(std::string uniforms, std::string functions);

 private:
  std::string normalText(const vrml::Node& style, const std::string& id);
  VolumeStyleCode blended(const vrml::Node& node, int depth);
  VolumeStyleCode boundaryEnhancement(const vrml::Node& node);
  VolumeStyleCode cartoon(const vrml::Node& node);
  VolumeStyleCode composed(const vrml::Node& node, int depth);
  VolumeStyleCode edgeEnhancement(const vrml::Node& node);
  VolumeStyleCode projectionStyle(const vrml::Node& node);
  VolumeStyleCode shaded(const vrml::Node& node);
  VolumeStyleCode silhouetteEnhancement(const vrml::Node& node);
  VolumeStyleCode toneMapped(const vrml::Node& node);

  int counter_ = 0;
  bool lightMatrix_ = false;  // a lit ShadedVolumeStyle reads x3d_LightMatrix
  std::vector<std::string> defines_;
  std::vector<VolumeStyleSampler> samplers_;
};

}  // namespace gs::render::detail
