// The point-sprite splat path (see splat_points.hpp): its shaders and the check that a
// view can be drawn with it.
#include "splat_points.hpp"

#include <algorithm>
#include <cmath>

namespace gs::render::detail {

// The point path's vertex shader after the shared model (splat_glsl.hpp).
const char* const kSplatPointsVertexBody = R"glsl(
uniform mat4 u_modelView;
uniform mat4 u_projection;
uniform vec2 u_viewportSize;  // pixels
flat out vec3 v_center;       // eye coordinates
flat out vec3 v_normal;       // eye coordinates, the patch plane's normal (not unit)
flat out vec3 v_uAxis;        // patch coordinate u (in spreads) of eye offset q: dot(q, v_uAxis)
flat out vec3 v_vAxis;
flat out vec3 v_color;
flat out float v_peak;

void cull() {
  gl_Position = vec4(0.0, 0.0, 2.0, 1.0);  // beyond the far plane: clipped
  gl_PointSize = 1.0;
}

void main() {
  vec4 c = splatRgba();
  vec3 n = a_normal;
  float spread;
  float peak;
  splatProfile(a_positionMagnitude.w, c.a, spread, peak);
  peak = clamp(peak, 0.0, 1.0);
  if (!(peak > 0.0) || !(spread > 0.0)) {
    cull();
    return;
  }
  vec3 helper = abs(n.z) < 0.9 ? vec3(0.0, 0.0, 1.0) : vec3(1.0, 0.0, 0.0);
  vec3 tangent = normalize(cross(helper, n));
  vec3 bitangent = cross(n, tangent);
  mat3 linear = mat3(u_modelView);
  vec3 center = (u_modelView * vec4(a_positionMagnitude.xyz, 1.0)).xyz;
  vec3 t = linear * (tangent * spread);
  vec3 b = linear * (bitangent * spread);
  // Screen box of the 3-sigma disk center + 3 (cos a t + sin a b): clip x / w over a is
  // (x0 + x1 cos a + x2 sin a) / (w0 + w1 cos a + w2 sin a), whose extremes k solve
  // (x0 - k w0)^2 = (x1 - k w1)^2 + (x2 - k w2)^2 (exact while the disk is in front).
  vec4 c0 = u_projection * vec4(center, 1.0);
  vec4 c1 = u_projection * vec4(3.0 * t, 0.0);
  vec4 c2 = u_projection * vec4(3.0 * b, 0.0);
  float qa = c0.w * c0.w - c1.w * c1.w - c2.w * c2.w;
  if (!(qa > 0.0) || !(c0.w > 0.0)) {  // reaches behind the eye: pointsFit prevents it
    cull();
    return;
  }
  vec2 qb = c0.xy * c0.w - c1.xy * c1.w - c2.xy * c2.w;
  vec2 qc = c0.xy * c0.xy - c1.xy * c1.xy - c2.xy * c2.xy;
  vec2 root = sqrt(max(qb * qb - qa * qc, vec2(0.0)));
  vec2 lo = ((qb - root) / qa * 0.5 + 0.5) * u_viewportSize;
  vec2 hi = ((qb + root) / qa * 0.5 + 0.5) * u_viewportSize;
  lo = max(lo, vec2(0.0));
  hi = min(hi, u_viewportSize);
  if (!(lo.x < hi.x && lo.y < hi.y)) {  // outside the view (or not finite)
    cull();
    return;
  }
  gl_PointSize = max(hi.x - lo.x, hi.y - lo.y) + 0.5;  // a quarter pixel of margin each side
  gl_Position = vec4((lo + hi) / u_viewportSize - 1.0, 0.0, 1.0);
  vec3 normal = cross(t, b);
  vec3 bn = cross(b, normal);
  vec3 nt = cross(normal, t);
  v_uAxis = bn / dot(t, bn);
  v_vAxis = nt / dot(b, nt);
  v_center = center;
  v_normal = normal;
  v_peak = peak;
  v_color = splatLit(n, c.rgb);
}
)glsl";

const char* const kSplatPointsFragmentShader = R"glsl(#version 330 core
flat in vec3 v_center;
flat in vec3 v_normal;
flat in vec3 v_uAxis;
flat in vec3 v_vAxis;
flat in vec3 v_color;
flat in float v_peak;
uniform vec4 u_viewport;   // x, y, width, height (pixels)
uniform vec2 u_rayScale;   // 1 / projection[0][0], 1 / projection[1][1]
uniform vec2 u_clipRange;  // near, far (eye depth)
uniform vec2 u_depthMap;   // projection[2][2], projection[3][2]
out vec4 o_color;
void main() {
  vec2 pixel = gl_FragCoord.xy - u_viewport.xy;
  if (any(lessThan(pixel, vec2(0.0))) || any(greaterThanEqual(pixel, u_viewport.zw))) discard;
  // The pixel's ray from the eye, scaled to eye depth 1; its hit on the patch plane.
  vec3 d = vec3((pixel / u_viewport.zw * 2.0 - 1.0) * u_rayScale, -1.0);
  float denominator = dot(d, v_normal);
  if (denominator == 0.0) discard;
  float depth = dot(v_center, v_normal) / denominator;
  if (!(depth >= u_clipRange.x && depth <= u_clipRange.y)) discard;
  vec3 q = depth * d - v_center;
  vec2 local = vec2(dot(q, v_uAxis), dot(q, v_vAxis));
  float r2 = dot(local, local);
  if (!(r2 <= 9.0)) discard;  // the 3-sigma disk (inside the square patch)
  float alpha = v_peak * exp(-0.5 * r2);
  o_color = vec4(v_color * alpha, alpha);  // premultiplied
  float ndcZ = (u_depthMap.x * -depth + u_depthMap.y) / depth;
  gl_FragDepth = 0.5 * (gl_DepthRange.diff * ndcZ + gl_DepthRange.near + gl_DepthRange.far);
}
)glsl";

namespace {

/// Largest singular value of `m` (power iteration on m^T m).
float spectralNorm(const glm::mat3& m) {
  const glm::mat3 g = glm::transpose(m) * m;
  glm::vec3 v(0.577f, 0.577f, 0.578f);
  float value = 0.0f;
  for (int i = 0; i < 32; ++i) {
    const glm::vec3 w = g * v;
    value = glm::length(w);
    if (!(value > 0.0f) || !std::isfinite(value)) return value;
    v = w / value;
  }
  return std::sqrt(value) * 1.001f;  // a little margin for the iteration's rounding
}

}  // namespace

bool pointsFit(std::span<const qnv::DecodedVector> vectors, const SplatStyle& style,
               const PointView& view) {
  const float stretch = spectralNorm(glm::mat3(view.modelView));
  if (!std::isfinite(stretch)) return false;
  // A corner of the patch lies 3 sqrt(2) spreads from the centre in model units.
  const float reach = 3.0f * std::sqrt(2.0f) * stretch;
  const bool volume = style.kind == qnv::StreamKind::volume;
  const float volumeSpread = 2.0f * style.sigma * style.voxelSize;
  const float surfaceScale = 2.0f * style.sigma / std::sqrt(3.14159265f);
  // The sprite is clipped to the viewport: under the largest size it always fits.
  const float margin = 1.5f;  // the shader's half pixel and one for rounding
  const bool sizeMatters =
      static_cast<float>(std::max(view.width, view.height)) + margin > view.maxPointSize;
  const float pixelsX = 0.5f * static_cast<float>(view.width) * std::abs(view.scaleX);
  const float pixelsY = 0.5f * static_cast<float>(view.height) * std::abs(view.scaleY);
  const glm::mat4& m = view.modelView;
  for (const qnv::DecodedVector& v : vectors) {
    const float spread =
        volume ? volumeSpread : surfaceScale * std::sqrt(std::max(v.magnitude, 0.0f));
    const float radius = reach * spread;
    const glm::vec3 p = v.position;
    const float depth = -((m[0][2] * p.x + m[1][2] * p.y) + (m[2][2] * p.z + m[3][2]));
    if (depth + radius < view.nearClip) continue;  // wholly behind the near plane: culled
    if (!(depth - radius >= view.nearClip)) {
      if (std::isnan(depth) || std::isnan(radius)) continue;  // draws nothing either way
      return false;                                           // crosses the near plane
    }
    if (!sizeMatters) continue;
    const float x = (m[0][0] * p.x + m[1][0] * p.y) + (m[2][0] * p.z + m[3][0]);
    const float y = (m[0][1] * p.x + m[1][1] * p.y) + (m[2][1] * p.z + m[3][1]);
    const float near = depth - radius;
    const float width = 2.0f * radius * (1.0f + std::abs(x) / depth) / near * pixelsX + margin;
    const float height = 2.0f * radius * (1.0f + std::abs(y) / depth) / near * pixelsY + margin;
    const float side = std::max(std::min(width, static_cast<float>(view.width) + margin),
                                std::min(height, static_cast<float>(view.height) + margin));
    if (!(side <= view.maxPointSize)) return false;
  }
  return true;
}

}  // namespace gs::render::detail
