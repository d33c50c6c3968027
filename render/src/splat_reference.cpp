// The CPU reference of equation (1): splat-centric ray/patch intersection and per-pixel
// compositing (see splat_reference.hpp for the definitions).
#include "render/splat_reference.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/glm.hpp>

#include "render/splat_sort.hpp"

namespace gs::render {

namespace {

/// One splat prepared for drawing, in eye space.
struct EyeSplat {
  glm::vec3 center;
  glm::vec3 normal;
  glm::vec3 tangent;
  glm::vec3 bitangent;
  glm::vec3 color;
  SplatProfile profile;
  float half;  // kSplatExtent * spread
};

bool isFiniteVec(const glm::vec3& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// False when the splat draws nothing anywhere.
bool prepare(const qnv::DecodedVector& vector, const SplatStyle& style,
             std::span<const SplatLight> lights, const glm::mat4& view, EyeSplat& out) {
  const float length = glm::length(vector.normal);
  if (!(length > 0.0f) || !std::isfinite(length) || !isFiniteVec(vector.position)) return false;
  const glm::vec3 n = vector.normal / length;
  const glm::vec4 rgba = unpackRgba(vector.rgba);
  out.profile = splatProfile(style, vector.magnitude, rgba.a);
  if (!(out.profile.peak > 0.0f) || !(out.profile.spread > 0.0f) ||
      !std::isfinite(out.profile.spread)) {
    return false;
  }
  out.half = kSplatExtent * out.profile.spread;
  out.color = shadeSplat(n, glm::vec3(rgba), lights, style.ambient);
  glm::vec3 t, b;
  splatAxes(n, t, b);
  const glm::mat3 rotation(view);
  out.center = glm::vec3(view * glm::vec4(vector.position, 1.0f));
  out.normal = rotation * n;
  out.tangent = rotation * t;
  out.bitangent = rotation * b;
  return true;
}

struct PixelBox {
  int x0, y0, x1, y1;  // inclusive; empty when x0 > x1 or y0 > y1
};

/// The pixels whose centres may fall on the splat's square patch: the patch clipped to
/// the near plane, projected, padded by a pixel for rounding, clipped to the viewport.
PixelBox pixelBox(const EyeSplat& s, const glm::mat4& projection, float nearClip, int width,
                  int height) {
  const PixelBox none{0, 0, -1, -1};
  std::array<glm::vec3, 4> corners = {
      s.center - s.half * s.tangent - s.half * s.bitangent,
      s.center + s.half * s.tangent - s.half * s.bitangent,
      s.center + s.half * s.tangent + s.half * s.bitangent,
      s.center - s.half * s.tangent + s.half * s.bitangent,
  };
  // Sutherland-Hodgman against the near plane: keep -z >= nearClip.
  std::array<glm::vec3, 8> clipped;
  int count = 0;
  for (int i = 0; i < 4; ++i) {
    const glm::vec3& a = corners[i];
    const glm::vec3& b = corners[(i + 1) % 4];
    const bool inA = -a.z >= nearClip, inB = -b.z >= nearClip;
    if (inA) clipped[count++] = a;
    if (inA != inB) {
      const float t = (-nearClip - a.z) / (b.z - a.z);
      glm::vec3 p = a + t * (b - a);
      p.z = -nearClip;
      clipped[count++] = p;
    }
  }
  if (count == 0) return none;
  float minX = INFINITY, minY = INFINITY, maxX = -INFINITY, maxY = -INFINITY;
  for (int i = 0; i < count; ++i) {
    const glm::vec4 clip = projection * glm::vec4(clipped[i], 1.0f);
    const float px = (clip.x / clip.w + 1.0f) * 0.5f * static_cast<float>(width);
    const float py = (1.0f - clip.y / clip.w) * 0.5f * static_cast<float>(height);
    if (!std::isfinite(px) || !std::isfinite(py)) return none;
    minX = std::min(minX, px);
    maxX = std::max(maxX, px);
    minY = std::min(minY, py);
    maxY = std::max(maxY, py);
  }
  // Pixel x is covered when x + 0.5 lies in [minX, maxX]; one pixel of margin.
  const auto toPixel = [](float v, int limit) {
    return static_cast<int>(std::clamp(v, -2.0f, static_cast<float>(limit) + 2.0f));
  };
  PixelBox box;
  box.x0 = std::max(toPixel(std::floor(minX - 0.5f), width) - 1, 0);
  box.x1 = std::min(toPixel(std::ceil(maxX - 0.5f), width) + 1, width - 1);
  box.y0 = std::max(toPixel(std::floor(minY - 0.5f), height) - 1, 0);
  box.y1 = std::min(toPixel(std::ceil(maxY - 0.5f), height) + 1, height - 1);
  return box;
}

}  // namespace

std::vector<glm::vec3> compositeSplats(std::span<const qnv::DecodedVector> vectors,
                                       std::span<const std::uint32_t> order,
                                       SplatCompositing compositing, const SplatStyle& style,
                                       std::span<const SplatLight> lights,
                                       const scene::Camera& camera, int width, int height,
                                       const glm::vec3& background) {
  if (width <= 0 || height <= 0) return {};
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::mat4 view = scene::viewMatrix(camera);
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  const glm::mat4 inverseProjection = glm::inverse(projection);
  // The clip range projectionMatrix really uses.
  const float nearClip = std::max(camera.nearClip, 1e-6f);
  const float farClip = std::max(camera.farClip, nearClip * 1.001f);

  // Eye-space ray direction of each pixel centre, scaled to z = -1 so that the ray
  // parameter of a point is its eye depth.
  std::vector<glm::vec3> rays(pixels);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const float ndcX = 2.0f * (static_cast<float>(x) + 0.5f) / static_cast<float>(width) - 1.0f;
      const float ndcY = 1.0f - 2.0f * (static_cast<float>(y) + 0.5f) / static_cast<float>(height);
      const glm::vec4 h = inverseProjection * glm::vec4(ndcX, ndcY, -1.0f, 1.0f);
      const glm::vec3 d = glm::vec3(h) / h.w;
      rays[static_cast<std::size_t>(y) * width + x] = d / -d.z;
    }
  }

  const bool frontToBack = compositing == SplatCompositing::frontToBack;
  std::vector<glm::vec3> color(pixels, frontToBack ? glm::vec3(0.0f) : background);
  std::vector<float> transmittance(frontToBack ? pixels : 0, 1.0f);

  EyeSplat s;
  for (const std::uint32_t index : order) {
    if (index >= vectors.size()) continue;
    if (!prepare(vectors[index], style, lights, view, s)) continue;
    const PixelBox box = pixelBox(s, projection, nearClip, width, height);
    const float planeOffset = glm::dot(s.center, s.normal);
    for (int y = box.y0; y <= box.y1; ++y) {
      for (int x = box.x0; x <= box.x1; ++x) {
        const std::size_t at = static_cast<std::size_t>(y) * width + x;
        if (frontToBack && transmittance[at] == 0.0f) continue;  // exact: adds nothing
        const glm::vec3& d = rays[at];
        const float denominator = glm::dot(d, s.normal);
        if (denominator == 0.0f) continue;  // ray parallel to the patch
        const float depth = planeOffset / denominator;
        if (!(depth >= nearClip && depth <= farClip)) continue;  // behind the eye or clipped
        const glm::vec3 q = depth * d - s.center;
        if (std::abs(glm::dot(q, s.tangent)) > s.half ||
            std::abs(glm::dot(q, s.bitangent)) > s.half) {
          continue;  // outside the square patch
        }
        const float alpha = s.profile.alphaAt(glm::length(q));
        if (!(alpha > 0.0f)) continue;
        if (frontToBack) {
          color[at] += transmittance[at] * alpha * s.color;
          transmittance[at] *= 1.0f - alpha;
        } else {
          color[at] = alpha * s.color + (1.0f - alpha) * color[at];
        }
      }
    }
  }
  if (frontToBack) {
    for (std::size_t i = 0; i < pixels; ++i) color[i] += transmittance[i] * background;
  }
  return color;
}

Image splatColorsToImage(std::span<const glm::vec3> colors, int width, int height) {
  if (width <= 0 || height <= 0) return {};
  Image image(width, height);
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const auto level = [](float c) {
    if (!(c > 0.0f)) return std::uint8_t{0};  // NaN too
    return static_cast<std::uint8_t>(std::lround(std::min(c, 1.0f) * 255.0f));
  };
  for (std::size_t i = 0; i < pixels && i < colors.size(); ++i) {
    std::uint8_t* p = &image.rgba[i * 4];
    p[0] = level(colors[i].r);
    p[1] = level(colors[i].g);
    p[2] = level(colors[i].b);
    p[3] = 255;
  }
  return image;
}

namespace {

Image renderOrdered(std::span<const qnv::DecodedVector> vectors, const SplatStyle& style,
                    std::span<const SplatLight> lights, const scene::Camera& camera, int width,
                    int height, const glm::vec3& background, std::size_t count,
                    SplatCompositing compositing) {
  if (width <= 0 || height <= 0) return {};
  DepthSorter sorter;
  std::vector<std::uint32_t> order;
  const glm::mat4 view = scene::viewMatrix(camera);
  if (compositing == SplatCompositing::frontToBack) {
    sorter.sortFrontToBack(vectors, view, order, count);
  } else {
    sorter.sortBackToFront(vectors, view, order, count);
  }
  const std::vector<glm::vec3> colors = compositeSplats(vectors, order, compositing, style, lights,
                                                        camera, width, height, background);
  return splatColorsToImage(colors, width, height);
}

}  // namespace

Image renderSplatsReference(std::span<const qnv::DecodedVector> vectors, const SplatStyle& style,
                            std::span<const SplatLight> lights, const scene::Camera& camera,
                            int width, int height, const glm::vec3& background, std::size_t count) {
  return renderOrdered(vectors, style, lights, camera, width, height, background, count,
                       SplatCompositing::frontToBack);
}

Image renderSplatsReferenceBackToFront(std::span<const qnv::DecodedVector> vectors,
                                       const SplatStyle& style, std::span<const SplatLight> lights,
                                       const scene::Camera& camera, int width, int height,
                                       const glm::vec3& background, std::size_t count) {
  return renderOrdered(vectors, style, lights, camera, width, height, background, count,
                       SplatCompositing::backToFront);
}

}  // namespace gs::render
