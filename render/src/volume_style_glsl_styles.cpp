// X3D volume render styles as X_ITE 15 writes them in GLSL (volume_style_glsl.hpp): the
// style nodes, each after X_ITE 15.0.1's getUniformsText / getFunctionsText
// (dist/assets/components/VolumeRenderingComponent.js), its field values baked as
// constants (`const float retainedOpacity_3 = 0.2;` where X_ITE has `uniform float
// retainedOpacity_3;`).
#include "volume_style_glsl.hpp"

#include <glm/glm.hpp>

#include <string_view>

namespace gs::render::detail {

namespace {

/// Nesting of BlendedVolumeStyle / ComposedVolumeStyle followed at most (a node cycle
/// made at run time would otherwise recurse for ever).
constexpr int kVolumeStyleMaxDepth = 32;

std::string volumeStyleVec3(const glm::vec3& v) {
  return "vec3 (" + volumeStyleFloat(v.x) + ", " + volumeStyleFloat(v.y) + ", " +
         volumeStyleFloat(v.z) + ")";
}

std::string volumeStyleVec4(const glm::vec4& v) {
  return "vec4 (" + volumeStyleFloat(v.x) + ", " + volumeStyleFloat(v.y) + ", " +
         volumeStyleFloat(v.z) + ", " + volumeStyleFloat(v.w) + ")";
}

/// `text` with every `from` replaced by `to` (X_ITE's String.replace with a /g pattern).
std::string volumeStyleReplace(std::string text, std::string_view from, std::string_view to) {
  for (std::size_t i = text.find(from); i != std::string::npos; i = text.find(from, i)) {
    text.replace(i, from.size(), to);
    i += to.size();
  }
  return text;
}

float volumeStyleFloatField(const vrml::Node& n, vrml::FieldName name, float fallback) {
  return n.get<vrml::FieldType::SFFloat>(name, fallback);
}

/// The GLSL constant of SFFloat field `name` of style `n` (its value, or `fallback`):
/// "const float NAME_ID = VALUE;", X_ITE's uniform of that field baked in.
std::string volumeStyleFloatConst(const vrml::Node& n, const std::string& name, float fallback,
                                  const std::string& id) {
  return "const float " + name + "_" + id + " = " +
         volumeStyleFloat(volumeStyleFloatField(n, name, fallback)) + ";\n";
}

glm::vec4 volumeStyleRgba(const vrml::Node& n, vrml::FieldName name, glm::vec4 fallback) {
  return n.get<vrml::FieldType::SFColorRGBA>(name, fallback);
}

glm::vec3 volumeStyleRgb(const vrml::Node& n, vrml::FieldName name, glm::vec3 fallback) {
  return n.get<vrml::FieldType::SFColor>(name, fallback);
}

const std::string& volumeStyleString(const vrml::Node& n, vrml::FieldName name) {
  static const std::string kEmpty;
  const vrml::FieldValue* f = n.field(name);
  return f != nullptr && f->type() == vrml::FieldType::SFString
             ? f->get<vrml::FieldType::SFString>()
             : kEmpty;
}

/// X_ITE's getFunctionsText of a style: `textureColor = <function>_<id> (textureColor,
/// texCoord);` under the style's name.
std::string volumeStyleCall(std::string_view comment, std::string_view function,
                            const std::string& id) {
  return "\n   // " + std::string(comment) + "\n\n   textureColor = " + std::string(function) +
         "_" + id + " (textureColor, texCoord);\n";
}

/// One of BlendedVolumeStyle's weights, X_ITE's switch on weightFunction1 / 2 (`n`).
std::string volumeStyleBlendWeight(const vrml::Node& node, int n, const std::string& id,
                                   bool table) {
  const std::string k = std::to_string(n);
  const std::string w = "   float w" + k + "_" + id + " = ";
  const std::string& f = n == 1 ? volumeStyleString(node, "weightFunction1")
                                : volumeStyleString(node, "weightFunction2");
  if (f == "ALPHA0") return w + "originalColor .a;\n";
  // X_ITE writes "blendColor_ " + id here (a space inside the name), which does not
  // compile; the blended volume's alpha is what it evidently means.
  if (f == "ALPHA1") return w + "blendColor_" + id + " .a;\n";
  if (f == "ONE_MINUS_ALPHA0") return w + "1.0 - originalColor .a;\n";
  // Same space in X_ITE as for ALPHA1.
  if (f == "ONE_MINUS_ALPHA1") return w + "1.0 - blendColor_" + id + " .a;\n";
  if (f == "TABLE" && table)
    return w + "texture (weightTransferFunction" + k + "_" + id + ", vec2 (originalColor .a, " +
           "blendColor_" + id + " .a)) .r;\n";
  return w + "weightConstant" + k + "_" + id + ";\n";  // CONSTANT, TABLE without a table
}

}  // namespace

VolumeStyleCode VolumeStyleWriter::style(const vrml::Node& node, bool projection, int depth) {
  if (node.unresolved || depth > kVolumeStyleMaxDepth || !volumeStyleEnabled(node)) return {};
  switch (node.typeId()) {
    case vrml::NodeTypeId::OpacityMapVolumeStyle:
      return opacityMap(&node);
    case vrml::NodeTypeId::BlendedVolumeStyle:
      return blended(node, depth);
    case vrml::NodeTypeId::BoundaryEnhancementVolumeStyle:
      return boundaryEnhancement(node);
    case vrml::NodeTypeId::CartoonVolumeStyle:
      return cartoon(node);
    case vrml::NodeTypeId::ComposedVolumeStyle:
      return composed(node, depth);
    case vrml::NodeTypeId::EdgeEnhancementVolumeStyle:
      return edgeEnhancement(node);
    case vrml::NodeTypeId::ProjectionVolumeStyle:
      // Not composable: X_ITE's X3DCast drops it everywhere but VolumeData.renderStyle.
      return projection ? projectionStyle(node) : VolumeStyleCode{};
    case vrml::NodeTypeId::ShadedVolumeStyle:
      return shaded(node);
    case vrml::NodeTypeId::SilhouetteEnhancementVolumeStyle:
      return silhouetteEnhancement(node);
    case vrml::NodeTypeId::ToneMappedVolumeStyle:
      return toneMapped(node);
    default:
      return {};
  }
}

VolumeStyleCode VolumeStyleWriter::opacityMap(const vrml::Node* node) {
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// OpacityMapVolumeStyle\n\n";
  const vrml::NodePtr none;
  const vrml::NodePtr& tf = node != nullptr ? node->sfnode("transferFunction") : none;
  if (const vrml::Node* t2 = volumeStyleCast(tf, vrml::AbstractType::X3DTexture2DNode)) {
    c.uniforms += sampler("transferFunction_" + id, *t2, 2);
    c.uniforms += volumeStyleText(R"(
vec4
getOpacityMapStyle_@ (in vec4 originalColor)
{
   return texture (transferFunction_@, originalColor .rg);
}
)",
                                  id);
  } else if (const vrml::Node* t3 = volumeStyleCast(tf, vrml::AbstractType::X3DTexture3DNode)) {
    c.uniforms += sampler("transferFunction_" + id, *t3, 3);
    c.uniforms += volumeStyleText(R"(
vec4
getOpacityMapStyle_@ (in vec4 originalColor)
{
   return texture (transferFunction_@, originalColor .rgb);
}
)",
                                  id);
  } else {
    // X_ITE's getDefaultTransferFunction: a 256 x 1 luminance-alpha PixelTexture, texel i
    // = (L i, A i), CLAMP_TO_EDGE along s, linear. Sampled at s its level 0 reads
    // clamp (256 s - 0.5, 0, 255) / 255 in every channel: that formula, no sampler.
    c.uniforms += "// X_ITE's default transfer function, as a formula (no sampler)\n";
    c.uniforms += volumeStyleText(R"(
vec4
getOpacityMapStyle_@ (in vec4 originalColor)
{
   return vec4 (clamp (originalColor .r * 256.0 - 0.5, 0.0, 255.0) / 255.0);
}
)",
                                  id);
  }
  c.functions = volumeStyleText(R"(
   // OpacityMapVolumeStyle

   textureColor = getOpacityMapStyle_@ (textureColor);
)",
                                id);
  return c;
}

/// X3DVolumeRenderStyleNode.getNormalText: `vec4 getNormal_<id> (in vec3 texCoord)`, the
/// eye-space unit normal and the gradient's length, from surfaceNormals or the voxels.
std::string VolumeStyleWriter::normalText(const vrml::Node& style, const std::string& id) {
  if (const vrml::Node* normals =
          volumeStyleCast(style.sfnode("surfaceNormals"), vrml::AbstractType::X3DTexture3DNode)) {
    return sampler("surfaceNormals_" + id, *normals, 3) + volumeStyleText(R"(
vec4
getNormal_@ (in vec3 texCoord)
{
   vec3 n = texture (surfaceNormals_@, texCoord) .xyz * 2.0 - 1.0;

   return vec4 (normalize (x3d_TextureNormalMatrix * n), length (n));
}
)",
                                                                          id);
  }
  return volumeStyleText(kVolumeStyleGradientNormal, id);
}

VolumeStyleCode VolumeStyleWriter::blended(const vrml::Node& node, int depth) {
  const vrml::Node* voxels =
      volumeStyleCast(node.sfnode("voxels"), vrml::AbstractType::X3DTexture3DNode);
  if (voxels == nullptr) return {};
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// BlendedVolumeStyle\n\n";
  c.uniforms += volumeStyleFloatConst(node, "weightConstant1", 0.5f, id);
  c.uniforms += volumeStyleFloatConst(node, "weightConstant2", 0.5f, id);
  // X_ITE declares a weight table whenever there is one; here only when TABLE reads it.
  const vrml::Node* table1 =
      volumeStyleCast(node.sfnode("weightTransferFunction1"), vrml::AbstractType::X3DTexture2DNode);
  const vrml::Node* table2 =
      volumeStyleCast(node.sfnode("weightTransferFunction2"), vrml::AbstractType::X3DTexture2DNode);
  if (volumeStyleString(node, "weightFunction1") != "TABLE") table1 = nullptr;
  if (volumeStyleString(node, "weightFunction2") != "TABLE") table2 = nullptr;
  if (table1 != nullptr) c.uniforms += sampler("weightTransferFunction1_" + id, *table1, 2);
  if (table2 != nullptr) c.uniforms += sampler("weightTransferFunction2_" + id, *table2, 2);
  c.uniforms += sampler("voxels_" + id, *voxels, 3);

  // The second volume: X_ITE's default opacity map, then the composable renderStyle, on
  // voxels_<id> instead of x3d_Texture3D [0] and blendColor_<id> instead of textureColor.
  // X_ITE's BlendedVolumeStyle forwards no getDefines of its renderStyle (a Cartoon there
  // would not compile for want of X3D_HSV); style() here defines them.
  VolumeStyleCode second = opacityMap(nullptr);
  if (const vrml::Node* s = volumeStyleCast(
          node.sfnode("renderStyle"), vrml::AbstractType::X3DComposableVolumeRenderStyleNode)) {
    VolumeStyleCode code = style(*s, false, depth + 1);
    second.uniforms += code.uniforms;
    second.functions += code.functions;
  }
  c.uniforms += "\n" + volumeStyleReplace(second.uniforms, "x3d_Texture3D [0]", "voxels_" + id);
  c.uniforms += volumeStyleText(R"(
vec4
getBlendedStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   vec4 blendColor_@ = texture (voxels_@, texCoord);
)",
                                id);
  c.uniforms += volumeStyleReplace(second.functions, "textureColor", "blendColor_" + id);
  c.uniforms += volumeStyleBlendWeight(node, 1, id, table1 != nullptr);
  c.uniforms += volumeStyleBlendWeight(node, 2, id, table2 != nullptr);
  c.uniforms += volumeStyleText(R"(
   return clamp (originalColor * w1_@ + blendColor_@ * w2_@, 0.0, 1.0);
}
)",
                                id);
  c.functions = volumeStyleCall("BlendedVolumeStyle", "getBlendedStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::boundaryEnhancement(const vrml::Node& node) {
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// BoundaryEnhancementVolumeStyle\n\n";
  c.uniforms += volumeStyleFloatConst(node, "retainedOpacity", 0.2f, id);
  c.uniforms += volumeStyleFloatConst(node, "boundaryOpacity", 0.9f, id);
  c.uniforms += volumeStyleFloatConst(node, "opacityFactor", 2.0f, id);
  // X_ITE's one-sided difference along r, not the gradient's magnitude.
  c.uniforms += volumeStyleText(R"(
vec4
getBoundaryEnhancementStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   float f0 = texture (x3d_Texture3D [0], texCoord) .r;
   float f1 = texture (x3d_Texture3D [0], texCoord + vec3 (0.0, 0.0, 1.0 / float (textureSize (x3d_Texture3D [0], 0) .z))) .r;
   float f  = abs (f0 - f1);

   float retainedOpacity = retainedOpacity_@;
   float boundaryOpacity = boundaryOpacity_@;
   float opacityFactor   = opacityFactor_@;

   return vec4 (originalColor .rgb, originalColor .a * (retainedOpacity + boundaryOpacity * pow (f, opacityFactor)));
}
)",
                                id);
  c.functions =
      volumeStyleCall("BoundaryEnhancementVolumeStyle", "getBoundaryEnhancementStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::cartoon(const vrml::Node& node) {
  define("#define X3D_HSV");
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// CartoonVolumeStyle\n\n";
  c.uniforms += "const int  colorSteps_" + id + " = " +
                std::to_string(node.get<vrml::FieldType::SFInt32>("colorSteps", 4)) + ";\n";
  c.uniforms += "const vec4 orthogonalColor_" + id + " = " +
                volumeStyleVec4(volumeStyleRgba(node, "orthogonalColor", glm::vec4(1.0f))) + ";\n";
  c.uniforms += "const vec4 parallelColor_" + id + " = " +
                volumeStyleVec4(volumeStyleRgba(node, "parallelColor", {0.0f, 0.0f, 0.0f, 1.0f})) +
                ";\n";
  c.uniforms += normalText(node, id);
  c.uniforms += volumeStyleText(R"(
vec4
getCartoonStyle_@ (in vec4 originalColor, vec3 texCoord)
{
   vec4 surfaceNormal = getNormal_@ (texCoord);

   if (surfaceNormal .w == 0.0)
      return vec4 (0.0);

   vec4 orthogonalColor = orthogonalColor_@;
   vec4 parallelColor   = parallelColor_@;
   int  colorSteps      = colorSteps_@;

   float steps    = clamp (float (colorSteps), 1.0, 64.0);
   float step     = M_PI / 2.0 / steps;
   float cosTheta = min (dot (surfaceNormal .xyz, normalize (vertex)), 1.0);

   if (cosTheta < 0.0)
      return vec4 (0.0);

   float t             = cos (min (floor (acos (cosTheta) / step) * (steps > 1.0 ? steps / (steps - 1.0) : 1.0), steps) * step);
   vec3  orthogonalHSV = rgb2hsv (orthogonalColor .rgb);
   vec3  parallelHSV   = rgb2hsv (parallelColor .rgb);

   return vec4 (hsv2rgb (mix_hsv (orthogonalHSV, parallelHSV, t)), originalColor .a);
}
)",
                                id);
  c.functions = volumeStyleCall("CartoonVolumeStyle", "getCartoonStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::composed(const vrml::Node& node, int depth) {
  VolumeStyleCode c;
  std::string body;
  for (const vrml::Node* child : volumeStyleComposables(node)) {
    VolumeStyleCode code = style(*child, false, depth + 1);
    c.uniforms += code.uniforms;
    body += code.functions;
  }
  const std::string id = nextId();
  c.uniforms += volumeStyleText(R"(
vec4
getComposedStyle_@ (in vec4 textureColor, in vec3 texCoord)
{
)",
                                id);
  c.uniforms += body;
  c.uniforms += "\n   return textureColor;\n}\n";
  c.functions = volumeStyleCall("ComposedVolumeStyle", "getComposedStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::edgeEnhancement(const vrml::Node& node) {
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// EdgeEnhancementVolumeStyle\n\n";
  c.uniforms += "const vec4  edgeColor_" + id + " = " +
                volumeStyleVec4(volumeStyleRgba(node, "edgeColor", {0.0f, 0.0f, 0.0f, 1.0f})) +
                ";\n";
  c.uniforms += volumeStyleFloatConst(node, "gradientThreshold", 0.4f, id);
  c.uniforms += normalText(node, id);
  c.uniforms += volumeStyleText(R"(
vec4
getEdgeEnhacementStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   vec4 surfaceNormal = getNormal_@ (texCoord);

   if (surfaceNormal .w == 0.0)
      return vec4 (0.0);

   vec4  edgeColor         = edgeColor_@;
   float gradientThreshold = gradientThreshold_@;

   float angle = abs (dot (surfaceNormal .xyz, normalize (vertex)));

   if (angle >= cos (gradientThreshold))
      return originalColor;
   else
      return vec4 (mix (edgeColor .rgb, originalColor.rgb, angle), originalColor .a);
}
)",
                                id);
  c.functions = volumeStyleCall("EdgeEnhancementVolumeStyle", "getEdgeEnhacementStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::projectionStyle(const vrml::Node& node) {
  define("#define X3D_PLANE");
  const std::string id = nextId();
  const std::string& type = volumeStyleString(node, "type");
  const bool min = type == "MIN", average = type == "AVERAGE";  // else MAX
  VolumeStyleCode c;
  c.uniforms = "\n// ProjectionVolumeStyle\n\n";
  c.uniforms += volumeStyleFloatConst(node, "intensityThreshold", 0.0f, id);
  c.uniforms += volumeStyleText(R"(
vec4
getProjectionStyle_@(in vec4 originalColor, in vec3 texCoord)
{
)",
                                id);
  c.uniforms += min ? "   float  projectionColor = 1.0;\n" : "   float  projectionColor = 0.0;\n";
  c.uniforms += R"(   const  int samples     = 16;
   vec3   normal          = normalize (x3d_TextureViewDirection);
   Plane3 plane           = plane3 (vec3 (0.5), normal);
   vec3   point           = texCoord + plane3_perpendicular_vector (plane, texCoord);
   vec3   ray             = point - normal * M_SQRT1_2;
   vec3   step            = normal * (M_SQRT2 / float (samples));
   bool   first           = false;

   for (int i = 0; i < samples; ++ i, ray += step)
   {
      if (any (greaterThan (abs (ray - 0.5), vec3 (0.5))))
         continue;

      float intensity = texture (x3d_Texture3D [0], ray) .r;

)";
  if (average) {
    c.uniforms += "      projectionColor += intensity;\n";
  } else {
    c.uniforms += volumeStyleText(R"(      if (intensity < intensityThreshold_@)
         continue;

      if (first && intensityThreshold_@ > 0.0)
         break;

)",
                                  id);
    c.uniforms += min ? "      if (intensity >= projectionColor)\n"
                      : "      if (intensity <= projectionColor)\n";
    c.uniforms += R"(      {
         first = true;
         continue;
      }

      projectionColor = intensity;
)";
  }
  c.uniforms += "   }\n\n";
  if (average) c.uniforms += "   projectionColor /= float (samples);\n";
  c.uniforms += "   return vec4 (vec3 (projectionColor), originalColor .a);\n}\n";
  c.functions = volumeStyleCall("ProjectionVolumeStyle", "getProjectionStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::shaded(const vrml::Node& node) {
  define("#define X3D_SHADING");
  const std::string id = nextId();
  const vrml::Node* material =
      volumeStyleCast(node.sfnode("material"), vrml::AbstractType::X3DMaterialNode);
  // X_ITE's uniforms are set from the material and stay 0 without one (emissiveColor is
  // added even then). A material type without a field (X_ITE fails on them) reads as
  // Material's default.
  float ambient = 0.0f, shininess = 0.0f, transparency = 0.0f;
  glm::vec3 diffuse(0.0f), specular(0.0f), emissive(0.0f);
  if (material != nullptr) {
    ambient = volumeStyleFloatField(*material, "ambientIntensity", 0.2f);
    diffuse = volumeStyleRgb(*material, "diffuseColor", glm::vec3(0.8f));
    specular = volumeStyleRgb(*material, "specularColor", glm::vec3(0.0f));
    emissive = volumeStyleRgb(*material, "emissiveColor", glm::vec3(0.0f));
    shininess = volumeStyleFloatField(*material, "shininess", 0.2f);
    transparency = volumeStyleFloatField(*material, "transparency", 0.0f);
  }
  VolumeStyleCode c;
  c.uniforms = "\n// ShadedVolumeStyle\n\n";
  c.uniforms += "const float ambientIntensity_" + id + " = " + volumeStyleFloat(ambient) + ";\n";
  c.uniforms += "const vec3  diffuseColor_" + id + " = " + volumeStyleVec3(diffuse) + ";\n";
  c.uniforms += "const vec3  specularColor_" + id + " = " + volumeStyleVec3(specular) + ";\n";
  c.uniforms += "const vec3  emissiveColor_" + id + " = " + volumeStyleVec3(emissive) + ";\n";
  c.uniforms += "const float shininess_" + id + " = " + volumeStyleFloat(shininess) + ";\n";
  c.uniforms += "const float transparency_" + id + " = " + volumeStyleFloat(transparency) + ";\n";
  c.uniforms += normalText(node, id);
  c.uniforms += volumeStyleText(R"(
vec4
getShadedStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   vec4 surfaceNormal = getNormal_@ (texCoord);

   if (surfaceNormal .w == 0.0)
      return vec4 (0.0);

   vec4 shadedColor   = vec4 (0.0);
)",
                                id);
  if (node.get<vrml::FieldType::SFBool>("lighting", false)) {
    lightMatrix_ = true;
    c.uniforms +=
        volumeStyleText(material != nullptr ? R"(   vec3 diffuseFactor = diffuseColor_@;
   vec3 ambientTerm   = diffuseFactor * ambientIntensity_@;

   shadedColor .a = originalColor .a * (1.0 - transparency_@);
)"
                                            : R"(   vec3 diffuseFactor = originalColor .rgb;
   vec3 ambientTerm   = vec3 (0.0);

   shadedColor .a = originalColor .a;
)",
                        id);
    // X_ITE's light .matrix is x3d_LightMatrix [i] here; its emissive term is added once
    // per light (kept).
    c.uniforms += volumeStyleText(R"(
   vec3 N = surfaceNormal .xyz;
   vec3 V = normalize (-vertex); // normalized vector from point on geometry to viewer's position

   for (int i = 0; i < X3D_NUM_LIGHTS; ++ i)
   {
      x3d_LightSourceParameters light = x3d_LightSource [i];

      vec3  vL = light .location - vertex; // Light to fragment
      float dL = length (x3d_LightMatrix [i] * vL);
      bool  di = light .type == x3d_DirectionalLight;

      if (di || dL <= light .radius)
      {
         vec3 d = light .direction;
         vec3 c = light .attenuation;
         vec3 L = di ? -d : normalize (vL);      // Normalized vector from point on geometry to light source i position.
         vec3 H = normalize (L + V);             // Specular term

         float lightAngle     = max (dot (N, L), 0.0);      // Angle between normal and light ray.
         vec3  diffuseTerm    = diffuseFactor * lightAngle;
         float specularFactor = shininess_@ > 0.0 ? pow (max (dot (N, H), 0.0), shininess_@ * 128.0) : 1.0;
         vec3  specularTerm   = light .intensity * specularColor_@ * specularFactor;

         float attenuationFactor     = di ? 1.0 : 1.0 / max (dot (c, vec3 (1.0, dL, dL * dL)), 1.0);
         float spotFactor            = light .type == x3d_SpotLight ? getSpotFactor (light .cutOffAngle, light .beamWidth, L, d) : 1.0;
         float attenuationSpotFactor = attenuationFactor * spotFactor;
         vec3  ambientColor          = light .ambientIntensity * ambientTerm;
         vec3  diffuseSpecularColor  = light .intensity * (diffuseTerm + specularTerm);

         shadedColor .rgb += attenuationSpotFactor * light .color * (ambientColor + diffuseSpecularColor);
      }

      shadedColor .rgb += emissiveColor_@;
   }
)",
                                  id);
  } else if (material != nullptr) {
    c.uniforms += volumeStyleText(R"(   shadedColor .rgb = diffuseColor_@;
   shadedColor .a   = originalColor .a * (1.0 - transparency_@);
)",
                                  id);
  } else {
    c.uniforms += "   shadedColor = originalColor;\n";
  }
  c.uniforms += "\n   return shadedColor;\n}\n";
  c.functions = volumeStyleCall("ShadedVolumeStyle", "getShadedStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::silhouetteEnhancement(const vrml::Node& node) {
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// SilhouetteEnhancementVolumeStyle\n\n";
  c.uniforms += volumeStyleFloatConst(node, "silhouetteRetainedOpacity", 1.0f, id);
  c.uniforms += volumeStyleFloatConst(node, "silhouetteBoundaryOpacity", 0.0f, id);
  c.uniforms += volumeStyleFloatConst(node, "silhouetteSharpness", 0.5f, id);
  c.uniforms += normalText(node, id);
  c.uniforms += volumeStyleText(R"(
vec4
getSilhouetteEnhancementStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   vec4 surfaceNormal = getNormal_@ (texCoord);

   if (surfaceNormal .w == 0.0)
      return vec4 (0.0);

   float silhouetteRetainedOpacity = silhouetteRetainedOpacity_@;
   float silhouetteBoundaryOpacity = silhouetteBoundaryOpacity_@;
   float silhouetteSharpness       = silhouetteSharpness_@;

   return vec4 (originalColor .rgb, originalColor .a * (silhouetteRetainedOpacity + silhouetteBoundaryOpacity * pow (1.0 - abs (dot (surfaceNormal .xyz, normalize (vertex))), silhouetteSharpness)));
}
)",
                                id);
  c.functions =
      volumeStyleCall("SilhouetteEnhancementVolumeStyle", "getSilhouetteEnhancementStyle", id);
  return c;
}

VolumeStyleCode VolumeStyleWriter::toneMapped(const vrml::Node& node) {
  const std::string id = nextId();
  VolumeStyleCode c;
  c.uniforms = "\n// ToneMappedVolumeStyle\n\n";
  c.uniforms += "const vec4 coolColor_" + id + " = " +
                volumeStyleVec4(volumeStyleRgba(node, "coolColor", {0.0f, 0.0f, 1.0f, 0.0f})) +
                ";\n";
  c.uniforms += "const vec4 warmColor_" + id + " = " +
                volumeStyleVec4(volumeStyleRgba(node, "warmColor", {1.0f, 1.0f, 0.0f, 0.0f})) +
                ";\n";
  c.uniforms += normalText(node, id);
  c.uniforms += volumeStyleText(R"(
vec4
getToneMappedStyle_@ (in vec4 originalColor, in vec3 texCoord)
{
   vec4 surfaceNormal = getNormal_@ (texCoord);

   if (surfaceNormal .w == 0.0)
      return vec4 (0.0);

   vec3 toneColor = vec3 (0.0);
   vec3 coolColor = coolColor_@ .rgb;
   vec3 warmColor = warmColor_@ .rgb;

   for (int i = 0; i < X3D_NUM_LIGHTS; ++ i)
   {
      x3d_LightSourceParameters light = x3d_LightSource [i];

      vec3  L           = light .type == x3d_DirectionalLight ? -light .direction : normalize (light .location - vertex);
      float colorFactor = dot (L, surfaceNormal .xyz) * 0.5 + 0.5;

      toneColor += mix (warmColor .rgb, coolColor .rgb, colorFactor);
   }

   return vec4 (toneColor, originalColor .a);
}
)",
                                id);
  c.functions = volumeStyleCall("ToneMappedVolumeStyle", "getToneMappedStyle", id);
  return c;
}

}  // namespace gs::render::detail
