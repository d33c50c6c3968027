// GLSL 3.30 core: the physically based surface program for X3D 4's PhysicalMaterial and
// glTF's metallic-roughness materials (X3D 4.0 clause 17.3.3 "Physically based lighting";
// glTF 2.0 appendix B "BRDF implementation"), with kSurfaceVertexShader. Per light i:
//
//   f = (1 - F) c_diff / pi + F D V,   c_diff = mix(base, 0, metallic),
//   F = f0 + (1 - f0) (1 - V.H)^5,     f0 = mix(0.04, base, metallic),
//   D = a^2 / (pi ((N.H)^2 (a^2 - 1) + 1)^2),  a = roughness^2,
//   V = 0.5 / (N.L sqrt((N.V)^2 (1 - a^2) + a^2) + N.V sqrt((N.L)^2 (1 - a^2) + a^2)),
//   color += attenuation_i spot_i I_i C_i (N.L) f + ambient_i I_ia base occlusion
//
// plus emissive. Lights, attenuation, spot cones and fog are the Phong program's
// (shaders.cpp). Shading is done in linear light: the base colour and emissive textures
// (sRGB, as glTF stores them) are decoded, and the result is encoded to sRGB, as
// castle-model-viewer does for physical materials. Textures: base colour (unit 0),
// metallic-roughness (1: G roughness, B metallic), normal (2, tangent space, the tangent
// frame from screen-space derivatives of position and texture coordinates), emissive (3),
// occlusion (4: R). An X3D 4.1 EnvironmentLight adds image-based light (environment_maps.hpp):
//
//   color += I_env C_env occlusion (c_diff E(n) / pi + L_spec(r, roughness) (f0 A + B)),
//
// E(n) / pi from nine spherical-harmonic coefficients, L_spec the specular cube map (unit
// 5) read at mip level roughness * maxLod along the reflected view direction, and (A, B)
// the split-sum environment BRDF in B. Karis's analytic fit ("Physically Based Shading on
// Mobile", 2014). Without one the only ambient term is the lights' ambientIntensity
// (docs/gltf.md, "Lighting").
#include "gl_program.hpp"
#include "hatch_glsl.hpp"
#include "shading_normal_glsl.hpp"
#include "texture_projectors.hpp"

namespace gs::render::detail {

const char* const kPhysicalFragmentShader = R"glsl(#version 330 core
const int kMaxLights = 8;
const int kDirectional = 0;
const int kSpot = 2;
const float kPi = 3.14159265;

in vec3 v_position;
in vec3 v_normal;
in vec4 v_color;
in vec2 v_texCoord;
in vec2 v_texCoord1;
in float v_texQ;  // X3D TextureCoordinate4D's q (1 otherwise): v_texCoord / it
in float v_fogDepth;  // X3D FogCoordinate's depth, negative where the geometry has none

uniform bool u_hasColor;
uniform int u_textureComponents;  // base colour texture: 0 none
uniform sampler2D u_texture;
uniform bool u_hasMetallicRoughnessTexture;
uniform sampler2D u_metallicRoughnessTexture;
uniform bool u_hasNormalTexture;
uniform sampler2D u_normalTexture;
uniform float u_normalScale;
uniform bool u_hasEmissiveTexture;
uniform sampler2D u_emissiveTexture;
uniform bool u_hasOcclusionTexture;
uniform sampler2D u_occlusionTexture;
uniform float u_occlusionStrength;
// The texture coordinate set each texture reads (0 or 1: PhysicalMaterial's *TextureMapping
// fields against the geometry's MultiTextureCoordinate): base colour, then
// metallic-roughness, normal, emissive, occlusion.
uniform int u_baseTexCoordSet;
uniform ivec4 u_mapTexCoordSet;

uniform vec3 u_diffuseColor;  // baseColor, linear
uniform vec3 u_emissiveColor;
uniform float u_metallic;
uniform float u_roughness;
uniform float u_transparency;
uniform int u_alphaMode;  // 0 AUTO / BLEND, 1 OPAQUE, 2 MASK
uniform float u_alphaCutoff;

uniform int u_lightCount;
uniform int u_lightType[kMaxLights];
uniform vec3 u_lightColor[kMaxLights];
uniform float u_lightIntensity[kMaxLights];
uniform float u_lightAmbientIntensity[kMaxLights];
uniform vec3 u_lightPosition[kMaxLights];
uniform vec3 u_lightDirection[kMaxLights];
uniform vec3 u_lightAttenuation[kMaxLights];
uniform float u_lightRadius[kMaxLights];
uniform float u_lightBeamWidth[kMaxLights];
uniform float u_lightCutOffAngle[kMaxLights];

uniform int u_fogType;
uniform vec3 u_fogColor;
uniform float u_fogVisibilityRange;
uniform vec4 u_fogPlane;  // volumetric fog: distance dot(plane, (eye, 1)); zero: eye distance

// X3D FillProperties (clause 12.4.3), as the Phong program draws them.
uniform int u_hatchStyle;  // 0 no hatches, 1 .. 6
uniform bool u_filled;
uniform vec3 u_hatchColor;
#define HATCH_STYLE u_hatchStyle

uniform bool u_hasEnvironment;
uniform bool u_hasEnvironmentMap;
uniform samplerCube u_environmentMap;
uniform vec3 u_environmentSh[9];  // E(n) / pi, real SH bands 0..2
uniform vec3 u_environmentColor;  // color * intensity
uniform float u_environmentAmbient;
uniform float u_environmentMaxLod;
uniform mat3 u_eyeToEnvironment;

out vec4 fragColor;

vec3 toLinear(vec3 c) {
  return mix(c / 12.92, pow((c + 0.055) / 1.055, vec3(2.4)), step(0.04045, c));
}
vec3 toSrgb(vec3 c) {
  return mix(c * 12.92, 1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, c));
}

vec2 uvOf(int set) {
  return set == 1 ? v_texCoord1 : v_texCoord / v_texQ;
}

)glsl" GS_HATCH_GLSL GS_SHADING_NORMAL_GLSL R"glsl(
vec3 surfaceNormal() {
  vec3 n = shadingNormal();
  if (!u_hasNormalTexture) return n;
  vec3 dp1 = dFdx(v_position), dp2 = dFdy(v_position);
  vec2 uv = uvOf(u_mapTexCoordSet.y);
  vec2 duv1 = dFdx(uv), duv2 = dFdy(uv);
  vec3 dp2perp = cross(dp2, n), dp1perp = cross(n, dp1);
  vec3 t = dp2perp * duv1.x + dp1perp * duv2.x;
  vec3 b = dp2perp * duv1.y + dp1perp * duv2.y;
  float scale = max(dot(t, t), dot(b, b));
  if (!(scale > 0.0)) return n;
  float invmax = inversesqrt(scale);
  vec3 m = texture(u_normalTexture, uv).xyz * 2.0 - 1.0;
  m.xy *= u_normalScale;
  vec3 mapped = normalize(mat3(t * invmax, b * invmax, n) * m);
  return mapped;
}

vec3 irradiance(vec3 d) {
  vec3 e = u_environmentSh[0] * 0.282095;
  e += u_environmentSh[1] * (0.488603 * d.y) + u_environmentSh[2] * (0.488603 * d.z) +
       u_environmentSh[3] * (0.488603 * d.x);
  e += u_environmentSh[4] * (1.092548 * d.x * d.y) + u_environmentSh[5] * (1.092548 * d.y * d.z) +
       u_environmentSh[6] * (0.315392 * (3.0 * d.z * d.z - 1.0)) +
       u_environmentSh[7] * (1.092548 * d.x * d.z) +
       u_environmentSh[8] * (0.546274 * (d.x * d.x - d.y * d.y));
  return max(e, vec3(0.0));
}

vec2 environmentBrdf(float roughness, float nDotV) {
  const vec4 c0 = vec4(-1.0, -0.0275, -0.572, 0.022);
  const vec4 c1 = vec4(1.0, 0.0425, 1.04, -0.04);
  vec4 r = roughness * c0 + c1;
  float a004 = min(r.x * r.x, exp2(-9.28 * nDotV)) * r.x + r.y;
  return vec2(-1.04, 1.04) * a004 + r.zw;
}

)glsl" GS_TEXTURE_PROJECTOR_GLSL R"glsl(
void main() {
  vec3 base = u_diffuseColor;
  float alpha = 1.0 - u_transparency;
  if (u_hasColor) {  // glTF COLOR_0 / X3D ColorRGBA multiply the base colour and alpha
    base *= v_color.rgb;
    alpha *= v_color.a;
  }
  if (u_textureComponents > 0) {
    vec4 t = texture(u_texture, uvOf(u_baseTexCoordSet));
    base *= u_textureComponents <= 2 ? vec3(t.r) : toLinear(t.rgb);
    if (u_textureComponents == 2 || u_textureComponents == 4) alpha *= t.a;
  }
  // X3D 4.0 clause 42: projected textures multiply the base colour (linear light).
  if (u_projectorCount > 0)
    base *= projectedColor(v_position, gl_FrontFacing ? v_normal : -v_normal, true);
  if (u_alphaMode == 1) alpha = 1.0;
  if (u_alphaMode == 2) {
    if (alpha < u_alphaCutoff) discard;
    alpha = 1.0;
  }
  float metallic = u_metallic;
  float roughness = u_roughness;
  if (u_hasMetallicRoughnessTexture) {
    vec4 mr = texture(u_metallicRoughnessTexture, uvOf(u_mapTexCoordSet.x));
    roughness *= mr.g;
    metallic *= mr.b;
  }
  roughness = clamp(roughness, 0.03, 1.0);
  metallic = clamp(metallic, 0.0, 1.0);
  float occlusion = 1.0;
  if (u_hasOcclusionTexture)
    occlusion = 1.0 + u_occlusionStrength * (texture(u_occlusionTexture, uvOf(u_mapTexCoordSet.w)).r - 1.0);

  vec3 n = surfaceNormal();
  vec3 v = normalize(-v_position);
  float nDotV = max(dot(n, v), 1e-4);
  vec3 cDiff = mix(base, vec3(0.0), metallic);
  vec3 f0 = mix(vec3(0.04), base, metallic);
  float a = roughness * roughness;
  float a2 = a * a;
  vec3 color = u_emissiveColor;
  if (u_hasEmissiveTexture) color *= toLinear(texture(u_emissiveTexture, uvOf(u_mapTexCoordSet.z)).rgb);
  if (u_hasEnvironment) {
    vec3 envColor = u_environmentColor * occlusion;
    vec3 light = cDiff * irradiance(normalize(u_eyeToEnvironment * n));
    if (u_hasEnvironmentMap) {
      vec3 r = normalize(u_eyeToEnvironment * reflect(-v, n));
      vec3 prefiltered = textureLod(u_environmentMap, r, roughness * u_environmentMaxLod).rgb;
      vec2 ab = environmentBrdf(roughness, nDotV);
      light += prefiltered * (f0 * ab.x + ab.y);
    }
    color += envColor * light + u_environmentColor * u_environmentAmbient * base * occlusion;
  }
  for (int i = 0; i < kMaxLights; ++i) {
    if (i >= u_lightCount) break;
    vec3 l;
    float attenuation = 1.0;
    float spot = 1.0;
    if (u_lightType[i] == kDirectional) {
      l = -u_lightDirection[i];
    } else {
      vec3 toLight = u_lightPosition[i] - v_position;
      float d = length(toLight);
      if (d > u_lightRadius[i]) continue;
      l = d > 0.0 ? toLight / d : vec3(0.0, 0.0, 1.0);
      vec3 at = u_lightAttenuation[i];
      attenuation = 1.0 / max(at.x + at.y * d + at.z * d * d, 1.0);
      if (u_lightType[i] == kSpot) {
        float angle = acos(clamp(dot(-l, u_lightDirection[i]), -1.0, 1.0));
        float cutOff = u_lightCutOffAngle[i];
        float beam = u_lightBeamWidth[i];
        if (angle >= cutOff) continue;
        if (angle > beam) spot = (angle - cutOff) / (beam - cutOff);
      }
    }
    vec3 radiance = attenuation * spot * u_lightColor[i];
    color += radiance * u_lightAmbientIntensity[i] * base * occlusion;
    float nDotL = dot(n, l);
    if (nDotL <= 0.0) continue;
    vec3 h = normalize(l + v);
    float nDotH = max(dot(n, h), 0.0);
    float vDotH = max(dot(v, h), 0.0);
    vec3 F = f0 + (1.0 - f0) * pow(1.0 - vDotH, 5.0);
    float dd = nDotH * nDotH * (a2 - 1.0) + 1.0;
    float D = a2 / (kPi * dd * dd);
    float gv = nDotL * sqrt(nDotV * nDotV * (1.0 - a2) + a2);
    float gl = nDotV * sqrt(nDotL * nDotL * (1.0 - a2) + a2);
    float Vis = gv + gl > 0.0 ? 0.5 / (gv + gl) : 0.0;
    vec3 brdf = (1.0 - F) * cDiff / kPi + F * D * Vis;
    color += radiance * u_lightIntensity[i] * nDotL * brdf;
  }
  color = toSrgb(clamp(color, 0.0, 1.0));
  if (u_hatchStyle > 0 && hatchOn(gl_FragCoord.xy)) color = u_hatchColor;
  else if (!u_filled) discard;

  if (u_fogType != 0 && u_fogVisibilityRange > 0.0) {
    float d = u_fogPlane != vec4(0.0) ? dot(u_fogPlane, vec4(v_position, 1.0)) : length(v_position);
    float r = u_fogVisibilityRange;
    float f0g = 0.0;
    if (d < r) f0g = u_fogType == 1 ? (r - d) / r : exp(-d / (r - d));
    // A FogCoordinate's depth is the amount of fog itself, 0 none to 1 all.
    if (v_fogDepth >= 0.0) f0g = 1.0 - v_fogDepth;
    color = mix(u_fogColor, color, clamp(f0g, 0.0, 1.0));
  }
  fragColor = vec4(color, clamp(alpha, 0.0, 1.0));
}
)glsl";

}  // namespace gs::render::detail
