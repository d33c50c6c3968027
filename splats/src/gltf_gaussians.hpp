// What the two glTF KHR_gaussian_splatting readers share (gltf_gaussians.cpp, whole;
// gltf_batches.cpp, a batch at a time): which accessors a primitive's attributes are, the
// default scene's splat primitives with their world transforms, and where a splat goes.
// Private to splats/.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include "gltf/document.hpp"
#include "splats/gaussian.hpp"

namespace gs::splats::detail {

inline constexpr const char* kGltfSplatExtension = "KHR_gaussian_splatting";

/// The accessors of one KHR_gaussian_splatting primitive (none read yet).
struct GltfSplatAttributes {
  int position = -1, rotation = -1, scale = -1, opacity = -1;
  int dc = -1;            // SH_DEGREE_0_COEF_0 (RGB), or -1
  int color = -1;         // COLOR_0 (VEC3 or VEC4), the colour when dc is -1
  std::vector<int> rest;  // SH_DEGREE_l_COEF_m (RGB), l = 1..degree, m = 0..2l
  int degree = 0;
  ColorSpace colorSpace = ColorSpace::srgb;
};

/// The attributes of `primitive` (whose extension object is `ext`), or FormatError naming
/// `name`: not POINTS, POSITION, ROTATION, SCALE or OPACITY missing, no colour (neither
/// SH_DEGREE_0_COEF_0 nor COLOR_0), an SH degree partly defined, an unknown colorSpace.
GltfSplatAttributes gltfSplatAttributes(const tinygltf::Primitive& primitive,
                                        const tinygltf::Value& ext, const std::string& name);

/// Calls `visit` for each KHR_gaussian_splatting primitive of each mesh instance of the
/// default scene (gltf::sceneRoots), depth first in node order, with its node's world
/// transform (glTF 2.0 clause 3.5.3). FormatError for a node that does not exist or is
/// reached twice.
void forEachGltfSplatPrimitive(
    const tinygltf::Model& model, const std::string& name,
    const std::function<void(const tinygltf::Primitive&, const tinygltf::Value&,
                             const glm::dmat4&)>& visit);

/// Where one primitive's splats go in the cloud: its node's world transform M, then
/// glTF's axes turned into the .ply's (180 degrees about Z). A similarity keeps scale and
/// rotation; any other M goes through the covariance (M C C^T M^T); SH are turned by M's
/// rotation.
class GltfPlacement {
 public:
  /// FormatError naming `name` when M is not decomposable (a zero, negative or infinite
  /// scale).
  GltfPlacement(const glm::dmat4& world, int degree, const std::string& name);
  /// Splat `j` of `part` (allocated at this degree or above) from one element of each
  /// attribute as floats: position xyz, rotation xyzw, scale xyz (linear), opacity, the
  /// DC coefficient RGB, and rest[k] the RGB of SH coefficient k + 1 (k < the degree's).
  void place(const float* position, const float* rotation, const float* scale, float opacity,
             const float* dc, const float* const* rest, GaussianCloud& part, std::size_t j) const;

 private:
  glm::dmat4 toCloud_{1.0};
  glm::dmat3 m_{1.0};
  double s0_ = 1.0;
  bool similar_ = true;
  glm::quat turn_{1.0f, 0.0f, 0.0f, 0.0f};
  int degree_ = 0;
  std::vector<std::vector<double>> d_;  // per band 1..degree: the SH rotation, row-major
};

/// The DC coefficient of a COLOR_0 value (red, green, blue in 0..1): (c - 0.5) / C0.
inline float dcOfColor(float c) {
  return (c - 0.5f) / kShC0;
}

}  // namespace gs::splats::detail
