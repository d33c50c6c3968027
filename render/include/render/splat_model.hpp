// How one decoded QNV vector becomes a textured square patch (Nagasawa, "Beyond VRML",
// sections 3.1 and 3.5), shared by the OpenGL splat pass and the CPU reference of
// equation (1) so both draw exactly the same splats. Units: world units (metres), radians.
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

/// Half-size of the square patch in Gaussian standard deviations: beyond 3 sigma the
/// profile is below 1.2% of its peak and is cut to zero.
inline constexpr float kSplatExtent = 3.0f;

/// The Gaussian opacity profile of one vector: alpha(r) = peak * exp(-r^2 / (2 s^2)) for
/// r <= 3 s in the patch plane, else 0 (section 3.1: alpha ~ exp(-|u - x_k|^2 / A)).
struct SplatProfile {
  float spread = 0.0f;  // s, world units
  float peak = 0.0f;    // 0..1
  float alphaAt(float r) const {
    if (!(r <= kSplatExtent * spread) || spread <= 0.0f) return 0.0f;
    return peak * std::exp(-r * r / (2.0f * spread * spread));
  }
};

/// Surfaces: the disk of the triangle's area has radius R = sqrt(A / pi); s = 2 sigma R
/// (s = R for the default sigma 0.5) and peak = opacityScale * A / (2 pi s^2), so that the
/// integrated opacity is A: the paper's "exact conservation of integrated surface area"
/// (clamped to 1). Volumes: s = 2 sigma * voxelSize (one voxel by default) and peak =
/// opacityScale * transfer alpha * sqrt(A / magnitudeMax) (clamped to 1): strong
/// gradients of opaque materials are opaque.
inline SplatProfile splatProfile(const SplatStyle& style, float magnitude, float transferAlpha) {
  const splats::VectorProfile v =
      splats::vectorProfile(style.kind == qnv::StreamKind::surface, style.sigma, style.opacityScale,
                            style.voxelSize, style.magnitudeMax, magnitude, transferAlpha);
  return {v.spread, v.peak};
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

/// RGBA8 packed little-endian (R in the low byte) to 0..1 floats.
inline glm::vec4 unpackRgba(std::uint32_t rgba) {
  return glm::vec4(rgba & 255u, (rgba >> 8) & 255u, (rgba >> 16) & 255u, rgba >> 24) / 255.0f;
}

/// Two unit vectors spanning the patch plane perpendicular to `normal` (unit): the same
/// construction on the CPU and in the shader, so both orient the square identically.
inline void splatAxes(const glm::vec3& normal, glm::vec3& tangent, glm::vec3& bitangent) {
  const glm::vec3 helper =
      std::abs(normal.z) < 0.9f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  tangent = glm::normalize(glm::cross(helper, normal));
  bitangent = glm::cross(normal, tangent);
}

}  // namespace gs::render
