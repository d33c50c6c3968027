// The CPU reference of the splat pass: a plain implementation of equation (1) of
// Nagasawa, "Beyond VRML", section 3.1, used to test the OpenGL splat pass and the
// splat model (splat_model.hpp). Pure CPU code, no OpenGL; slow but exact.
//
// Definitions (the GPU pass follows them exactly):
//
// - Camera: P = projectionMatrix(camera, width / height) and V = viewMatrix(camera).
//   Pixel (x, y), y counted from the top row, has its centre at (x + 0.5, y + 0.5), i.e.
//   NDC (2 (x + 0.5) / width - 1, 1 - 2 (y + 0.5) / height); its ray leaves the eye (the
//   eye-space origin: a perspective camera) through the point of the near plane that P
//   maps to that NDC position.
// - Splat k of vector k: centre x_k = position, unit normal n_k = normalize(normal) (a
//   zero normal draws nothing), axes t_k, b_k = splatAxes(n_k); profile =
//   splatProfile(style, magnitude, transferAlpha) with transferAlpha =
//   unpackRgba(rgba).a; colour c_k = shadeSplat(n_k, unpackRgba(rgba).rgb, lights,
//   style.ambient), flat over the splat.
// - alpha_k(u) = profile.alphaAt(r), r = |p - x_k|, where p is the intersection of the
//   ray of pixel u with the plane through x_k perpendicular to n_k. alpha_k(u) = 0 when
//   the ray is parallel to the plane, when p is behind the eye or outside the clip range
//   (eye depth -p_eye.z below camera.nearClip or above camera.farClip: what the GPU's
//   clipping of the patch does), or when p is outside the square patch
//   |(p - x_k) . t_k| <= 3 s and |(p - x_k) . b_k| <= 3 s (s = profile.spread,
//   kSplatExtent = 3; the disk cut of alphaAt lies inside it anyway).
// - Depth order: the eye-space z of the centres x_k (DepthSorter), one order for the
//   whole image, not a per-pixel depth: the GPU sorts and draws whole splats too.
// - Compositing, per pixel, front to back: C = 0, T = 1; for each splat nearest first
//   C += T alpha_k c_k, T *= 1 - alpha_k; finally C += T background. That is
//   C(u) = sum_k c_k alpha_k(u) prod_{m in front of k} (1 - alpha_m(u)) + background T.
//   Back to front, the over operator gives the same: C = background; for each splat
//   farthest first C = alpha_k c_k + (1 - alpha_k) C.
// - Output: opaque RGBA8 (alpha 255), rows top to bottom as Image, each channel
//   round(255 clamp(C, 0, 1)).
//
// Arithmetic is float per pixel (the accumulation too). Expected agreement with the GPU:
// the GPU blends in an 8-bit framebuffer, rounding colour and transmittance to 1/255 at
// every splat, and rasterizes in its own float precision, so where many splats overlap
// its result can differ from this reference by a few levels per channel (compare with
// compareImages and a channel tolerance of about 8, not for equality); where at most one
// or two splats cover a pixel it agrees within 1 or 2 levels. Front to back and back to
// front here agree within float rounding (1e-5 in 0..1, at most 1 level after rounding).
//
// Implementation: splat-centric. Each splat's square patch is clipped against the near
// plane, its corners projected to find the pixel bounding box (clipped to the viewport),
// and only the pixels in that box are evaluated. Cost: O(width height) + the sum over
// splats of their box areas; single thread.
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
