// The CPU reference of the splat pass: a plain implementation of equation (1) of
// Nagasawa, "Beyond VRML", section 3.1, over the one splat model (splats/gaussian.hpp,
// docs/splats.md), used to test the cpu and GL paths. Pure CPU code, no OpenGL; slow but
// exact.
//
// Definitions (both paths follow them):
//
// - Camera: P = projectionMatrix(camera, width / height) and V = viewMatrix(camera); the
//   focal lengths fx = P[0][0] width / 2, fy = P[1][1] height / 2 (pixels). Pixel (x, y),
//   y counted from the top row, has its centre at (x + 0.5, height - y - 0.5) in the y-up
//   pixel frame of splats::projectGaussian.
// - Splat k of vector k: vectorGaussian(vector, style) (splat_model.hpp): centre x_k, the
//   flat-disc covariance spread^2 (I - n n^T), peak o_k (a vector that draws nothing is
//   skipped); colour c_k = shadeSplat(n_k, rgb, lights, style.ambient), flat over the
//   splat.
// - Its projection: splats::projectGaussian (EWA: Sigma' = J W Sigma W^T J^T + 0.3 px, the
//   Jacobian at the centre, centres outside [nearClip, farClip] not drawn), the peak scaled
//   by lowPassKeep so that the integrated opacity survives the low-pass.
// - alpha_k(u) = min(0.99, o_k keep exp(power)), power = -1/2 d^T Sigma'^-1 d for the
//   pixel's offset d from the projected centre, inside the 3-sigma box, power in (-8, 0];
//   alpha below keep times splats::kVisiblePeak (half an 8-bit level) is 0: the cut
//   follows the peak, so where the unfiltered profile o_k exp(power) reaches half a level.
// - Depth order: the eye-space z of the centres x_k (DepthSorter), one order for the
//   whole image, not a per-pixel depth: every path sorts and draws whole splats too.
// - Compositing, per pixel, front to back: C = 0, T = 1; for each splat nearest first
//   C += T alpha_k c_k, T *= 1 - alpha_k; finally C += T background. That is
//   C(u) = sum_k c_k alpha_k(u) prod_{m in front of k} (1 - alpha_m(u)) + background T.
//   Back to front, the over operator gives the same: C = background; for each splat
//   farthest first C = alpha_k c_k + (1 - alpha_k) C.
// - Output: opaque RGBA8 (alpha 255), rows top to bottom as Image, each channel
//   round(255 clamp(C, 0, 1)).
//
// Arithmetic is float per pixel (the accumulation too). The cpu path composites in float
// too (a pixel stops at T < 1e-4) and agrees within 1-2 levels; the GL path blends in an
// 8-bit framebuffer, rounding at every splat, so where many splats overlap it differs by a
// few levels per channel (compare with compareImages and a channel tolerance of about 8).
// Front to back and back to front here agree within float rounding.
//
// Cost: O(width height) + the sum over splats of their 3-sigma boxes; single thread.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include <glm/vec3.hpp>

#include "qnv/decoder.hpp"
#include "render/image.hpp"
#include "render/splat_model.hpp"
#include "scene/camera.hpp"

namespace gs::render {

/// Draws the first min(count, vectors.size()) vectors (count is the level of detail: 0
/// draws only the background) with equation (1), compositing front to back in the
/// DepthSorter order. Returns an opaque width x height image (an empty Image when width or
/// height is not positive). `background` is linear 0..1 RGB.
Image renderSplatsReference(std::span<const qnv::DecodedVector> vectors, const SplatStyle& style,
                            std::span<const SplatLight> lights, const scene::Camera& camera,
                            int width, int height, const glm::vec3& background,
                            std::size_t count = static_cast<std::size_t>(-1));

/// The same image computed back to front with the over operator (equal up to float
/// rounding to renderSplatsReference): a check of the compositing itself.
Image renderSplatsReferenceBackToFront(std::span<const qnv::DecodedVector> vectors,
                                       const SplatStyle& style, std::span<const SplatLight> lights,
                                       const scene::Camera& camera, int width, int height,
                                       const glm::vec3& background,
                                       std::size_t count = static_cast<std::size_t>(-1));

/// How compositeSplats walks the order it is given.
enum class SplatCompositing {
  frontToBack,  // order[0] is the nearest splat: C += T alpha c, T *= 1 - alpha
  backToFront,  // order[0] is the farthest splat: C = alpha c + (1 - alpha) C
};

/// The lower level: composites exactly the splats `vectors[order[i]]`, in the given order
/// whatever their depths (so a test can pass a wrong order), and returns the linear RGB
/// colour of each pixel (width * height entries, rows top to bottom, not clamped). Indices
/// outside `vectors` are ignored. Returns an empty vector when width or height is not
/// positive.
std::vector<glm::vec3> compositeSplats(std::span<const qnv::DecodedVector> vectors,
                                       std::span<const std::uint32_t> order,
                                       SplatCompositing compositing, const SplatStyle& style,
                                       std::span<const SplatLight> lights,
                                       const scene::Camera& camera, int width, int height,
                                       const glm::vec3& background);

/// Converts compositeSplats' colours to an opaque RGBA8 Image: round(255 clamp(c, 0, 1)).
Image splatColorsToImage(std::span<const glm::vec3> colors, int width, int height);

}  // namespace gs::render
