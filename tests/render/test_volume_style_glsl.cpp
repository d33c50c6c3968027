// X3D volume render styles as X_ITE 15's GLSL (render/src/volume_style_glsl.hpp): which
// data nodes need the ray caster, the field values baked as constants, disabled styles,
// and the samplers a style lists. Text only: no GL context.
#include "../../render/src/volume_style_glsl.hpp"
#include "encodings/parser.hpp"

#include <catch2/catch.hpp>

#include <memory>
#include <string>

namespace {

using gs::render::detail::needsVolumeRaycast;
using gs::render::detail::volumeStyleGlsl;
using gs::render::detail::VolumeStyleGlsl;

std::shared_ptr<gs::vrml::Scene> volumeStyleWorld(const std::string& body) {
  auto scene = std::make_shared<gs::vrml::Scene>(
      gs::vrml::parseVrml("#X3D V4.0 utf8\nPROFILE Full\n" + body, "v.x3dv"));
  REQUIRE(scene->diagnostics.items.empty());
  REQUIRE(!scene->rootNodes.empty());
  return scene;
}

/// A VolumeData of 2x2x2 voxels with `style` as its renderStyle ("" for none).
std::string volumeStyleData(const std::string& style) {
  return "VolumeData { voxels PixelTexture3D { image [ 1 2 2 2 0 255 0 255 0 255 0 255 ] }" +
         (style.empty() ? std::string() : " renderStyle " + style) + " }";
}

bool volumeStyleHas(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

TEST_CASE("volume styles: which data nodes need the ray caster", "[render][volume]") {
  const auto need = [](const std::string& body) {
    auto scene = volumeStyleWorld(body);
    return needsVolumeRaycast(*scene->rootNodes[0]);
  };
  CHECK_FALSE(need(volumeStyleData("")));
  CHECK_FALSE(need(volumeStyleData("OpacityMapVolumeStyle { }")));
  CHECK_FALSE(need(volumeStyleData(
      "OpacityMapVolumeStyle { transferFunction PixelTexture { image 2 1 2 0x0000 0xffff } }")));
  CHECK(need(volumeStyleData("BoundaryEnhancementVolumeStyle { }")));
  CHECK(need(volumeStyleData("CartoonVolumeStyle { }")));
  CHECK(need(volumeStyleData("EdgeEnhancementVolumeStyle { }")));
  CHECK(need(volumeStyleData("ProjectionVolumeStyle { }")));
  CHECK(need(volumeStyleData("ShadedVolumeStyle { }")));
  CHECK(need(volumeStyleData("SilhouetteEnhancementVolumeStyle { }")));
  CHECK(need(volumeStyleData("ToneMappedVolumeStyle { }")));
  CHECK(need(volumeStyleData("ComposedVolumeStyle { renderStyle [ CartoonVolumeStyle { } ] }")));
  CHECK(need(volumeStyleData("BlendedVolumeStyle { voxels PixelTexture3D { } }")));
  CHECK_FALSE(need(volumeStyleData("CartoonVolumeStyle { enabled FALSE }")));

  CHECK_FALSE(need("SegmentedVolumeData { }"));
  CHECK_FALSE(need("SegmentedVolumeData { renderStyle [ OpacityMapVolumeStyle { } ] }"));
  CHECK(
      need("SegmentedVolumeData { renderStyle [ OpacityMapVolumeStyle { } "
           "ShadedVolumeStyle { } ] }"));
  CHECK(need("SegmentedVolumeData { segmentIdentifiers PixelTexture3D { } }"));

  CHECK_FALSE(need("IsoSurfaceVolumeData { surfaceValues 0.5 }"));
  CHECK(need("IsoSurfaceVolumeData { surfaceValues 0.5 renderStyle OpacityMapVolumeStyle { } }"));
}

TEST_CASE("volume styles: field values are baked as constants", "[render][volume]") {
  auto scene = volumeStyleWorld(volumeStyleData(R"(ComposedVolumeStyle { renderStyle [
    CartoonVolumeStyle { colorSteps 5 orthogonalColor 1 0.5 0.25 1 }
    BoundaryEnhancementVolumeStyle { retainedOpacity 0.3 opacityFactor 3 }
    EdgeEnhancementVolumeStyle { gradientThreshold 0.125 }
    SilhouetteEnhancementVolumeStyle { silhouetteSharpness 4 }
    ToneMappedVolumeStyle { warmColor 1 0 0 1 }
    ShadedVolumeStyle { lighting TRUE material Material { shininess 0.5 } }
  ] })"));
  const VolumeStyleGlsl g = volumeStyleGlsl(*scene->rootNodes[0]);
  // Each style numbered in turn (1 is X_ITE's default opacity map).
  CHECK(volumeStyleHas(g.uniforms, "const int  colorSteps_2 = 5;"));
  CHECK(volumeStyleHas(g.uniforms, "const vec4 orthogonalColor_2 = vec4 (1.0, 0.5, 0.25, 1.0);"));
  CHECK(volumeStyleHas(g.uniforms, "const float retainedOpacity_3 = 0.3;"));
  CHECK(volumeStyleHas(g.uniforms, "const float boundaryOpacity_3 = 0.9;"));
  CHECK(volumeStyleHas(g.uniforms, "const float opacityFactor_3 = 3.0;"));
  CHECK(volumeStyleHas(g.uniforms, "const float gradientThreshold_4 = 0.125;"));
  CHECK(volumeStyleHas(g.uniforms, "const float silhouetteSharpness_5 = 4.0;"));
  CHECK(volumeStyleHas(g.uniforms, "const vec4 warmColor_6 = vec4 (1.0, 0.0, 0.0, 1.0);"));
  CHECK(volumeStyleHas(g.uniforms, "const float shininess_7 = 0.5;"));
  CHECK(volumeStyleHas(g.uniforms, "const vec3  diffuseColor_7 = vec3 (0.8, 0.8, 0.8);"));
  // No style uniform but the lit Shaded style's light matrices; the helpers its styles need.
  CHECK_FALSE(volumeStyleHas(g.uniforms, "uniform float"));
  CHECK_FALSE(volumeStyleHas(g.uniforms, "uniform int"));
  CHECK_FALSE(volumeStyleHas(g.uniforms, "uniform vec"));
  CHECK(volumeStyleHas(g.uniforms, "uniform mat3 x3d_LightMatrix [8];"));
  CHECK(g.samplers.empty());
  CHECK(g.defines == "#define X3D_HSV\n#define X3D_SHADING\n");
  CHECK(volumeStyleHas(g.uniforms, "rgb2hsv (in vec3 color)"));
  CHECK(volumeStyleHas(g.uniforms, "getSpotFactor (const in float cutOffAngle"));
  CHECK_FALSE(volumeStyleHas(g.uniforms, "struct Plane3"));
  // The default opacity map, then the composed style.
  CHECK(volumeStyleHas(g.functions, "textureColor = getOpacityMapStyle_1 (textureColor);"));
  CHECK(volumeStyleHas(g.functions, "textureColor = getComposedStyle_8 (textureColor, texCoord);"));
  CHECK(g.functions.find("getOpacityMapStyle_1") < g.functions.find("getComposedStyle_8"));
}

TEST_CASE("volume styles: a disabled style generates nothing", "[render][volume]") {
  auto bare = volumeStyleWorld(volumeStyleData(""));
  const VolumeStyleGlsl none = volumeStyleGlsl(*bare->rootNodes[0]);
  for (const char* style :
       {"CartoonVolumeStyle { enabled FALSE colorSteps 7 }",
        "ProjectionVolumeStyle { enabled FALSE }",
        "ShadedVolumeStyle { enabled FALSE lighting TRUE }",
        "OpacityMapVolumeStyle { enabled FALSE transferFunction PixelTexture { image 1 1 1 0xff } "
        "}",
        "ComposedVolumeStyle { enabled FALSE renderStyle [ CartoonVolumeStyle { } ] }",
        "ComposedVolumeStyle { renderStyle [ ] }"}) {
    INFO(style);
    auto scene = volumeStyleWorld(volumeStyleData(style));
    const VolumeStyleGlsl g = volumeStyleGlsl(*scene->rootNodes[0]);
    CHECK(g.defines.empty());
    CHECK(g.samplers.empty());
    if (std::string(style) != "ComposedVolumeStyle { renderStyle [ ] }") {
      CHECK(g.uniforms == none.uniforms);
      CHECK(g.functions == none.functions);
    }
  }
  // Inside a ComposedVolumeStyle, a disabled child leaves the composition empty.
  auto scene = volumeStyleWorld(volumeStyleData(
      "ComposedVolumeStyle { renderStyle [ CartoonVolumeStyle { enabled FALSE } ] }"));
  const VolumeStyleGlsl g = volumeStyleGlsl(*scene->rootNodes[0]);
  CHECK_FALSE(volumeStyleHas(g.uniforms, "Cartoon"));
  CHECK(volumeStyleHas(g.uniforms, "getComposedStyle_2"));
  CHECK(g.defines.empty());
}

TEST_CASE("volume styles: samplers of transfer functions, normals and volumes",
          "[render][volume]") {
  auto scene = volumeStyleWorld(
      volumeStyleData("OpacityMapVolumeStyle { transferFunction DEF TF PixelTexture { image 2 1 "
                      "2 0x0000 0xffff } }"));
  const VolumeStyleGlsl g = volumeStyleGlsl(*scene->rootNodes[0]);
  REQUIRE(g.samplers.size() == 1);
  CHECK(g.samplers[0].uniform == "transferFunction_2");
  CHECK(g.samplers[0].dimensions == 2);
  REQUIRE(g.samplers[0].texture != nullptr);
  CHECK(g.samplers[0].texture->typeId() == gs::vrml::NodeTypeId::PixelTexture);
  CHECK(volumeStyleHas(g.uniforms, "uniform sampler2D transferFunction_2;"));
  CHECK(volumeStyleHas(g.uniforms, "texture (transferFunction_2, originalColor .rg)"));
  // X_ITE's default map comes first and is a formula, not a sampler.
  CHECK(volumeStyleHas(g.functions, "textureColor = getOpacityMapStyle_1 (textureColor);"));
  CHECK(volumeStyleHas(g.functions, "textureColor = getOpacityMapStyle_2 (textureColor);"));

  auto normals = volumeStyleWorld(
      volumeStyleData("SilhouetteEnhancementVolumeStyle { surfaceNormals PixelTexture3D { } }"));
  const VolumeStyleGlsl n = volumeStyleGlsl(*normals->rootNodes[0]);
  REQUIRE(n.samplers.size() == 1);
  CHECK(n.samplers[0].uniform == "surfaceNormals_2");
  CHECK(n.samplers[0].dimensions == 3);

  // BlendedVolumeStyle: its voxels, its table, its style on its voxels.
  auto blended = volumeStyleWorld(volumeStyleData(R"(BlendedVolumeStyle {
    weightFunction1 "TABLE" weightTransferFunction1 PixelTexture { image 1 1 1 0x80 }
    weightFunction2 "ALPHA1" weightConstant2 0.25
    renderStyle EdgeEnhancementVolumeStyle { }
    voxels PixelTexture3D { image [ 1 1 1 1 0x80 ] } })"));
  const VolumeStyleGlsl b = volumeStyleGlsl(*blended->rootNodes[0]);
  REQUIRE(b.samplers.size() == 2);
  CHECK(b.samplers[0].uniform == "weightTransferFunction1_2");
  CHECK(b.samplers[0].dimensions == 2);
  CHECK(b.samplers[1].uniform == "voxels_2");
  CHECK(b.samplers[1].dimensions == 3);
  CHECK(volumeStyleHas(b.uniforms, "const float weightConstant2_2 = 0.25;"));
  CHECK(volumeStyleHas(b.uniforms, "float w2_2 = blendColor_2 .a;"));
  CHECK(volumeStyleHas(b.uniforms, "textureSize (voxels_2, 0)"));
  CHECK_FALSE(volumeStyleHas(b.uniforms, "x3d_Texture3D"));
  CHECK(volumeStyleHas(b.uniforms,
                       "blendColor_2 = getEdgeEnhacementStyle_4 (blendColor_2, texCoord);"));

  // SegmentedVolumeData's identifiers; IsoSurfaceVolumeData's gradients.
  auto segmented = volumeStyleWorld(
      "SegmentedVolumeData { segmentEnabled [ TRUE FALSE ] segmentIdentifiers PixelTexture3D { } "
      "renderStyle [ CartoonVolumeStyle { } ToneMappedVolumeStyle { } ] }");
  const VolumeStyleGlsl s = volumeStyleGlsl(*segmented->rootNodes[0]);
  REQUIRE(s.samplers.size() == 1);
  CHECK(s.samplers[0].uniform == "segmentIdentifiers_2");
  // A disabled segment's samples are transparent (X_ITE discards them; in the ray caster's
  // march a discard would end the ray).
  CHECK(volumeStyleHas(s.functions, "case 1:\n      {\n         return vec4 (0.0);"));
  CHECK_FALSE(volumeStyleHas(s.functions, "discard"));
  CHECK_FALSE(volumeStyleHas(s.uniforms, "ToneMapped"));

  auto iso = volumeStyleWorld(
      "IsoSurfaceVolumeData { surfaceValues [ 0.25 0.75 ] surfaceTolerance 0.125 "
      "gradients PixelTexture3D { } renderStyle [ ShadedVolumeStyle { } ] }");
  const VolumeStyleGlsl i = volumeStyleGlsl(*iso->rootNodes[0]);
  REQUIRE(i.samplers.size() == 1);
  CHECK(i.samplers[0].uniform == "gradients_2");
  CHECK(volumeStyleHas(i.uniforms, "const float surfaceValues_2 [2] = float [2] (0.25, 0.75);"));
  CHECK(volumeStyleHas(i.uniforms, "const float surfaceTolerance_2 = 0.125;"));
  CHECK(volumeStyleHas(i.functions, "else if (intensity > surfaceValues_2 [1])"));
}

TEST_CASE("volume styles: IsoSurfaceVolumeData contours as X_ITE writes them", "[render][volume]") {
  // One value and a step: X_ITE keeps the lowest contour above 0 only (0.5 - 2 * 0.2).
  auto scene = volumeStyleWorld("IsoSurfaceVolumeData { surfaceValues 0.5 contourStepSize 0.2 }");
  const VolumeStyleGlsl g = volumeStyleGlsl(*scene->rootNodes[0]);
  CHECK(volumeStyleHas(g.functions, "else if (intensity > 0.09999999999999998)"));
  CHECK(volumeStyleHas(g.functions, "return vec4 (0.0);"));  // off the contours
  CHECK_FALSE(volumeStyleHas(g.functions, "discard"));
  CHECK(volumeStyleHas(g.uniforms, "getNormal_2 (in vec3 texCoord)"));
}
