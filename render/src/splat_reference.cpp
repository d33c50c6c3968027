// The CPU reference of equation (1): each vector's Gaussian projected and composited
// pixel by pixel (see splat_reference.hpp for the definitions).
#include "render/splat_reference.hpp"

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "render/splat_sort.hpp"
#include "splats/gaussian.hpp"

namespace gs::render {

std::vector<glm::vec3> compositeSplats(std::span<const qnv::DecodedVector> vectors,
                                       std::span<const std::uint32_t> order,
                                       SplatCompositing compositing, const SplatStyle& style,
                                       std::span<const SplatLight> lights,
                                       const scene::Camera& camera, int width, int height,
                                       const glm::vec3& background) {
  if (width <= 0 || height <= 0) return {};
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const glm::mat4 projection = scene::projectionMatrix(camera, aspect);
  splats::ProjectionView view;
  view.modelView = scene::viewMatrix(camera);
  const float w = static_cast<float>(width), h = static_cast<float>(height);
  view.fx = projection[0][0] * w * 0.5f;
  view.fy = projection[1][1] * h * 0.5f;
  view.cx = 0.5f * w * (1.0f - projection[2][0]);
  view.cy = 0.5f * h * (1.0f - projection[2][1]);
  view.width = width;
  view.height = height;
  // The clip range projectionMatrix really uses.
  view.nearClip = std::max(camera.nearClip, 1e-6f);
  view.farClip = std::max(camera.farClip, view.nearClip * 1.001f);

  const bool frontToBack = compositing == SplatCompositing::frontToBack;
  std::vector<glm::vec3> color(pixels, frontToBack ? glm::vec3(0.0f) : background);
  std::vector<float> transmittance(frontToBack ? pixels : 0, 1.0f);

  for (const std::uint32_t index : order) {
    if (index >= vectors.size()) continue;
    VectorGaussian g;
    if (!vectorGaussian(vectors[index], style, g)) continue;
    splats::ProjectedGaussian p;
    if (!splats::projectGaussian(g.position, g.covariance, view, p)) continue;
    const float opacity = g.opacity * p.lowPassKeep;
    const float minAlpha = splats::kVisiblePeak * p.lowPassKeep;
    if (!(opacity > 0.0f)) continue;
    const glm::vec3 c = shadeSplat(g.normal, g.rgb, lights, style.ambient);
    // The 3-sigma box, pixel centres (i + 0.5, j + 0.5) in a y-up frame.
    const auto pixel = [](float v, int size) {  // clamped before the conversion to int
      return static_cast<int>(std::floor(std::clamp(v, -1.0f, static_cast<float>(size))));
    };
    const int x0 = std::max(0, pixel(p.center.x - p.extent.x, width));
    const int x1 = std::min(width - 1, pixel(p.center.x + p.extent.x, width));
    const int y0 = std::max(0, pixel(p.center.y - p.extent.y, height));
    const int y1 = std::min(height - 1, pixel(p.center.y + p.extent.y, height));
    for (int yUp = y0; yUp <= y1; ++yUp) {
      const float dy = static_cast<float>(yUp) + 0.5f - p.center.y;
      for (int x = x0; x <= x1; ++x) {
        const float dx = static_cast<float>(x) + 0.5f - p.center.x;
        const float power =
            -0.5f * (p.conic.x * dx * dx + p.conic.z * dy * dy) - p.conic.y * dx * dy;
        if (!(power <= 0.0f) || !(power > -8.0f)) continue;
        const float alpha = std::min(kGaussianMaxAlpha, opacity * std::exp(power));
        if (!(alpha >= minAlpha)) continue;
        const std::size_t at = static_cast<std::size_t>(height - 1 - yUp) * width + x;
        if (frontToBack) {
          color[at] += transmittance[at] * alpha * c;
          transmittance[at] *= 1.0f - alpha;
        } else {
          color[at] = alpha * c + (1.0f - alpha) * color[at];
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
