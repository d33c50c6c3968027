// GLSL 3.30 core sources. The surface program implements the VRML97 lighting model
// (ISO/IEC 14772-1:1997 clause 4.14.4) per fragment, in eye coordinates:
//
//   I = I_F (1 - f0) + f0 (O_E + sum_i on_i attenuation_i spot_i I_Lrgb,i
//                            (ambient_i + diffuse_i + specular_i))
//   ambient_i  = I_ia O_D O_a
//   diffuse_i  = I_i O_D (N . L)
//   specular_i = I_i O_S (N . (L + V) / |L + V|) ^ (shininess 128)
//   attenuation_i = 1 / max(c1 + c2 d_L + c3 d_L^2, 1)  (1 for directional lights)
//   spot_i = 0 beyond cutOffAngle, 1 within beamWidth, linear in between
//
// with textures and colours modulating O_D and the alpha per clause 4.14.3 (table 4.5):
// 1- and 2-component textures multiply the diffuse (or Color) colour by their intensity,
// 3- and 4-component ones replace it; 2- and 4-component textures give the alpha,
// otherwise alpha = 1 - transparency. In X3D worlds (u_textureModulates, X3D 4.0 clause
// 17.2.2.4) 3- and 4-component textures multiply the colour and the alpha instead; with the
// browser option Shading GOURAUD (u_textureAfterLighting) the texture multiplies the lit
// colour I (emissive and specular included) in VRML97 and X3D 3 worlds, as X_ITE 15 draws by
// default. Unlit shapes (no Material, lines, points) take u_unlitColor (white, or emissiveColor for
// lines and points) with the same texture and colour rules. Fog (clause 6.19): f0 = (r - d) / r
// (LINEAR) or exp(-d / (r - d)) (EXPONENTIAL), 0 beyond the visibility range r, d the distance to
// the viewer; where the geometry has an X3D FogCoordinate (X3D 4.0 clause 24.4.2), f0 = 1 - its
// depth (the fog amount, as X_ITE and castle-model-viewer read it).
//
// Multi-texturing (X3D 4.0 clause 18.4.3, multi_texture.hpp): a MultiTexture's stages, up
// to 4, replace the single texture. Each combines its texture (Arg1, after its function)
// with its source (Arg2) by its mode in RGB and alpha (table 18.3), the first stage's
// "previous" being the diffuse colour and 1 - transparency; the last result is the diffuse
// colour and alpha the lighting uses.
#include "gl_program.hpp"
#include "hatch_glsl.hpp"
#include "shading_normal_glsl.hpp"
#include "texture_projectors.hpp"

namespace gs::render::detail {

const char* const kSurfaceVertexShader = R"glsl(#version 330 core
layout(location = 0) in vec3 a_position;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec4 a_color;
layout(location = 3) in vec2 a_texCoord;
layout(location = 4) in vec2 a_texCoord1;  // the second set (MultiTextureCoordinate)
layout(location = 5) in float a_fogDepth;   // X3D FogCoordinate; -1: the eye distance
// X3D TextureCoordinate3D / TextureCoordinate4D (clauses 33.4.6, 33.4.7) as (s, t, r, q);
// q = 0 where the geometry has none. Read by 2D textures as (s, t) / q and by 3D textures
// as (s, t, r) / q, the division per pixel (v_texQ).
layout(location = 6) in vec4 a_texCoordStrq;

uniform mat4 u_modelView;
uniform mat4 u_projection;
uniform mat3 u_normalMatrix;
uniform mat3 u_textureMatrix;
uniform float u_pointSize;  // pixels, the nominal size
// X3D PointProperties (clause 12.4.9): the nominal size times u_pointScale over the
// attenuation polynomial of the distance, clamped to u_pointSizeRange times the nominal.
uniform float u_pointScale;
uniform vec2 u_pointSizeRange;
uniform vec3 u_pointAttenuation;
// X3D ClipPlanes (clause 11.4.1) in eye coordinates: kept where dot(plane, eye) >= 0.
// A specialized variant fixes their count (surface_programs.cpp).
const int kMaxClipPlanes = 6;
#ifdef GS_VARIANT
#define CLIP_PLANES GS_CLIP_PLANES
#else
uniform int u_clipPlaneCount;
#define CLIP_PLANES u_clipPlaneCount
#endif
uniform vec4 u_clipPlanes[kMaxClipPlanes];
out float gl_ClipDistance[kMaxClipPlanes];
// X3D TextureCoordinateGenerator (clause 18.4.8; texture_generation.hpp numbers the modes):
// texture coordinates made per vertex instead of read. 0: read a_texCoord.
#ifdef GS_VARIANT
#define TEX_GEN GS_TEX_GEN
#else
uniform int u_texGen;
#define TEX_GEN u_texGen
#endif
#ifdef GS_VARIANT
#define TEXTURE_3D GS_TEXTURE_3D
#else
uniform bool u_texture3DOn;  // an X3D Texturing3D texture: v_texCoord3 is read
#define TEXTURE_3D u_texture3DOn
#endif
// 3D texture coordinates (X3D 4.0 clause 33): the geometry's TextureCoordinate3D/4D,
// COORD / COORD-EYE generation, else the shape's bounding box mapped to [0, 1]^3 (r from
// the back); then the Appearance's 3D texture transform.
uniform mat4 u_textureMatrix3D;
uniform vec3 u_texBoundsMin;
uniform vec3 u_texBoundsSize;
out vec3 v_texCoord3;
out float v_texQ;  // v_texCoord and v_texCoord3 are divided by it (1 but for a_texCoordStrq)
uniform float u_texGenParameter;  // SPHERE-REFLECT's index of refraction
uniform mat3 u_eyeToWorld;        // the view's rotation, inverted

// Sphere mapping of direction r (OpenGL's GL_SPHERE_MAP).
vec2 sphereMap(vec3 r) {
  float m = 2.0 * sqrt(r.x * r.x + r.y * r.y + (r.z + 1.0) * (r.z + 1.0));
  return m > 0.0 ? r.xy / m + 0.5 : vec2(0.5);
}

vec2 generatedTexCoord(vec3 eye, vec3 eyeNormal) {
  vec3 u = normalize(eye);
  vec3 n = normalize(eyeNormal);
  vec3 localN = normalize(a_normal);
  if (TEX_GEN == 1) return sphereMap(reflect(u, n));                     // SPHERE
  if (TEX_GEN == 2) return n.xy;                                         // CAMERASPACENORMAL
  if (TEX_GEN == 3) return eye.xy;                                       // CAMERASPACEPOSITION
  if (TEX_GEN == 4) return reflect(u, n).xy;                             // CAMERASPACEREFLECTIONVECTOR
  if (TEX_GEN == 5) return localN.xy * 0.5 + 0.5;                        // SPHERE-LOCAL
  if (TEX_GEN == 6) return a_position.xy;                                // COORD (and NOISE)
  if (TEX_GEN == 7) return eye.xy;                                       // COORD-EYE (and NOISE-EYE)
  if (TEX_GEN == 8) return sphereMap(refract(u, n, 1.0 / max(u_texGenParameter, 1e-3)));
  if (TEX_GEN == 9) return (u_eyeToWorld * reflect(u, n)).xy;            // WORLDSPACEREFLECTIONVECTOR
  if (TEX_GEN == 10) return (u_eyeToWorld * n).xy;                       // WORLDSPACENORMAL
  return a_texCoord;
}

out vec3 v_position;  // eye coordinates
out vec3 v_normal;    // eye coordinates, not normalized
out vec4 v_color;  // RGBA: ColorRGBA alpha multiplies the material alpha
out vec2 v_texCoord;
out vec2 v_texCoord1;
out float v_fogDepth;
// Screen-space line patterns (LineProperties.linetype): the position in normalized device
// coordinates, and (flat) that of the segment's provoking vertex, where its pattern starts.
noperspective out vec2 v_ndc;
flat out vec2 v_lineStart;

void main() {
  vec4 eye = u_modelView * vec4(a_position, 1.0);
  v_position = eye.xyz;
  v_normal = u_normalMatrix * a_normal;
  v_color = a_color;
  v_fogDepth = a_fogDepth;
  bool strq = a_texCoordStrq.w != 0.0;
  v_texQ = strq ? a_texCoordStrq.w : 1.0;
  vec2 texCoord = strq           ? a_texCoordStrq.xy
                  : TEX_GEN != 0 ? generatedTexCoord(eye.xyz, v_normal)
                                 : a_texCoord;
  // Homogeneous (s, t, q): the affine texture matrix keeps q, divided out per pixel.
  v_texCoord = (u_textureMatrix * vec3(texCoord, v_texQ)).xy;
  v_texCoord1 = (u_textureMatrix * vec3(a_texCoord1, 1.0)).xy;
  if (TEXTURE_3D) {
    // The box mapping's r runs backwards, 1 at the back (X3D 4.0 clause 33.2.4, as
    // castle-model-viewer reads it); 0 for a flat shape.
    vec3 box = (a_position - u_texBoundsMin) / max(u_texBoundsSize, vec3(1e-6));
    box.z = u_texBoundsSize.z > 1e-6 ? 1.0 - box.z : 0.0;
    vec3 r = TEX_GEN == 6 ? a_position : TEX_GEN == 7 ? eye.xyz : box;
    vec4 h = strq ? a_texCoordStrq : vec4(r, 1.0);
    v_texCoord3 = (u_textureMatrix3D * h).xyz;
  } else {
    // A cube map texture's direction (CUBE_MAP 5) where the geometry has them.
    v_texCoord3 = strq ? a_texCoordStrq.xyz : vec3(0.0);
  }
  float r = length(eye.xyz);
  float attenuation = max(dot(u_pointAttenuation, vec3(1.0, r, r * r)), 1e-6);
  gl_PointSize = clamp(u_pointSize * u_pointScale / attenuation, u_pointSize * u_pointSizeRange.x,
                       u_pointSize * u_pointSizeRange.y);
  for (int i = 0; i < kMaxClipPlanes; ++i)
    gl_ClipDistance[i] = i < CLIP_PLANES ? dot(u_clipPlanes[i], eye) : 1.0;
  gl_Position = u_projection * eye;
  float w = abs(gl_Position.w) > 1e-6 ? gl_Position.w : 1e-6;
  v_ndc = gl_Position.xy / w;
  v_lineStart = v_ndc;
}
)glsl";

const char* const kSurfaceFragmentShader = R"glsl(#version 330 core
const int kMaxLights = 8;
const int kDirectional = 0;
const int kPoint = 1;
const int kSpot = 2;

in vec3 v_position;
in vec3 v_normal;
in vec4 v_color;
in vec2 v_texCoord;
in vec2 v_texCoord1;
in float v_fogDepth;  // X3D FogCoordinate's depth, negative where the geometry has none

uniform sampler2D u_texture;  // also stage 0 of a MultiTexture
// A ComposedCubeMapTexture (X3D 4.0 clause 34.4.1) on unit 6, looked up by the direction
// CUBE_MAP names: 1 the world-space reflection (castle-model-viewer's
// WORLDSPACEREFLECTIONVECTOR, and the default), 2 the eye-space one
// (CAMERASPACEREFLECTIONVECTOR), 3 the eye-space normal, 4 the world-space normal, 5 the
// geometry's TextureCoordinate3D (s, t, r) itself (X_ITE 15 reads a cube map there).
uniform samplerCube u_cubeTexture;
uniform mat3 u_eyeToWorld;
// An X3D Texturing3D texture (clause 33) on unit 7, read at v_texCoord3.
uniform sampler3D u_texture3D;
in vec3 v_texCoord3;
in float v_texQ;  // X3D TextureCoordinate4D's q (1 otherwise): v_texCoord and v_texCoord3 / it

// A MultiTexture's stages (multi_texture.hpp): stage i samples unit i.
const int kMaxStages = 4;
uniform sampler2D u_stageTexture1;
uniform sampler2D u_stageTexture2;
uniform sampler2D u_stageTexture3;
uniform ivec2 u_stageMode[kMaxStages];  // TextureMode of RGB and of alpha
uniform int u_stageSource[kMaxStages];  // TextureSource
uniform int u_stageFunction[kMaxStages];
uniform int u_stageTexCoord[kMaxStages];  // 0: v_texCoord, 1: v_texCoord1
uniform mat3 u_stageMatrix[kMaxStages];
uniform vec4 u_stageFactor;  // MultiTexture color and alpha

// What a shape uses: uniforms in the generic program; compile-time constants in a
// specialized variant (surface_programs.cpp prepends GS_VARIANT and the GS_ values), where
// the light loop unrolls and the branches on them fold away.
#ifdef GS_VARIANT
const int kLightTypes[kMaxLights] = int[kMaxLights](GS_LIGHT_TYPES);
#define LIT GS_LIT
#define HAS_COLOR GS_HAS_COLOR
#define TEXTURE_COMPONENTS GS_TEXTURE_COMPONENTS
#define LIGHT_COUNT GS_LIGHT_COUNT
#define LIGHT_TYPE(i) kLightTypes[i]
#define FOG_TYPE GS_FOG_TYPE
#define TEXTURE_MODULATES GS_TEXTURE_MODULATES
#define SEPARATE_BACK GS_SEPARATE_BACK
#define STAGE_COUNT GS_STAGE_COUNT
#define CUBE_MAP GS_CUBE_MAP
#define TEXTURE_3D GS_TEXTURE_3D
#define LINE_TYPE GS_LINE_TYPE
#define HATCH_STYLE GS_HATCH_STYLE
#define FILLED GS_FILLED
#else
uniform int u_lineType;    // LineProperties.linetype: 1 solid .. 5 dash-dot-dot
uniform int u_hatchStyle;  // FillProperties: 0 no hatches, 1 .. 6
uniform bool u_filled;     // FillProperties.filled
#define LINE_TYPE u_lineType
#define HATCH_STYLE u_hatchStyle
#define FILLED u_filled
uniform bool u_texture3DOn;
#define TEXTURE_3D u_texture3DOn
uniform int u_stageCount;  // 0: no MultiTexture
uniform int u_cubeMap;     // 0: no cube map texture
#define CUBE_MAP u_cubeMap
uniform bool u_textureModulates;  // X3D 4 Material.diffuseTexture: diffuse x texture
uniform bool u_separateBack;      // TwoSidedMaterial.separateBackColor
uniform bool u_lit;
uniform bool u_hasColor;
uniform int u_textureComponents;  // 0: no texture
uniform int u_lightCount;
uniform int u_lightType[kMaxLights];
uniform int u_fogType;  // 0 none, 1 LINEAR, 2 EXPONENTIAL
#define LIT u_lit
#define HAS_COLOR u_hasColor
#define TEXTURE_COMPONENTS u_textureComponents
#define LIGHT_COUNT u_lightCount
#define LIGHT_TYPE(i) u_lightType[i]
#define FOG_TYPE u_fogType
#define TEXTURE_MODULATES u_textureModulates
#define SEPARATE_BACK u_separateBack
#define STAGE_COUNT u_stageCount
#endif

// The browser option Shading GOURAUD (browser_options.hpp ShadingOption): the texture (or
// the MultiTexture's stages) multiplies the lit colour instead of the diffuse colour.
uniform bool u_textureAfterLighting;
uniform vec3 u_diffuseColor;
uniform float u_ambientIntensity;
uniform vec3 u_specularColor;
uniform vec3 u_emissiveColor;
uniform float u_shininess;
uniform float u_transparency;
uniform vec3 u_unlitColor;
// X3D 4.0 TwoSidedMaterial (clause 12.4.11) with separateBackColor TRUE: back faces take
// these instead.
uniform vec3 u_backDiffuseColor;
uniform float u_backAmbientIntensity;
uniform vec3 u_backSpecularColor;
uniform vec3 u_backEmissiveColor;
uniform float u_backShininess;
uniform float u_backTransparency;

uniform vec3 u_lightColor[kMaxLights];
uniform float u_lightIntensity[kMaxLights];
uniform float u_lightAmbientIntensity[kMaxLights];
uniform vec3 u_lightPosition[kMaxLights];   // eye coordinates
uniform vec3 u_lightDirection[kMaxLights];  // eye coordinates, unit
uniform vec3 u_lightAttenuation[kMaxLights];
uniform float u_lightRadius[kMaxLights];
uniform float u_lightBeamWidth[kMaxLights];
uniform float u_lightCutOffAngle[kMaxLights];

uniform vec3 u_fogColor;
uniform float u_fogVisibilityRange;
// Volumetric fog (castle-engine's): the fog distance is dot(u_fogPlane, (eye position, 1));
// all zero: the distance to the eye.
uniform vec4 u_fogPlane;

out vec4 fragColor;

// X3D LineProperties and FillProperties (clauses 12.4.6, 12.4.3; line_fill_properties.hpp):
// dash patterns along each segment from its provoking vertex, in points (4/3 pixel), and
// hatch lines every 8 pixels of the window in hatchColor over the fill.
noperspective in vec2 v_ndc;
flat in vec2 v_lineStart;
uniform vec2 u_viewportSize;  // pixels
uniform vec3 u_hatchColor;

bool linePatternOn() {
  // X_ITE 15's patterns (its assets/linetype/linetypes.png), one step a typographic point
  // (4/3 pixel at 96 dpi) whatever the line's width.
  float d = length((v_ndc - v_lineStart) * 0.5 * u_viewportSize) * 0.75;
  if (LINE_TYPE == 3) return mod(d, 4.0) < 2.0;  // dotted: 2 on, 2 off
  float p = mod(d, 16.0);
  if (LINE_TYPE == 2) return p < 9.0;                              // dashed: 9 on, 7 off
  if (LINE_TYPE == 4) return p < 8.0 || (p >= 11.0 && p < 13.0);  // dash-dot
  return p < 6.0 || (p >= 8.0 && p < 10.0) || (p >= 12.0 && p < 14.0);  // dash-dot-dot
}


)glsl" GS_HATCH_GLSL GS_SHADING_NORMAL_GLSL R"glsl(
vec3 cubeDirection() {
  vec3 n = shadingNormal();
  vec3 r = reflect(normalize(v_position), n);
  if (CUBE_MAP == 2) return r;
  if (CUBE_MAP == 3) return n;
  if (CUBE_MAP == 4) return u_eyeToWorld * n;
  if (CUBE_MAP == 5) return v_texCoord3;
  return u_eyeToWorld * r;
}

vec4 stageSample(int i, vec2 st) {
  if (i == 0) return texture(u_texture, st);
  if (i == 1) return texture(u_stageTexture1, st);
  if (i == 2) return texture(u_stageTexture2, st);
  return texture(u_stageTexture3, st);
}

// Table 18.3: t is Arg1 (the stage's texture), s Arg2 (its source).
vec4 combine(int mode, vec4 t, vec4 s, vec4 previous, float diffuseAlpha) {
  vec4 r;
  if (mode == 0) r = t * s;
  else if (mode == 1) r = t;
  else if (mode == 2) r = 2.0 * t * s;
  else if (mode == 3) r = 4.0 * t * s;
  else if (mode == 4) r = t + s;
  else if (mode == 5) r = t + s - 0.5;
  else if (mode == 6) r = 2.0 * (t + s - 0.5);
  else if (mode == 7) r = t - s;
  else if (mode == 8) r = t + s - t * s;
  else if (mode == 9) r = mix(s, t, diffuseAlpha);
  else if (mode == 10) r = mix(s, t, t.a);
  else if (mode == 11) r = mix(s, t, u_stageFactor.a);
  else if (mode == 12) r = mix(s, t, previous.a);
  else if (mode == 13) r = vec4(t.rgb + t.a * s.rgb, t.a);
  else if (mode == 14) r = vec4((1.0 - t.a) * s.rgb + t.rgb, t.a);
  else if (mode == 15) r = vec4((1.0 - t.rgb) * s.rgb + t.a, t.a);
  else if (mode == 17) r = s;
  else if (mode == 18) r = vec4(4.0 * dot(t.rgb - 0.5, s.rgb - 0.5));
  else r = previous;  // OFF
  return clamp(r, 0.0, 1.0);
}

vec4 applyStages(vec4 diffuse, vec3 specular) {
  vec4 previous = diffuse;
  for (int i = 0; i < kMaxStages; ++i) {
    if (i >= STAGE_COUNT) break;
    ivec2 mode = u_stageMode[i];
    if (mode.x == 16) continue;  // OFF
    vec2 uv = u_stageTexCoord[i] == 0 ? v_texCoord / v_texQ : v_texCoord1;
    vec4 t = stageSample(i, (u_stageMatrix[i] * vec3(uv, 1.0)).xy);
    int source = u_stageSource[i];
    vec4 s = source == 1 ? diffuse : source == 2 ? vec4(specular, diffuse.a)
                                   : source == 3 ? u_stageFactor : previous;
    previous = vec4(combine(mode.x, t, s, previous, diffuse.a).rgb,
                    combine(mode.y, t, s, previous, diffuse.a).a);
    // The function acts on the stage's result (as castle-model-viewer applies it).
    if (u_stageFunction[i] == 1) previous.rgb = 1.0 - previous.rgb;
    else if (u_stageFunction[i] == 2) previous.rgb = vec3(previous.a);
  }
  return previous;
}

)glsl" GS_TEXTURE_PROJECTOR_GLSL R"glsl(
void main() {
  if (LINE_TYPE > 1 && !linePatternOn()) discard;
  bool back = SEPARATE_BACK && !gl_FrontFacing;
  vec3 diffuseColor = back ? u_backDiffuseColor : u_diffuseColor;
  float ambientIntensity = back ? u_backAmbientIntensity : u_ambientIntensity;
  vec3 specularColor = back ? u_backSpecularColor : u_specularColor;
  vec3 emissiveColor = back ? u_backEmissiveColor : u_emissiveColor;
  float shininess = back ? u_backShininess : u_shininess;
  vec3 diffuse = LIT ? diffuseColor : u_unlitColor;
  float alpha = 1.0 - (back ? u_backTransparency : u_transparency);
  if (HAS_COLOR) {
    diffuse = v_color.rgb;
    alpha *= v_color.a;  // X3D ColorRGBA (clause 11.4.3); 1 for Color
  }
  bool afterLighting = u_textureAfterLighting && LIT;
  vec3 textureColor = vec3(1.0);  // what multiplies the lit colour (afterLighting)
  if (TEXTURE_COMPONENTS > 0) {
    vec4 t = TEXTURE_3D    ? texture(u_texture3D, v_texCoord3 / v_texQ)
             : CUBE_MAP > 0 ? vec4(texture(u_cubeTexture, cubeDirection()).rgb, 1.0)
                            : texture(u_texture, v_texCoord / v_texQ);
    if (afterLighting) textureColor = TEXTURE_COMPONENTS <= 2 ? vec3(t.r) : t.rgb;
    else if (TEXTURE_COMPONENTS <= 2) diffuse *= t.r;
    else diffuse = TEXTURE_MODULATES ? diffuse * t.rgb : t.rgb;
    if (TEXTURE_COMPONENTS == 2 || TEXTURE_COMPONENTS == 4)
      alpha = TEXTURE_MODULATES || afterLighting ? alpha * t.a : t.a;
  }
  if (STAGE_COUNT > 0 && !afterLighting) {
    vec4 combined = applyStages(vec4(diffuse, alpha), specularColor);
    diffuse = combined.rgb;
    alpha = combined.a;
  }
  // X3D 4.0 clause 42: projected textures multiply the colour before lighting.
  if (u_projectorCount > 0)
    diffuse *= projectedColor(v_position, gl_FrontFacing ? v_normal : -v_normal, false);

  vec3 color = diffuse;
  if (LIT) {
    vec3 n = shadingNormal();  // two-sided lighting (solid FALSE)
    vec3 v = normalize(-v_position);
    color = emissiveColor;
    for (int i = 0; i < kMaxLights; ++i) {
      if (i >= LIGHT_COUNT) break;
      vec3 l;
      float attenuation = 1.0;
      float spot = 1.0;
      if (LIGHT_TYPE(i) == kDirectional) {
        l = -u_lightDirection[i];
      } else {
        vec3 toLight = u_lightPosition[i] - v_position;
        float d = length(toLight);
        if (d > u_lightRadius[i]) continue;
        l = d > 0.0 ? toLight / d : vec3(0.0, 0.0, 1.0);
        vec3 a = u_lightAttenuation[i];
        attenuation = 1.0 / max(a.x + a.y * d + a.z * d * d, 1.0);
        if (LIGHT_TYPE(i) == kSpot) {
          float angle = acos(clamp(dot(-l, u_lightDirection[i]), -1.0, 1.0));
          float cutOff = u_lightCutOffAngle[i];
          float beam = u_lightBeamWidth[i];
          if (angle >= cutOff) continue;
          if (angle > beam) spot = (angle - cutOff) / (beam - cutOff);
        }
      }
      float nDotL = max(dot(n, l), 0.0);
      vec3 ambient = u_lightAmbientIntensity[i] * diffuse * ambientIntensity;
      vec3 lambert = u_lightIntensity[i] * diffuse * nDotL;
      vec3 specular = vec3(0.0);
      if (nDotL > 0.0) {
        vec3 h = normalize(l + v);
        float exponent = max(shininess * 128.0, 1e-3);
        specular = u_lightIntensity[i] * specularColor * pow(max(dot(n, h), 1e-6), exponent);
      }
      color += attenuation * spot * u_lightColor[i] * (ambient + lambert + specular);
    }
  }

  if (afterLighting) {
    color *= textureColor;
    if (STAGE_COUNT > 0) {
      vec4 combined = applyStages(vec4(color, alpha), specularColor);
      color = combined.rgb;
      alpha = combined.a;
    }
  }

  if (HATCH_STYLE > 0 && hatchOn(gl_FragCoord.xy)) color = u_hatchColor;
  else if (!FILLED) discard;

  if (FOG_TYPE != 0 && u_fogVisibilityRange > 0.0) {
    float d = u_fogPlane != vec4(0.0) ? dot(u_fogPlane, vec4(v_position, 1.0)) : length(v_position);
    float r = u_fogVisibilityRange;
    float f0 = 0.0;
    if (d < r) f0 = FOG_TYPE == 1 ? (r - d) / r : exp(-d / (r - d));
    // A FogCoordinate's depth is the amount of fog itself, 0 none to 1 all.
    if (v_fogDepth >= 0.0) f0 = 1.0 - v_fogDepth;
    color = mix(u_fogColor, color, clamp(f0, 0.0, 1.0));
  }
  fragColor = vec4(clamp(color, 0.0, 1.0), clamp(alpha, 0.0, 1.0));
}
)glsl";

// A full-screen triangle; the fragment shader turns each pixel into a view direction.
const char* const kBackgroundVertexShader = R"glsl(#version 330 core
out vec2 v_ndc;
void main() {
  vec2 p = vec2(gl_VertexID == 1 ? 3.0 : -1.0, gl_VertexID == 2 ? 3.0 : -1.0);
  v_ndc = p;
  gl_Position = vec4(p, 0.0, 1.0);
}
)glsl";

// Background (clause 6.5): skyColor[0] at the zenith, skyColor[i] at skyAngle[i - 1]
// from it, linear in angle in between, the last colour beyond; ground colours likewise
// from the nadir up to the last groundAngle, drawn over the sky.
const char* const kBackgroundFragmentShader = R"glsl(#version 330 core
const int kMaxColors = 16;
in vec2 v_ndc;
uniform mat4 u_inverseViewProjection;  // of the rotation-only view
uniform mat3 u_worldToBackground;
uniform int u_skyCount;
uniform vec3 u_skyColor[kMaxColors];
uniform float u_skyAngle[kMaxColors];
uniform int u_groundCount;
uniform vec3 u_groundColor[kMaxColors];
uniform float u_groundAngle[kMaxColors];
out vec4 fragColor;

vec3 gradient(float angle, int count, vec3 colors[kMaxColors], float angles[kMaxColors]) {
  vec3 c = colors[0];
  float previous = 0.0;
  for (int i = 0; i + 1 < kMaxColors; ++i) {
    if (i + 1 >= count) return colors[i];
    if (angle <= angles[i]) {
      float span = angles[i] - previous;
      float t = span > 0.0 ? clamp((angle - previous) / span, 0.0, 1.0) : 1.0;
      return mix(colors[i], colors[i + 1], t);
    }
    previous = angles[i];
  }
  return c;
}

void main() {
  vec4 p = u_inverseViewProjection * vec4(v_ndc, 1.0, 1.0);
  vec3 direction = normalize(u_worldToBackground * (p.xyz / p.w));
  float fromZenith = acos(clamp(direction.y, -1.0, 1.0));
  vec3 color = gradient(fromZenith, u_skyCount, u_skyColor, u_skyAngle);
  if (u_groundCount > 1) {
    float fromNadir = 3.14159265 - fromZenith;
    if (fromNadir <= u_groundAngle[u_groundCount - 2])
      color = gradient(fromNadir, u_groundCount, u_groundColor, u_groundAngle);
  }
  fragColor = vec4(color, 1.0);
}
)glsl";

// Background panorama (clause 6.5): one face of the cube [-1, 1]^3 around the viewer as
// two triangles made from gl_VertexID; z = w puts it on the far plane, so no clip plane
// cuts the cube whatever the near distance. Texels blend over the sky by their alpha
// (1- and 3-component images are opaque; grey images draw grey).
const char* const kPanoramaVertexShader = R"glsl(#version 330 core
uniform mat4 u_matrix;  // Background coordinates to clip coordinates, rotation only
uniform vec3 u_center;
uniform vec3 u_right;
uniform vec3 u_up;
out vec2 v_texCoord;
void main() {
  const vec2 corners[6] = vec2[6](vec2(0, 0), vec2(1, 0), vec2(1, 1),
                                  vec2(0, 0), vec2(1, 1), vec2(0, 1));
  vec2 st = corners[gl_VertexID];
  v_texCoord = st;
  vec3 p = u_center + (2.0 * st.x - 1.0) * u_right + (2.0 * st.y - 1.0) * u_up;
  vec4 clip = u_matrix * vec4(p, 1.0);
  gl_Position = vec4(clip.xy, clip.w * 0.99999, clip.w);
}
)glsl";

const char* const kPanoramaFragmentShader = R"glsl(#version 330 core
in vec2 v_texCoord;
uniform sampler2D u_texture;
out vec4 fragColor;
void main() {
  fragColor = texture(u_texture, v_texCoord);
}
)glsl";

}  // namespace gs::render::detail
