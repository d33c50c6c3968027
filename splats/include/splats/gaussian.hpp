// The one splat model of GhostSpace (docs/splats.md): an anisotropic 3D Gaussian with a
// position, a covariance Sigma = R S S^T R^T (scale + rotation), an opacity and a colour
// as spherical harmonics of degree 0..3 (Kerbl et al. 2023, "3D Gaussian Splatting for
// Real-Time Radiance Field Rendering", section 4; Zwicker et al. 2002, "EWA Splatting").
// A QNV vector is one case of it (splats/qnv_gaussians.hpp): a flat disc across the
// vector with the paper's opacity profile (Nagasawa, "Beyond VRML", sections 3.1, 3.5).
//
// No OpenGL, no files: the readers (splats/readers.hpp), the level-of-detail tree
// (splats/lod_tree.hpp) and every renderer (render/) share these types.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

namespace gs::splats {

/// Highest spherical-harmonics degree of the model (3: 16 coefficients per channel).
inline constexpr int kMaxShDegree = 3;

/// Coefficients per colour channel of degree `degree` (0..3): (degree + 1)^2.
constexpr int shCoefficients(int degree) {
  return (degree + 1) * (degree + 1);
}

/// The colour space the SH colours evaluate in (glTF KHR_gaussian_splatting `colorSpace`):
/// display sRGB (every 3DGS file format; the default) or linear Rec. 709, turned into sRGB
/// after evaluation.
enum class ColorSpace : std::uint8_t { srgb, linear };

/// The kernel the opacity profile follows (glTF KHR_gaussian_splatting `kernel`):
/// "ellipse" is the 3D Gaussian cut at 3 sigma (Kerbl et al. 2023), the only one defined.
enum class Kernel : std::uint8_t { ellipse };

/// A set of 3D Gaussians, structure of arrays, in the axes of the file they came from
/// (docs/splats.md, "Axes", says per format; the scene places them). Every array has
/// size() entries, but shRest, which has size() * shRestPerSplat() entries.
struct GaussianCloud {
  /// Centres, scene units (metres).
  std::vector<glm::vec3> positions;
  /// Standard deviations along the Gaussian's own axes, scene units, linear (a PLY's
  /// scale_i is log: exp() is applied on reading). >= 0; 0 makes a flat Gaussian.
  std::vector<glm::vec3> scales;
  /// Unit quaternions turning the Gaussian's axes into the cloud's (glm: w, x, y, z).
  std::vector<glm::quat> rotations;
  /// Peak opacity, 0..1 (a PLY's logit opacity has the sigmoid applied on reading).
  std::vector<float> opacities;
  /// Degree-0 SH coefficient per channel (a PLY's f_dc_0..2): colour = 0.5 + kShC0 * dc + ...
  std::vector<glm::vec3> shDc;
  /// Higher SH coefficients, splat-major: splat i's coefficient k (k = 1..15, the order
  /// of Kerbl et al.'s f_rest within a channel) is shRest[i * shRestPerSplat() + k - 1],
  /// an RGB triple. Empty when shDegree is 0.
  std::vector<glm::vec3> shRest;
  /// SH degree of every splat, 0..3.
  int shDegree = 0;
  ColorSpace colorSpace = ColorSpace::srgb;
  Kernel kernel = Kernel::ellipse;

  std::size_t size() const { return positions.size(); }
  bool empty() const { return positions.empty(); }
  /// Higher SH coefficients per splat: shCoefficients(shDegree) - 1 (0, 3, 8 or 15).
  int shRestPerSplat() const { return shCoefficients(shDegree) - 1; }
  /// Reserves room for n splats.
  void reserve(std::size_t n);
  /// Resizes every array to n splats (new ones: origin, unit scale, identity, opaque,
  /// grey), keeping shDegree.
  void resize(std::size_t n);
  /// Appends splat `i` of `other`, whose shDegree may differ (missing bands are zero,
  /// extra bands dropped).
  void append(const GaussianCloud& other, std::size_t i);
  /// Appends splats [first, last) of `other` as append() does, copying each array at once
  /// when the SH degrees agree. Requires first <= last <= other.size().
  void appendRange(const GaussianCloud& other, std::size_t first, std::size_t last);
  /// Lowers (or raises, with zeros) the SH degree of every splat.
  void setShDegree(int degree);
};

/// The importance of a Gaussian, the paper's magnitude for splats (Nagasawa section 2:
/// largest first): opacity times the area of its largest cross-section, pi s1 s2 with s1,
/// s2 the two largest scales (scene units squared).
float importance(const GaussianCloud& cloud, std::size_t i);

/// The cloud with its splats sorted by importance, largest first (stable: equal
/// importances keep their order), so that every prefix is the best picture of its size.
GaussianCloud sortByImportance(const GaussianCloud& cloud);

/// SH basis constants of Kerbl et al.'s reference implementation (real SH, the sign
/// convention of their forward.cu).
inline constexpr float kShC0 = 0.28209479177387814f;

/// The logistic function: PLY opacities are logits.
inline float sigmoid(float x) {
  return 1.0f / (1.0f + std::exp(-x));
}
/// Its inverse, clamped away from 0 and 1 so that the result is finite.
inline float logit(float p) {
  p = std::clamp(p, 1e-7f, 1.0f - 1e-7f);
  return std::log(p / (1.0f - p));
}

/// The covariance of a Gaussian: R S S^T R^T with S = diag(scale), R = the rotation's
/// matrix (Kerbl et al. 2023, eq. 6). Symmetric, column-major glm.
glm::mat3 covariance(const glm::vec3& scale, const glm::quat& rotation);

/// The colour of splat `i` of `cloud` seen along `direction` (unit, from the camera to
/// the splat, in the cloud's axes): 0.5 + SH(direction), clamped below at 0 (Kerbl et
/// al.'s computeColorFromSH), in sRGB (linear-space clouds converted). Not clamped above.
glm::vec3 shColor(const GaussianCloud& cloud, std::size_t i, const glm::vec3& direction);

/// The real SH basis of Kerbl et al.'s computeColorFromSH (their constants and signs, an
/// orthonormal basis) along `direction` (unit): writes shCoefficients(degree) values to
/// `out` (room for 16) and returns how many.
int shBasis(int degree, const glm::vec3& direction, float* out);

/// The SH sum of degree `degree` of `coefficients` (dc then the rest, RGB triples, at
/// least shCoefficients(degree) of them) along `direction` (unit), without the 0.5 offset.
glm::vec3 evaluateSh(int degree, const glm::vec3* coefficients, const glm::vec3& direction);

/// What the screen sees of one Gaussian (Kerbl et al. 2023, section 6 and their
/// rasterizer): the EWA projection Sigma' = J W Sigma W^T J^T (Zwicker et al. 2002) with
/// 0.3 pixel added to the diagonal (the low-pass filter) and a 3-sigma extent.
struct ProjectedGaussian {
  glm::vec2 center{0.0f};  // pixels, x right, y up, pixel (i, j) centred at (i + 0.5, j + 0.5)
  /// The inverse 2D covariance (conic) (a, b, c): the profile at pixel offset d is
  /// exp(-0.5 (a dx^2 + 2 b dx dy + c dy^2)).
  glm::vec3 conic{0.0f};
  glm::vec2 extent{0.0f};  // half-size of the 3-sigma box, pixels, per axis
  float depth = 0.0f;      // eye depth of the centre (positive in front), scene units
  /// sqrt(det(Sigma' without the low-pass) / det(Sigma')), 0..1: the share of the peak
  /// opacity that keeps a splat's integrated opacity through the 0.3-pixel low-pass
  /// (Yu et al. 2024, Mip-Splatting, eq. 13: the "antialiased" mode). 1 for a splat much
  /// wider than a pixel; used for QNV vectors (render/splat_model.hpp), not for captures.
  float lowPassKeep = 1.0f;
};

/// The viewing transform of a projection: eye = view * model position, perspective with
/// focal lengths fx, fy in pixels and the principal point cx, cy (pixels, y up).
struct ProjectionView {
  glm::mat4 modelView{1.0f};  // cloud to eye (OpenGL eye: looking down -Z)
  float fx = 1.0f, fy = 1.0f;
  float cx = 0.0f, cy = 0.0f;
  int width = 0, height = 0;  // viewport, pixels
  float nearClip = 0.2f;      // centres nearer than this are not drawn (eye depth)
  float farClip = 1e30f;
};

/// Projects a Gaussian of centre `position` and covariance `sigma` (cloud axes). False
/// when nothing of it can show: behind the near plane or past the far plane, a degenerate
/// 2D covariance, or its 3-sigma box outside the viewport. Follows Kerbl et al.'s
/// computeCov2D: the Jacobian at a centre clamped to 1.3 times the field of view.
bool projectGaussian(const glm::vec3& position, const glm::mat3& sigma, const ProjectionView& view,
                     ProjectedGaussian& out);

}  // namespace gs::splats
