#include "splat_glsl.hpp"

namespace gs::render::detail {

namespace {

// The splat model of splat_model.hpp in GLSL: keep the two in step.
const char* const kSplatModelGlsl = R"glsl(#version 330 core
layout(location = 0) in vec4 a_positionMagnitude;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in uint a_rgba;
uniform mat3 u_normalMatrix;
uniform int u_surface;
uniform float u_sigma;
uniform float u_opacityScale;
uniform float u_voxelSize;
uniform float u_magnitudeMax;
uniform float u_ambient;
uniform int u_lightCount;
uniform vec3 u_lightDirection[8];
uniform vec3 u_lightColor[8];

// The palette colour of the vector, RGBA in [0, 1].
vec4 splatRgba() {
  uint rgba = a_rgba;
  return vec4(float(rgba & 255u), float((rgba >> 8) & 255u), float((rgba >> 16) & 255u),
              float(rgba >> 24)) / 255.0;
}

// Spread (world units) and peak opacity (not yet clamped) of the splat of a vector of
// magnitude `magnitude` and palette opacity `alpha`.
void splatProfile(float magnitude, float alpha, out float spread, out float peak) {
  if (u_surface == 1) {
    float radius = sqrt(max(magnitude, 0.0) / 3.14159265);
    spread = 2.0 * u_sigma * radius;
    peak = spread > 0.0 ? u_opacityScale * magnitude / (2.0 * 3.14159265 * spread * spread) : 0.0;
    peak *= alpha;
  } else {
    spread = 2.0 * u_sigma * u_voxelSize;
    peak = u_opacityScale * alpha * sqrt(clamp(magnitude / u_magnitudeMax, 0.0, 1.0));
  }
}

// Two-sided flat lighting of colour `rgb` on a splat of model normal `n`.
vec3 splatLit(vec3 n, vec3 rgb) {
  vec3 wn = normalize(u_normalMatrix * n);
  vec3 light = vec3(u_ambient);
  for (int k = 0; k < u_lightCount; ++k)
    light += (1.0 - u_ambient) * abs(dot(wn, u_lightDirection[k])) * u_lightColor[k];
  return min(rgb * light, vec3(1.0));
}
)glsl";

}  // namespace

std::string splatVertexShader(const char* body) {
  return std::string(kSplatModelGlsl) + body;
}

}  // namespace gs::render::detail
