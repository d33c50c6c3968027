// How one decoded QNV vector becomes a splat of the one splat model (splats/gaussian.hpp,
// docs/splats.md): the flat-disc Gaussian across the vector with the paper's opacity
// profile (Nagasawa, "Beyond VRML", sections 3.1 and 3.5), shaded flat by the lights.
// Shared by the CPU rasterizer, the GL pass and the CPU reference of equation (1), so all
// draw exactly the same splats. Units: world units (metres), radians.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include <glm/glm.hpp>

#include "qnv/decoder.hpp"
#include "qnv/stream.hpp"
#include "splats/vector_splat.hpp"

namespace gs::render {

/// The fog a splat's colour goes through (X3D 4.0 clause 24.2.1, as a shape's fragment:
/// the bound Fog or the innermost LocalFog), by its centre's distance from the eye.
struct SplatFog {
  int type = 0;               // 0: none, 1: LINEAR, 2: EXPONENTIAL
  glm::vec3 color{1.0f};      // the fog's colour (the splat colours' space)
  float visibilityRange = 0;  // eye metres; where the fog is whole
  /// Volumetric fog (castle-engine's): the distance is dot(eyePlane, (eye position, 1));
  /// all 0: the distance to the eye.
  glm::vec4 eyePlane{0.0f};
};

/// `color` fogged at eye position `eye` (metres, eye coordinates): mixed towards the fog's
/// colour by f = (r - d) / r (LINEAR) or exp(-d / (r - d)) (EXPONENTIAL), 0 beyond r.
inline glm::vec3 fogged(const SplatFog& fog, const glm::vec3& color, const glm::vec3& eye) {
  if (fog.type == 0 || !(fog.visibilityRange > 0.0f)) return color;
  const float d = fog.eyePlane != glm::vec4(0.0f) ? glm::dot(fog.eyePlane, glm::vec4(eye, 1.0f))
                                                  : glm::length(eye);
  const float r = fog.visibilityRange;
  float f = 0.0f;
  if (d < r) f = fog.type == 1 ? (r - d) / r : std::exp(-d / (r - d));
  return glm::mix(fog.color, color, std::clamp(f, 0.0f, 1.0f));
}

/// Per-stream parameters of the splat model.
struct SplatStyle {
  qnv::StreamKind kind = qnv::StreamKind::surface;
  float sigma = 0.5f;         // profile sigma from the stream header (see splatProfile)
  float opacityScale = 1.0f;  // header opacity scale times the node's opacityScale
  float voxelSize = 1.0f;     // volumes: the largest voxel spacing (world units)
  float magnitudeMax = 1.0f;  // volumes: the stream's largest magnitude
  /// Light every splat receives whatever its orientation: 0 for surfaces, as the VRML97
  /// headlight (ambientIntensity 0) lights polygons; 0.2 for volumes, whose gradients
  /// have no outside.
  float ambient = 0.0f;

  /// From a stream header; `opacityScale` multiplies the header's.
  static SplatStyle fromHeader(const qnv::StreamHeader& h, float opacityScale = 1.0f) {
    SplatStyle s;
    s.kind = h.kind;
    s.sigma = h.profile.sigma;
    s.opacityScale = h.profile.opacityScale * opacityScale;
    s.voxelSize = std::max({h.voxelSpacing.x, h.voxelSpacing.y, h.voxelSpacing.z, 1e-6f});
    s.magnitudeMax = std::max(h.magnitudeMax, 1e-30f);
    s.ambient = h.kind == qnv::StreamKind::volume ? 0.2f : 0.0f;
    return s;
  }
};

/// RGBA8 packed little-endian (R in the low byte) to 0..1 floats.
inline glm::vec4 unpackRgba(std::uint32_t rgba) {
  return glm::vec4(rgba & 255u, (rgba >> 8) & 255u, (rgba >> 16) & 255u, rgba >> 24) / 255.0f;
}

/// Surfaces: the disk of the triangle's area has radius R = sqrt(A / pi); s = 2 sigma R
/// (s = R for the default sigma 0.5) and peak = opacityScale * A / (2 pi s^2), so that the
/// integrated opacity is A: the paper's "exact conservation of integrated surface area"
/// (clamped to 1). Volumes: s = 2 sigma * voxelSize (one voxel by default) and peak =
/// opacityScale * transfer alpha * sqrt(A / magnitudeMax) (clamped to 1): strong
/// gradients of opaque materials are opaque.
/// The profile's spread s (world units) and peak (0..1): splats::vectorProfile for a style.
inline splats::VectorProfile splatProfile(const SplatStyle& style, float magnitude,
                                          float transferAlpha) {
  return splats::vectorProfile(style.kind == qnv::StreamKind::surface, style.sigma,
                               style.opacityScale, style.voxelSize, style.magnitudeMax, magnitude,
                               transferAlpha);
}

/// A directional light for splat shading (world direction the light travels, unit).
struct SplatLight {
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  glm::vec3 color{1.0f};  // colour times intensity
};

/// Flat shading of one splat, two-sided (a volume gradient has no outside; a surface
/// splat is seen from either side): rgb * (ambient + (1 - ambient) * sum of |n . L| *
/// light), clamped to 1. `ambient` is SplatStyle::ambient. The diffuse share is 1 - ambient
/// so that a white volume under the headlight reaches white only where it faces the light:
/// with ambient added on top, every face within 37 degrees of the light clipped to flat
/// white (issue 42, friction 9: the engine's near faces).
inline glm::vec3 shadeSplat(const glm::vec3& normal, const glm::vec3& rgb,
                            std::span<const SplatLight> lights, float ambient) {
  glm::vec3 light(ambient);
  for (const SplatLight& l : lights)
    light += (1.0f - ambient) * std::abs(glm::dot(normal, l.direction)) * l.color;
  return glm::min(rgb * light, glm::vec3(1.0f));
}

/// The largest alpha one Gaussian fragment has (Kerbl et al. 2023's 0.99: a splat never
/// closes a pixel alone).
inline constexpr float kGaussianMaxAlpha = 0.99f;

/// A QNV vector as a 3D Gaussian of the splat model (issue 40 item 1): centre the vector's
/// position, covariance spread^2 (I - n n^T) (a flat disc across the unit normal n whose
/// in-plane profile is splatProfile's exp(-r^2 / (2 spread^2))), peak opacity the profile's
/// peak. Model coordinates. Projected as every Gaussian is (splats::projectGaussian: EWA,
/// 0.3-pixel low-pass, 3-sigma box); a vector's opacity keeps its integrated value through
/// the low-pass (ProjectedGaussian::lowPassKeep), as the paper's profile conserves area.
struct VectorGaussian {
  glm::vec3 position{0.0f};
  glm::mat3 covariance{0.0f};
  float opacity = 0.0f;                // 0..1
  glm::vec3 normal{0.0f, 0.0f, 1.0f};  // unit, model coordinates
  glm::vec3 rgb{1.0f};                 // the vector's colour before shading, 0..1
};

/// Fills `out` for `vector` under `style`. False when the vector draws nothing: a zero or
/// non-finite normal or position, a peak below splats::kVisiblePeak (half an 8-bit level),
/// a spread that is not positive and finite.
inline bool vectorGaussian(const qnv::DecodedVector& vector, const SplatStyle& style,
                           VectorGaussian& out) {
  const float length = glm::length(vector.normal);
  if (!(length > 0.0f) || !std::isfinite(length)) return false;
  if (!std::isfinite(vector.position.x) || !std::isfinite(vector.position.y) ||
      !std::isfinite(vector.position.z))
    return false;
  const glm::vec4 rgba = unpackRgba(vector.rgba);
  const splats::VectorProfile profile = splatProfile(style, vector.magnitude, rgba.a);
  if (!(profile.peak >= splats::kVisiblePeak) || !(profile.spread > 0.0f) ||
      !std::isfinite(profile.spread))
    return false;
  out.normal = vector.normal / length;
  const float s2 = profile.spread * profile.spread;
  out.covariance = s2 * (glm::mat3(1.0f) - glm::outerProduct(out.normal, out.normal));
  out.position = vector.position;
  out.opacity = std::min(profile.peak, 1.0f);
  out.rgb = glm::vec3(rgba);
  return true;
}

}  // namespace gs::render
